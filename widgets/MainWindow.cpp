#include "MainWindow.h"

#include "AcquisitionPanel.h"
#include "CompensationPanel.h"
#include "BundleTransfer.h"
#include "CsvImportDialog.h"
#include "AnalysisPanel.h"
#include "DiagnosisPanel.h"
#include "DuplicateSessionError.h"
#include "ErrorSurface3D.h"
#include "ModelExportDialog.h"
#include "CentralStoreActions.h"
#include "ModelsPanel.h"
#include "PlotExporter.h"
#include "ReviewWorkspace.h"
#include "SessionBrowser.h"
#include "SessionStore.h"
#include "SessionTextCommand.h"
#include "StorageError.h"

#include <QApplication>
#include <QCloseEvent>
#include <QDesktopServices>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QUndoStack>
#include <QUrl>

namespace driftlab {

namespace {
constexpr int kMaxRecent = 8;
const char *kRecentKey = "recentDatabases";

bool isBundlePath(const QString &path)
{
    const QFileInfo info(path);
    return (info.isDir() && QFileInfo::exists(info.filePath() + QStringLiteral("/manifest.json"))) ||
           info.suffix().compare(QLatin1String("zip"), Qt::CaseInsensitive) == 0;
}

bool isDatabasePath(const QString &path)
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    return QFileInfo(path).isFile() && (suffix == QLatin1String("sqlite") || suffix == QLatin1String("db"));
}
} // namespace

MainWindow::MainWindow(QWidget *parent)
    : QMainWindow(parent),
      m_browser(new SessionBrowser(this)),
      m_split(new QSplitter(this)),
      m_workspace(new ReviewWorkspace(this)),
      m_comparison(new ReviewWorkspace(this)),
      m_acquisition(new AcquisitionPanel(this)),
      m_models(new ModelsPanel(this)),
      m_diagnosis(new DiagnosisPanel(this)),
      m_undo(new QUndoStack(this)),
      m_analysis(new AnalysisPanel(this)),
      m_compensation(new CompensationPanel(this))
{
    setObjectName(QStringLiteral("DriftLabMainWindow"));
    setWindowTitle(tr("DriftLab"));
    setAcceptDrops(true);
    m_split->addWidget(m_workspace);
    m_split->addWidget(m_comparison);
    m_split->setChildrenCollapsible(false);
    m_comparison->hide();
    setCentralWidget(m_split);
    // The sessions dock runs the full height; bottom docks share the width right of it.
    setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
    setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
    setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
    setDockOptions(dockOptions() | QMainWindow::AllowTabbedDocks);

    m_central = new CentralStoreActions(
        this, [this] { return m_store.get(); }, [this] { return m_sessionId; }, [this](const QString &a) { return openDatabase(a); });
    buildMenus();
    addPanelDock(tr("Sessions"), QStringLiteral("SessionsDock"), m_browser, Qt::LeftDockWidgetArea,
                 QKeySequence(Qt::CTRL + Qt::Key_1));
    QDockWidget *acquisition = addPanelDock(tr("Acquisition"), QStringLiteral("AcquisitionDock"), m_acquisition,
                                            Qt::RightDockWidgetArea, QKeySequence(Qt::CTRL + Qt::Key_2));
    acquisition->hide();
    QDockWidget *models = addPanelDock(tr("Models"), QStringLiteral("ModelsDock"), m_models, Qt::BottomDockWidgetArea,
                                       QKeySequence(Qt::CTRL + Qt::Key_3));
    models->hide();
    QDockWidget *diagnosis = addPanelDock(tr("Diagnosis"), QStringLiteral("DiagnosisDock"), m_diagnosis,
                                          Qt::BottomDockWidgetArea, QKeySequence(Qt::CTRL + Qt::Key_4));
    tabifyDockWidget(models, diagnosis);
    diagnosis->hide();
    QDockWidget *analysis = addPanelDock(tr("Analysis"), QStringLiteral("AnalysisDock"), m_analysis,
                                         Qt::BottomDockWidgetArea, QKeySequence(Qt::CTRL + Qt::Key_5));
    tabifyDockWidget(diagnosis, analysis); // sensitive points and data-driven models
    analysis->hide();
    QDockWidget *compensation = addPanelDock(tr("Compensation"), QStringLiteral("CompensationDock"), m_compensation,
                                             Qt::RightDockWidgetArea, QKeySequence(Qt::CTRL + Qt::Key_6));
    tabifyDockWidget(acquisition, compensation); // live offsets to a controller (docs/export.md)
    compensation->hide();
    // Further docks (rig setup, ...): addPanelDock(...) here.

    // A finished recording appears in the session list of the database it went to.
    connect(m_acquisition, &AcquisitionPanel::recordingStopped, this, [this](qint64 id) {
        const QString db = m_acquisition->databasePath();
        bool open = m_store && QFileInfo(m_store->path()).absoluteFilePath() == QFileInfo(db).absoluteFilePath();
        if (!open)
            open = openDatabase(db);
        if (!open)
            return;
        refreshSessions(id);
        QString message;
        if (CentralStoreActions::autoPush())
            statusBar()->showMessage(m_central->afterRecording(id, &message) ? message : tr("Automatic push: %1").arg(message));
    });
    connect(m_browser, &SessionBrowser::sessionSelected, this, &MainWindow::showSession);
    connect(m_browser, &SessionBrowser::channelsChanged, this, &MainWindow::showChannels);

    fitToScreen();
    QSettings settings;
    restoreGeometry(settings.value(QStringLiteral("geometry")).toByteArray());
    restoreState(settings.value(QStringLiteral("windowState")).toByteArray());
    // A layout saved on a larger screen must not push the window off this one.
    if (const QScreen *screen = QGuiApplication::primaryScreen()) {
        const QSize avail = screen->availableGeometry().size();
        if (width() > avail.width() || height() > avail.height())
            resize(std::min(width(), avail.width()), std::min(height(), avail.height()));
    }
    statusBar()->showMessage(tr("No database open: File > New or Open database, or drop a .sqlite or a recording bundle here"));
}

MainWindow::~MainWindow()
{
    m_undo->clear(); // commands refer to the store
}

void MainWindow::fitToScreen()
{
    QSize size(1280, 760);
    if (const QScreen *screen = QGuiApplication::primaryScreen()) {
        const QRect avail = screen->availableGeometry();
        size = QSize(std::min(avail.width(), std::max(1024, avail.width() * 9 / 10)),
                     std::min(avail.height(), std::max(700, avail.height() * 9 / 10)));
        move(avail.topLeft() + QPoint((avail.width() - size.width()) / 2, (avail.height() - size.height()) / 2));
    }
    resize(size);
}

QDockWidget *MainWindow::addPanelDock(const QString &title, const QString &objectName, QWidget *panel, Qt::DockWidgetArea area,
                                      const QKeySequence &shortcut)
{
    auto *dock = new QDockWidget(title, this);
    dock->setObjectName(objectName);
    // A panel larger than the room it gets scrolls instead of growing the window.
    auto *scroll = new QScrollArea(dock);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    scroll->setWidget(panel);
    dock->setWidget(scroll);
    addDockWidget(area, dock);
    QAction *toggle = dock->toggleViewAction();
    if (!shortcut.isEmpty())
        toggle->setShortcut(shortcut);
    m_viewMenu->insertAction(m_viewDocksEnd, toggle);
    return dock;
}

QDockWidget *MainWindow::dock(const QString &objectName) const
{
    return findChild<QDockWidget *>(objectName);
}

void MainWindow::buildMenus()
{
    QMenu *file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&New database..."), this, &MainWindow::chooseNewDatabase, QKeySequence::New);
    file->addAction(tr("&Open database..."), this, &MainWindow::chooseDatabase, QKeySequence::Open);
    m_recentMenu = file->addMenu(tr("Open &recent"));
    refreshRecentMenu();
    m_central->addTo(file);
    file->addSeparator();
    file->addAction(tr("&Import recording bundle..."), this, &MainWindow::chooseBundle, QKeySequence(Qt::CTRL + Qt::Key_I));
    file->addAction(tr("Import &CSV table..."), this, &MainWindow::importCsv)->setObjectName(QStringLiteral("ImportCsvAction"));
    file->addAction(tr("&Export session as bundle..."), this, &MainWindow::exportSession, QKeySequence(Qt::CTRL + Qt::Key_E));
    file->addAction(tr("Export &model to controller..."), this, [this] { ModelExportDialog(this).exec(); })
        ->setObjectName(QStringLiteral("ExportModelAction"));
    file->addAction(tr("Export current &view (PNG, SVG, PDF)..."), this, &MainWindow::exportView,
                    QKeySequence(Qt::CTRL + Qt::SHIFT + Qt::Key_E));
    m_reportAction = file->addAction(tr("Test &report (PDF, HTML)..."));
    m_reportAction->setObjectName(QStringLiteral("ReportAction"));
    m_reportAction->setShortcut(QKeySequence(Qt::CTRL + Qt::Key_R));
    file->addSeparator();
    file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);

    QMenu *edit = menuBar()->addMenu(tr("&Edit"));
    QAction *undo = m_undo->createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction *redo = m_undo->createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    QAction *rename = edit->addAction(tr("Re&name session..."), this, &MainWindow::askRename, QKeySequence(Qt::Key_F2));
    QAction *notes = edit->addAction(tr("Session &notes..."), this, &MainWindow::askNotes,
                                     QKeySequence(Qt::CTRL + Qt::SHIFT + Qt::Key_N));
    QAction *remove = edit->addAction(tr("&Delete session..."), this, &MainWindow::askDelete, QKeySequence::Delete);
    // The same actions on the session list's context menu.
    QListWidget *list = m_browser->sessionList();
    list->setContextMenuPolicy(Qt::ActionsContextMenu);
    list->addActions({rename, notes, remove});

    m_viewMenu = menuBar()->addMenu(tr("&View"));
    m_viewMenu->setObjectName(QStringLiteral("ViewMenu"));
    m_viewDocksEnd = m_viewMenu->addSeparator(); // dock toggles go above
    m_viewMenu->addAction(tr("&Compare with session..."), this, &MainWindow::chooseComparison);
    m_viewMenu->addAction(tr("Close c&omparison"), this, [this] { compareWith(0); });

    QMenu *help = menuBar()->addMenu(tr("&Help"));
    help->addAction(tr("&Documentation"), this, &MainWindow::showDocumentation, QKeySequence::HelpContents);
    help->addAction(tr("&About DriftLab"), this, &MainWindow::showAbout);
}

TimeSeriesPlot *MainWindow::plot() const
{
    return m_workspace->timeSeriesPlot();
}

void MainWindow::reportError(const QString &message)
{
    m_lastError = message;
    statusBar()->showMessage(message);
}

QStringList MainWindow::recentDatabases() const
{
    return QSettings().value(QLatin1String(kRecentKey)).toStringList();
}

void MainWindow::rememberDatabase(const QString &path)
{
    QSettings settings;
    QStringList recent = settings.value(QLatin1String(kRecentKey)).toStringList();
    const QString abs = SessionStore::isCentral(path) ? SessionStore::displayPath(path) : QFileInfo(path).absoluteFilePath();
    recent.removeAll(abs);
    recent.prepend(abs);
    while (recent.size() > kMaxRecent)
        recent.removeLast();
    settings.setValue(QLatin1String(kRecentKey), recent);
    settings.setValue(QStringLiteral("lastDatabase"), abs);
    refreshRecentMenu();
}

void MainWindow::refreshRecentMenu()
{
    m_recentMenu->clear();
    for (const QString &path : recentDatabases())
        m_recentMenu->addAction(path, this, [this, path] { openDatabase(path); });
    m_recentMenu->setEnabled(!m_recentMenu->isEmpty());
}

void MainWindow::closeEvent(QCloseEvent *event)
{
    QSettings settings;
    settings.setValue(QStringLiteral("geometry"), saveGeometry());
    settings.setValue(QStringLiteral("windowState"), saveState());
    QMainWindow::closeEvent(event);
}

void MainWindow::chooseDatabase()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("Open session database"), QString(),
                                                      tr("DriftLab databases (*.sqlite *.db);;All files (*)"));
    if (!path.isEmpty())
        openDatabase(path);
}

void MainWindow::chooseNewDatabase()
{
    QString path = QFileDialog::getSaveFileName(this, tr("New session database"), QStringLiteral("sessions.sqlite"),
                                                tr("DriftLab databases (*.sqlite)"), nullptr,
                                                QFileDialog::DontConfirmOverwrite);
    if (path.isEmpty())
        return;
    if (QFileInfo(path).suffix().isEmpty())
        path += QStringLiteral(".sqlite");
    newDatabase(path);
}

bool MainWindow::newDatabase(const QString &path)
{
    if (QFileInfo::exists(path)) {
        reportError(tr("%1 already exists: open it with File > Open database, or choose a new name").arg(path));
        return false;
    }
    if (!QDir().mkpath(QFileInfo(path).absolutePath())) {
        reportError(tr("Cannot create the folder %1").arg(QFileInfo(path).absolutePath()));
        return false;
    }
    return openDatabase(path);
}

bool MainWindow::openDatabase(const QString &path)
{
    if (m_models->running() || m_diagnosis->running() || m_analysis->running()) {
        reportError(tr("A model fit or diagnosis is running on the open database; cancel it first"));
        return false;
    }
    try {
        auto store = std::make_unique<SessionStore>(path);
        m_undo->clear();
        m_models->setStore(nullptr);
        m_diagnosis->setStore(nullptr);
        m_analysis->setStore(nullptr);
        m_workspace->clear();
        m_comparison->clear();
        m_comparison->hide();
        m_sessionId = 0;
        m_store = std::move(store);
        // A central store is for review: recordings keep going to the local database.
        const bool central = m_store->isCentralStore();
        if (!central)
            m_acquisition->setDatabasePath(QFileInfo(path).absoluteFilePath());
        setWindowTitle(tr("DriftLab - %1").arg(central ? m_store->path() : QFileInfo(path).fileName()));
        rememberDatabase(path);
        refreshSessions(0);
        statusBar()->showMessage(tr("%1: %n session(s)", nullptr, m_store->sessions().size()).arg(m_store->path()));
        return true;
    } catch (const StorageError &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

void MainWindow::refreshSessions(qint64 select)
{
    const QVector<SessionInfo> sessions = m_store->sessions();
    if (!m_models->running())
        m_models->setStore(m_store.get());
    if (!m_diagnosis->running())
        m_diagnosis->setStore(m_store.get());
    if (!m_analysis->running())
        m_analysis->setStore(m_store.get());
    m_browser->setSessions(sessions);
    if (sessions.isEmpty()) {
        m_workspace->clear();
        m_browser->setChannels({}, {});
        m_sessionId = 0;
        return;
    }
    qint64 id = sessions.back().id;
    for (const SessionInfo &s : sessions)
        if (s.id == select)
            id = select;
    m_browser->selectSession(id);
    showSession(id);
}

void MainWindow::showSession(qint64 sessionId)
{
    if (!m_store)
        return;
    try {
        m_workspace->setSession(m_store.get(), sessionId);
        m_sessionId = sessionId;
        m_compensation->setSession(m_store->path(), sessionId);
        m_browser->selectSession(sessionId);
        m_browser->setChannels(m_store->channels(sessionId), m_workspace->defaultChannels());
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::showChannels(const QVector<qint64> &channelIds)
{
    if (!m_store || m_sessionId == 0)
        return;
    try {
        m_workspace->showChannels(channelIds);
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::compareWith(qint64 sessionId)
{
    if (sessionId == 0 || !m_store) {
        m_comparison->clear();
        m_comparison->hide();
        return;
    }
    try {
        m_comparison->setSession(m_store.get(), sessionId);
        m_comparison->show();
        m_split->setSizes({m_split->width() / 2, m_split->width() / 2});
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::chooseComparison()
{
    if (!m_store)
        return;
    QStringList labels;
    QVector<qint64> ids;
    for (const SessionInfo &s : m_store->sessions()) {
        labels << QStringLiteral("#%1  %2").arg(s.id).arg(s.name);
        ids << s.id;
    }
    bool ok = false;
    const QString choice = QInputDialog::getItem(this, tr("Compare"), tr("Session to show beside the current one:"),
                                                 labels, 0, false, &ok);
    if (ok)
        compareWith(ids.value(labels.indexOf(choice)));
}

bool MainWindow::importBundle(const QString &path)
{
    return importBundle(path, false);
}

bool MainWindow::importBundle(const QString &path, bool allowDuplicate)
{
    if (!m_store) {
        reportError(tr("Open a database before importing %1 (File > New database or Open database)").arg(path));
        return false;
    }
    try {
        statusBar()->showMessage(tr("Importing %1...").arg(path));
        QApplication::setOverrideCursor(Qt::WaitCursor);
        const qint64 id = BundleTransfer::importBundle(*m_store, path, allowDuplicate);
        QApplication::restoreOverrideCursor();
        refreshSessions(id);
        statusBar()->showMessage(tr("Imported %1 as session %2").arg(path).arg(id));
        return true;
    } catch (const DuplicateSessionError &e) {
        QApplication::restoreOverrideCursor();
        const QMessageBox::StandardButton answer = QMessageBox::question(
            this, tr("Already in this database"),
            tr("%1.\n\nImport a second copy as a new session?").arg(QString::fromStdString(e.what())),
            QMessageBox::Yes | QMessageBox::No, QMessageBox::No);
        if (answer == QMessageBox::Yes)
            return importBundle(path, true);
        reportError(tr("%1 not imported: it is already session %2").arg(path).arg(e.existingSession()));
        m_browser->selectSession(e.existingSession());
        showSession(e.existingSession());
        return false;
    } catch (const std::exception &e) {
        QApplication::restoreOverrideCursor();
        // Nothing was imported: the store rolls the whole bundle back.
        reportError(QString::fromStdString(e.what()));
        if (isVisible())
            QMessageBox::warning(this, tr("Import failed"), m_lastError);
        return false;
    }
}

void MainWindow::chooseBundle()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("Import recording bundle"), QString(),
                                                      tr("Bundles (manifest.json *.zip);;All files (*)"));
    if (path.isEmpty())
        return;
    importBundle(QFileInfo(path).fileName() == QLatin1String("manifest.json") ? QFileInfo(path).absolutePath() : path);
}

bool MainWindow::renameSession(qint64 sessionId, const QString &name)
{
    if (!m_store)
        return false;
    try {
        const QString before = m_store->session(sessionId).name;
        if (name.trimmed() == before)
            return true;
        if (name.trimmed().isEmpty()) {
            reportError(tr("A session name must not be empty"));
            return false;
        }
        m_undo->push(new SessionTextCommand(*m_store, sessionId, SessionTextCommand::Field::Name, before, name.trimmed(),
                                            [this](qint64 id) { refreshSessions(id); }));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

bool MainWindow::setSessionNotes(qint64 sessionId, const QString &notes)
{
    if (!m_store)
        return false;
    try {
        const QString before = m_store->session(sessionId).notes;
        if (notes == before)
            return true;
        m_undo->push(new SessionTextCommand(*m_store, sessionId, SessionTextCommand::Field::Notes, before, notes,
                                            [this](qint64 id) { m_browser->setSessions(m_store->sessions());
                                                                m_browser->selectSession(id); }));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

bool MainWindow::deleteSession(qint64 sessionId)
{
    if (!m_store)
        return false;
    if (m_models->running() || m_diagnosis->running() || m_analysis->running()) {
        reportError(tr("A model fit or diagnosis is running; cancel it before deleting sessions"));
        return false;
    }
    if (m_acquisition->recording() && m_acquisition->sessionId() == sessionId &&
        QFileInfo(m_acquisition->databasePath()).absoluteFilePath() == QFileInfo(m_store->path()).absoluteFilePath()) {
        reportError(tr("Session %1 is being recorded; stop the recording first").arg(sessionId));
        return false;
    }
    try {
        const QString name = m_store->session(sessionId).name;
        m_store->deleteSession(sessionId);
        m_undo->clear(); // earlier edits may refer to the deleted session
        if (m_comparison->session() == sessionId)
            compareWith(0);
        if (m_sessionId == sessionId) {
            m_workspace->clear();
            m_sessionId = 0;
        }
        refreshSessions(m_sessionId);
        statusBar()->showMessage(tr("Deleted session %1 '%2'").arg(sessionId).arg(name));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

void MainWindow::askRename()
{
    if (!m_store || m_sessionId == 0)
        return;
    bool ok = false;
    const QString name = QInputDialog::getText(this, tr("Rename session"), tr("Name of session %1:").arg(m_sessionId),
                                               QLineEdit::Normal, m_store->session(m_sessionId).name, &ok);
    if (ok)
        renameSession(m_sessionId, name);
}

void MainWindow::askNotes()
{
    if (!m_store || m_sessionId == 0)
        return;
    bool ok = false;
    const QString notes = QInputDialog::getMultiLineText(this, tr("Session notes"), tr("Notes of session %1:").arg(m_sessionId),
                                                         m_store->session(m_sessionId).notes, &ok);
    if (ok)
        setSessionNotes(m_sessionId, notes);
}

void MainWindow::askDelete()
{
    if (!m_store || m_sessionId == 0)
        return;
    const qint64 id = m_sessionId;
    const QString name = m_store->session(id).name;
    const auto answer = QMessageBox::warning(
        this, tr("Delete session"),
        tr("Delete session %1 '%2' with everything recorded, fitted and analysed with it?\n\n"
           "This cannot be undone (export it as a bundle first to keep a copy).")
            .arg(id)
            .arg(name),
        QMessageBox::Yes | QMessageBox::Cancel, QMessageBox::Cancel);
    if (answer == QMessageBox::Yes)
        deleteSession(id);
}

void MainWindow::importCsv()
{
    if (!m_store) {
        reportError(tr("Open a database first (File > Open database): the table is imported into it"));
        return;
    }
    const QString path = QFileDialog::getOpenFileName(this, tr("Import CSV table"), QString(),
                                                      tr("Tables (*.csv *.txt *.tsv *.dat);;All files (*)"));
    if (path.isEmpty())
        return;
    auto *dialog = new CsvImportDialog(m_store->path(), this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    connect(dialog, &CsvImportDialog::imported, this, [this](qint64 id) { refreshSessions(id); });
    dialog->openFile(path);
    dialog->open();
}

void MainWindow::exportSession()
{
    if (!m_store || m_sessionId == 0)
        return;
    const QString out = QFileDialog::getSaveFileName(this, tr("Export session"), QStringLiteral("session.zip"),
                                                     tr("Zipped bundle (*.zip);;Bundle folder (*.bundle)"));
    if (out.isEmpty())
        return;
    try {
        BundleTransfer::exportBundle(*m_store, m_sessionId, out);
        statusBar()->showMessage(tr("Exported session %1 to %2").arg(m_sessionId).arg(out));
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::exportView()
{
    const QString name = m_workspace->currentViewName();
    QwtPlot *plot = m_workspace->plotForView(name);
    if (!plot)
        return;
    const QString out = QFileDialog::getSaveFileName(this, tr("Export view"), name + QStringLiteral(".png"),
                                                     tr("PNG (*.png);;SVG (*.svg);;PDF (*.pdf)"));
    if (out.isEmpty())
        return;
    try {
        PlotExporter::exportPlot(*plot, out);
        statusBar()->showMessage(tr("Wrote %1").arg(out));
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::showAbout()
{
    QMessageBox::about(this, tr("About DriftLab"),
                       tr("<b>DriftLab %1</b><p>Machine-tool thermal-error testing: records thermal tests, explains the "
                          "errors they show and fits models that compensate them.</p><p>Sessions are SQLite databases; "
                          "recordings travel as recording bundles (docs/recording-bundle.md). The command line "
                          "<tt>driftlab-cli</tt> runs the same analysis headless.</p>")
                           .arg(QApplication::applicationVersion()));
}

void MainWindow::showDocumentation()
{
    if (!m_docs.isEmpty() && QFileInfo(m_docs).isDir() && QDesktopServices::openUrl(QUrl::fromLocalFile(m_docs)))
        return;
    QMessageBox::information(this, tr("Documentation"),
                             tr("The documentation is the docs/ folder of the DriftLab sources%1: README.md, "
                                "docs/recording-bundle.md (the file format), docs/acquisition.md, docs/review.md, "
                                "docs/models.md, docs/diagnosis.md.")
                                 .arg(m_docs.isEmpty() ? QString() : QStringLiteral(" (%1)").arg(m_docs)));
}

QImage MainWindow::snapshot()
{
    QImage image = grab().toImage();
    QPainter painter(&image);
    for (ErrorSurface3D *surface : findChildren<ErrorSurface3D *>()) {
        if (!surface->isVisible())
            continue;
        const QImage gl = surface->renderImage();
        if (!gl.isNull())
            painter.drawImage(QRect(surface->mapTo(this, QPoint(0, 0)), surface->size()), gl);
    }
    return image;
}

void MainWindow::dragEnterEvent(QDragEnterEvent *event)
{
    for (const QUrl &url : event->mimeData()->urls()) {
        if (url.isLocalFile() && (isBundlePath(url.toLocalFile()) || isDatabasePath(url.toLocalFile()))) {
            event->acceptProposedAction();
            return;
        }
    }
}

void MainWindow::dropEvent(QDropEvent *event)
{
    for (const QUrl &url : event->mimeData()->urls()) {
        if (!url.isLocalFile())
            continue;
        if (isDatabasePath(url.toLocalFile()))
            openDatabase(url.toLocalFile());
        else if (isBundlePath(url.toLocalFile()))
            importBundle(url.toLocalFile());
    }
    event->acceptProposedAction();
}

} // namespace driftlab

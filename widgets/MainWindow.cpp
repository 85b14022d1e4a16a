#include "MainWindow.h"

#include "AcquisitionPanel.h"
#include "LiveRecordingView.h"
#include "AnalysisPanel.h"
#include "CentralStoreActions.h"
#include "CompensationPanel.h"
#include "DiagnosisPanel.h"
#include "ErrorSurface3D.h"
#include "HelpBrowser.h"
#include "Iso230View.h"
#include "ModelExportDialog.h"
#include "ModelsPanel.h"
#include "PlotExporter.h"
#include "ReviewWorkspace.h"
#include "ImporterRegistry.h"
#include "SessionActions.h"
#include "SessionBrowser.h"
#include "SessionStore.h"
#include "UnitLabels.h"
#include "WheelGuard.h"
#include "WelcomePage.h"
#include "Workbench.h"

#include <QApplication>
#include <QCloseEvent>
#include <QDesktopServices>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QLabel>
#include <QTableView>
#include <QListWidget>
#include <QDialogButtonBox>
#include <QVBoxLayout>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QSplitter>
#include <QStackedWidget>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QDirIterator>
#include <QTabWidget>
#include <QUrl>

namespace driftlab {

namespace {
bool isDatabasePath(const QString &path)
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    return QFileInfo(path).isFile() && (suffix == QLatin1String("sqlite") || suffix == QLatin1String("db"));
}
} // namespace

MainWindow::MainWindow(QWidget *parent)
    : QMainWindow(parent),
      m_workbench(new Workbench(this)),
      m_actions(new SessionActions(m_workbench, this)),
      m_views(new QTabWidget(this)),
      m_sessionPage(new QStackedWidget(this)),
      m_welcome(new WelcomePage(this)),
      m_browser(new SessionBrowser(this)),
      m_split(new QSplitter(this)),
      m_workspace(new ReviewWorkspace(this)),
      m_comparison(new ReviewWorkspace(this)),
      m_iso230(new Iso230View(this)),
      m_acquisition(new AcquisitionPanel(m_workbench, this)),
      m_models(new ModelsPanel(m_workbench, this)),
      m_diagnosis(new DiagnosisPanel(m_workbench, this)),
      m_analysis(new AnalysisPanel(m_workbench, this)),
      m_compensation(new CompensationPanel(this))
{
    setObjectName(QStringLiteral("DriftLabMainWindow"));
    setWindowTitle(tr("DriftLab"));
    setAcceptDrops(true);
    WheelGuard::installOnApplication();
    m_split->addWidget(m_workspace);
    m_split->addWidget(m_comparison);
    m_split->setChildrenCollapsible(false);
    m_comparison->hide();
    // The central area: the session under review, and the results of the Models, Diagnosis
    // and Analysis docks at full size (the docks keep their controls and tables).
    m_views->setObjectName(QStringLiteral("CentralViews"));
    m_views->setDocumentMode(true);
    // A database without sessions shows the ways to begin instead of empty plots.
    m_sessionPage->addWidget(m_welcome);
    m_sessionPage->addWidget(m_split);
    m_views->addTab(m_sessionPage, tr("Session"));
    m_views->addTab(m_acquisition->liveView(), tr("Recording")); // the running recording at full size
    m_views->addTab(m_iso230, tr("ISO 230")); // the interferometer runs of the current session
    m_views->addTab(m_models->resultsView(), tr("Model fit"));
    m_diagnosis->plotsView()->setOrientation(Qt::Horizontal);
    m_views->addTab(m_diagnosis->resultsView(), tr("Diagnosis"));
    m_views->addTab(m_analysis->resultsView(), tr("Analysis"));
    setCentralWidget(m_views);
    connect(m_models, &ModelsPanel::fitFinished, this, [this](bool ok) {
        if (ok)
            m_views->setCurrentWidget(m_models->resultsView());
    });
    connect(m_diagnosis, &DiagnosisPanel::finished, this, [this](bool ok) {
        if (ok)
            m_views->setCurrentWidget(m_diagnosis->resultsView());
    });
    for (auto signal : {&AnalysisPanel::selectionFinished, &AnalysisPanel::fitsFinished})
        connect(m_analysis, signal, this, [this](bool ok) {
            if (ok)
                m_views->setCurrentWidget(m_analysis->resultsView());
        });
    // The sessions dock (and its tabs) runs the full height; bottom docks share the width right of it.
    setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
    setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
    setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
    setDockOptions(dockOptions() | QMainWindow::AllowTabbedDocks);

    m_central = new CentralStoreActions(
        this, [this] { return m_workbench->store(); }, [this] { return m_workbench->currentSession(); },
        [this](const QString &a) { return m_workbench->openDatabase(a); });
    buildMenus();
    QDockWidget *sessions = addPanelDock(tr("Sessions"), QStringLiteral("SessionsDock"), m_browser, Qt::LeftDockWidgetArea,
                                         QKeySequence(Qt::CTRL + Qt::Key_1));
    // Acquisition and Compensation are tabs of the sessions dock: side by side with the
    // sessions they left the central views too little room at 1366 px and both scrolled
    // sideways (tst_layout1366).
    QDockWidget *acquisition = addPanelDock(tr("Acquisition"), QStringLiteral("AcquisitionDock"), m_acquisition,
                                            Qt::LeftDockWidgetArea, QKeySequence(Qt::CTRL + Qt::Key_2));
    tabifyDockWidget(sessions, acquisition);
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
                                             Qt::LeftDockWidgetArea, QKeySequence(Qt::CTRL + Qt::Key_6));
    tabifyDockWidget(acquisition, compensation); // live offsets to a controller (docs/export.md)
    compensation->hide();
    // Further docks (rig setup, ...): addPanelDock(...) here.

    m_summary = new QLabel(this);
    m_summary->setObjectName(QStringLiteral("StoreSummary"));
    statusBar()->addPermanentWidget(m_summary);
    connect(m_workbench, &Workbench::storeChanged, this, &MainWindow::onStoreChanged);
    connect(m_workbench, &Workbench::sessionsChanged, this, &MainWindow::onSessionsChanged);
    connect(m_workbench, &Workbench::sessionChanged, this, &MainWindow::onSessionChanged);
    connect(m_workbench, &Workbench::message, this, &MainWindow::say);
    connect(m_workbench, &Workbench::failed, this, &MainWindow::say);
    connect(m_acquisition, &AcquisitionPanel::recordingStopped, this, &MainWindow::onRecordingStopped);
    connect(m_acquisition, &AcquisitionPanel::recordingStarted, this, &MainWindow::markRecording);
    // A recording opens at full size in the central area; the dock keeps a compact status.
    connect(m_acquisition, &AcquisitionPanel::recordingStarted, this,
            [this] { m_views->setCurrentWidget(m_acquisition->liveView()); });
    connect(m_acquisition, &AcquisitionPanel::liveViewRequested, this,
            [this] { m_views->setCurrentWidget(m_acquisition->liveView()); });
    connect(m_welcome, &WelcomePage::recordSimulated, this, &MainWindow::recordSimulatedSession);
    connect(m_welcome, &WelcomePage::openExample, this, &MainWindow::openExampleBundle);
    connect(m_welcome, &WelcomePage::importCsv, this, [this] {
        if (ensureDatabase())
            m_actions->importCsv();
    });
    connect(m_browser, &SessionBrowser::sessionSelected, m_workbench, &Workbench::setCurrentSession);
    connect(m_browser, &SessionBrowser::channelsChanged, this, &MainWindow::showChannels);

    fitToScreen();
    m_defaultLayout = saveState();
    QSettings settings;
    restoreGeometry(settings.value(QStringLiteral("geometry")).toByteArray());
    restoreState(settings.value(QStringLiteral("windowState")).toByteArray());
    // A layout saved on a larger screen must not push the window off this one.
    if (const QScreen *screen = QGuiApplication::primaryScreen()) {
        const QSize avail = screen->availableGeometry().size();
        if (width() > avail.width() || height() > avail.height())
            resize(std::min(width(), avail.width()), std::min(height(), avail.height()));
    }
    onSessionsChanged();
    say(tr("No database open: File > New or Open database, or drop a .sqlite or a recording bundle here"));
}

MainWindow::~MainWindow()
{
    // A recording still running stops here, while the window is whole: the panel's own
    // destructor would tell a half-destroyed window (and its session list) that it stopped.
    m_acquisition->disconnect();
    m_acquisition->stopRecording();
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

void MainWindow::resetLayout()
{
    restoreState(m_defaultLayout);
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
    // Never narrower than the panel's content: docks scroll vertically, not sideways.
    // (Side docks at most 540 px; the side panels are tabs of one dock area, so one of them
    // and the central views fit 1366 px.)
    scroll->setMinimumWidth(std::min(540, std::max(panel->minimumSizeHint().width(), panel->minimumWidth()) +
                                                  scroll->verticalScrollBar()->sizeHint().width()));
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
    m_actions->addDatabaseActions(file, [this](QMenu *menu) { m_central->addTo(menu); });
    file->addSeparator();
    m_actions->addImportExportActions(file);
    file->addAction(tr("Export &model to controller..."), this, [this] {
        ModelExportDialog dialog(this);
        dialog.setStore(m_workbench->store(), m_workbench->currentSession()); // the models fitted with these sessions
        dialog.exec();
    })
        ->setObjectName(QStringLiteral("ExportModelAction"));
    file->addAction(tr("Export current &view (PNG, SVG, PDF)..."), this, &MainWindow::exportView,
                    QKeySequence(Qt::CTRL + Qt::SHIFT + Qt::Key_E));
    m_reportAction = file->addAction(tr("Test &report (PDF, HTML)..."));
    m_reportAction->setObjectName(QStringLiteral("ReportAction"));
    m_reportAction->setShortcut(QKeySequence(Qt::CTRL + Qt::Key_R));
    file->addSeparator();
    file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);

    QMenu *edit = menuBar()->addMenu(tr("&Edit"));
    // The session edits also on the session list's context menu.
    QTableView *list = m_browser->sessionTable();
    list->setContextMenuPolicy(Qt::ActionsContextMenu);
    list->addActions(m_actions->addEditActions(edit));

    m_viewMenu = menuBar()->addMenu(tr("&View"));
    m_viewMenu->setObjectName(QStringLiteral("ViewMenu"));
    m_viewDocksEnd = m_viewMenu->addSeparator(); // dock toggles go above
    m_viewMenu->addAction(tr("&Compare with session..."), this, &MainWindow::chooseComparison);
    m_viewMenu->addAction(tr("Close c&omparison"), this, [this] { compareWith(0); });
    m_viewMenu->addAction(tr("O&verlay sessions (time and position plots)..."), this, &MainWindow::chooseOverlay)
        ->setObjectName(QStringLiteral("OverlayAction"));
    m_viewMenu->addSeparator();
    m_viewMenu->addAction(tr("&Reset layout"), this, &MainWindow::resetLayout)->setObjectName(QStringLiteral("ResetLayoutAction"));

    QMenu *help = menuBar()->addMenu(tr("&Help"));
    help->addAction(tr("&Documentation"), this, &MainWindow::showDocumentation, QKeySequence::HelpContents);
    help->addAction(tr("&About DriftLab"), this, &MainWindow::showAbout);
}

TimeSeriesPlot *MainWindow::plot() const
{
    return m_workspace->timeSeriesPlot();
}

void MainWindow::say(const QString &message)
{
    statusBar()->showMessage(message);
}

QString MainWindow::storeSummary() const
{
    return m_summary->text();
}

void MainWindow::closeEvent(QCloseEvent *event)
{
    QSettings settings;
    settings.setValue(QStringLiteral("geometry"), saveGeometry());
    settings.setValue(QStringLiteral("windowState"), saveState());
    QMainWindow::closeEvent(event);
}

void MainWindow::onStoreChanged()
{
    m_workspace->clear();
    m_comparison->clear();
    m_comparison->hide();
    m_iso230->clear();
    if (const SessionStore *store = m_workbench->store())
        setWindowTitle(tr("DriftLab - %1").arg(store->isCentralStore() ? store->path() : QFileInfo(store->path()).fileName()));
}

void MainWindow::onSessionsChanged()
{
    const SessionStore *store = m_workbench->store();
    m_browser->setSessions(m_workbench->sessions(), store);
    markRecording();
    m_welcome->setDatabase(store ? store->path() : QString());
    m_sessionPage->setCurrentWidget(m_workbench->sessions().isEmpty() ? static_cast<QWidget *>(m_welcome) : m_split);
    m_summary->setText(store ? tr("%1: %n session(s)", nullptr, m_workbench->sessions().size()).arg(store->path())
                             : tr("no database open"));
}

void MainWindow::onSessionChanged(qint64 sessionId)
{
    if (m_views->currentWidget() != m_iso230) // the ISO 230 view follows the session in place
        m_views->setCurrentWidget(m_sessionPage);
    const SessionStore *store = m_workbench->store();
    if (!store || sessionId == 0) {
        m_workspace->clear();
        m_browser->setChannels({}, {});
        m_iso230->clear();
        return;
    }
    try {
        m_workspace->setSession(store, sessionId);
        m_iso230->setSession(store, sessionId);
        m_compensation->setSession(store->path(), sessionId);
        m_browser->selectSession(sessionId);
        m_browser->setChannels(store->channels(sessionId), m_workspace->defaultChannels());
    } catch (const std::exception &e) {
        m_workbench->reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::markRecording()
{
    // The sessions table says which session is being recorded, when it is in the open database.
    const bool here = m_acquisition->recording() && m_workbench->store() &&
                      QFileInfo(m_acquisition->databasePath()).absoluteFilePath() == m_workbench->localPath();
    m_browser->setRecordingSession(here ? m_acquisition->sessionId() : 0);
}

void MainWindow::onRecordingStopped(qint64 sessionId)
{
    m_browser->setRecordingSession(0);
    // A finished recording appears in the session list of the database it went to.
    const QString db = QFileInfo(m_acquisition->databasePath()).absoluteFilePath();
    if (m_workbench->localPath() != db && !m_workbench->openDatabase(db))
        return;
    m_workbench->refreshSessions(sessionId);
    QString message;
    if (CentralStoreActions::autoPush())
        say(m_central->afterRecording(sessionId, &message) ? message : tr("Automatic push: %1").arg(message));
}

bool MainWindow::ensureDatabase()
{
    if (m_workbench->store())
        return true;
    QString path = m_acquisition->targetDatabase();
    if (path.isEmpty())
        path = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/driftlab.sqlite");
    return QFileInfo::exists(path) ? m_workbench->openDatabase(path) : m_workbench->newDatabase(path);
}

bool MainWindow::recordSimulatedSession()
{
    if (!ensureDatabase())
        return false;
    if (m_workbench->localPath().isEmpty()) {
        m_workbench->reportError(tr("A central store is open: open a local database to record into"));
        return false;
    }
    if (QDockWidget *d = dock(QStringLiteral("AcquisitionDock"))) {
        d->show();
        d->raise();
    }
    m_acquisition->setRunDetails(QString(), QString(), 600.0, tr("first simulated session"));
    if (!m_acquisition->startRecording(QStringLiteral("baseline"), m_workbench->localPath(), 60.0)) {
        m_workbench->reportError(m_acquisition->lastError());
        return false;
    }
    return true;
}

bool MainWindow::openExampleBundle()
{
    if (!ensureDatabase())
        return false;
    // The example ships as a Qt resource: copied to a temporary folder, imported from there.
    const QString root = QStringLiteral(":/bundles/bundles/example.bundle");
    if (!QFileInfo(root).isDir()) {
        m_workbench->reportError(tr("This build has no example bundle"));
        return false;
    }
    QTemporaryDir tmp;
    const QString dir = tmp.filePath(QStringLiteral("example.bundle"));
    QDirIterator it(root, QDir::Files, QDirIterator::Subdirectories);
    while (it.hasNext()) {
        const QString from = it.next();
        const QString to = dir + from.mid(root.size());
        QDir().mkpath(QFileInfo(to).absolutePath());
        if (!QFile::copy(from, to)) {
            m_workbench->reportError(tr("Cannot copy the example bundle to %1").arg(to));
            return false;
        }
    }
    return m_actions->importBundle(dir);
}

void MainWindow::showChannels(const QVector<qint64> &channelIds)
{
    if (!m_workbench->store() || m_workbench->currentSession() == 0)
        return;
    try {
        m_workspace->showChannels(channelIds);
    } catch (const std::exception &e) {
        m_workbench->reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::compareWith(qint64 sessionId)
{
    if (sessionId == 0 || !m_workbench->store()) {
        m_comparison->clear();
        m_comparison->hide();
        return;
    }
    try {
        m_comparison->setSession(m_workbench->store(), sessionId);
        m_comparison->show();
        m_split->setSizes({m_split->width() / 2, m_split->width() / 2});
    } catch (const std::exception &e) {
        m_workbench->reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::chooseComparison()
{
    if (!m_workbench->store())
        return;
    QStringList labels;
    QVector<qint64> ids;
    for (const SessionInfo &s : m_workbench->sessions()) {
        labels << QStringLiteral("#%1  %2").arg(s.id).arg(s.name);
        ids << s.id;
    }
    bool ok = false;
    const QString choice = QInputDialog::getItem(this, tr("Compare"), tr("Session to show beside the current one:"),
                                                 labels, 0, false, &ok);
    if (ok)
        compareWith(ids.value(labels.indexOf(choice)));
}

void MainWindow::overlaySessions(const QVector<qint64> &sessionIds)
{
    if (!m_workbench->store() || m_workbench->currentSession() == 0)
        return;
    try {
        m_workspace->setOverlay(sessionIds);
        m_views->setCurrentWidget(m_sessionPage);
    } catch (const std::exception &e) {
        m_workbench->reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::chooseOverlay()
{
    if (!m_workbench->store() || m_workbench->currentSession() == 0)
        return;
    QDialog dialog(this);
    dialog.setWindowTitle(tr("Overlay sessions"));
    auto *list = new QListWidget(&dialog);
    for (const SessionInfo &s : m_workbench->sessions()) {
        if (s.id == m_workbench->currentSession())
            continue;
        auto *item = new QListWidgetItem(QStringLiteral("#%1  %2  (%3)").arg(s.id).arg(s.name, UnitLabels::startTime(s.started)), list);
        item->setData(Qt::UserRole, s.id);
        item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
        item->setCheckState(m_workspace->overlay().contains(s.id) ? Qt::Checked : Qt::Unchecked);
    }
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dialog);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    auto *layout = new QVBoxLayout(&dialog);
    auto *what = new QLabel(tr("Sessions to draw with the current one: the same channels on the time plot, the last "
                               "interferometer run on the error-vs-position plot:"), &dialog);
    what->setWordWrap(true);
    layout->addWidget(what);
    layout->addWidget(list);
    layout->addWidget(buttons);
    if (dialog.exec() != QDialog::Accepted)
        return;
    QVector<qint64> ids;
    for (int i = 0; i < list->count(); ++i)
        if (list->item(i)->checkState() == Qt::Checked)
            ids << list->item(i)->data(Qt::UserRole).toLongLong();
    overlaySessions(ids);
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
        m_workbench->reportError(QString::fromStdString(e.what()));
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
    // The documentation shipped in the application (Qt resources, :/docs).
    auto *help = findChild<HelpBrowser *>();
    if (!help) {
        help = new HelpBrowser(m_docs, this);
        help->setObjectName(QStringLiteral("HelpBrowser"));
    }
    help->show();
    help->raise();
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
            painter.drawImage(QRect(surface->mapTo(this, surface->graphRect().topLeft()), surface->graphRect().size()), gl);
    }
    return image;
}

void MainWindow::dragEnterEvent(QDragEnterEvent *event)
{
    for (const QUrl &url : event->mimeData()->urls()) {
        if (url.isLocalFile() && (isDatabasePath(url.toLocalFile()) || ImporterRegistry().find(url.toLocalFile()))) {
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
        // A database is opened; any other file goes to its importer (core/ImporterRegistry, the
        // one `driftlab-cli import` uses).
        if (isDatabasePath(url.toLocalFile()))
            m_workbench->openDatabase(url.toLocalFile());
        else if (ImporterRegistry().find(url.toLocalFile()))
            m_actions->importFile(url.toLocalFile());
    }
    event->acceptProposedAction();
}

} // namespace driftlab

#include "MainWindow.h"

#include "AcquisitionPanel.h"
#include "BundleTransfer.h"
#include "AnalysisPanel.h"
#include "DiagnosisPanel.h"
#include "ModelsPanel.h"
#include "PlotExporter.h"
#include "ReviewWorkspace.h"
#include "SessionBrowser.h"
#include "SessionStore.h"
#include "StorageError.h"

#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>

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
      m_analysis(new AnalysisPanel(this))
{
    setObjectName(QStringLiteral("DriftLabMainWindow"));
    setWindowTitle(tr("DriftLab"));
    setAcceptDrops(true);
    m_split->addWidget(m_workspace);
    m_split->addWidget(m_comparison);
    m_comparison->hide();
    setCentralWidget(m_split);

    auto *dock = new QDockWidget(tr("Sessions"), this);
    dock->setObjectName(QStringLiteral("SessionsDock"));
    dock->setWidget(m_browser);
    addDockWidget(Qt::LeftDockWidgetArea, dock);
    auto *acquisition = new QDockWidget(tr("Acquisition"), this);
    acquisition->setObjectName(QStringLiteral("AcquisitionDock"));
    acquisition->setWidget(m_acquisition);
    addDockWidget(Qt::RightDockWidgetArea, acquisition);
    acquisition->hide();
    auto *models = new QDockWidget(tr("Models"), this);
    models->setObjectName(QStringLiteral("ModelsDock"));
    models->setWidget(m_models);
    addDockWidget(Qt::BottomDockWidgetArea, models);
    models->hide();
    auto *diagnosis = new QDockWidget(tr("Diagnosis"), this);
    diagnosis->setObjectName(QStringLiteral("DiagnosisDock"));
    diagnosis->setWidget(m_diagnosis);
    addDockWidget(Qt::BottomDockWidgetArea, diagnosis);
    tabifyDockWidget(models, diagnosis);
    diagnosis->hide();
    auto *analysis = new QDockWidget(tr("Analysis"), this); // sensitive points and data-driven models
    analysis->setObjectName(QStringLiteral("AnalysisDock"));
    analysis->setWidget(m_analysis);
    addDockWidget(Qt::BottomDockWidgetArea, analysis);
    tabifyDockWidget(diagnosis, analysis);
    analysis->hide();
    buildMenus();
    QMenu *viewMenu = menuBar()->findChild<QMenu *>(QStringLiteral("ViewMenu"));
    viewMenu->addAction(dock->toggleViewAction());
    viewMenu->addAction(acquisition->toggleViewAction());
    viewMenu->addAction(models->toggleViewAction());
    viewMenu->addAction(diagnosis->toggleViewAction());
    viewMenu->addAction(analysis->toggleViewAction());
    // A finished recording appears in the session list (opening its database if needed).
    connect(m_acquisition, &AcquisitionPanel::recordingStopped, this, [this](qint64 id) {
        const QString db = m_acquisition->databasePath();
        if (m_store && QFileInfo(m_store->path()).absoluteFilePath() == QFileInfo(db).absoluteFilePath())
            refreshSessions(id);
        else if (openDatabase(db))
            refreshSessions(id);
    });

    connect(m_browser, &SessionBrowser::sessionSelected, this, &MainWindow::showSession);
    connect(m_browser, &SessionBrowser::channelsChanged, this, &MainWindow::showChannels);
    resize(1280, 760);
    QSettings settings;
    restoreGeometry(settings.value(QStringLiteral("geometry")).toByteArray());
    restoreState(settings.value(QStringLiteral("windowState")).toByteArray());
    statusBar()->showMessage(tr("No database open: File > Open database, or drop a recording bundle here"));
}

MainWindow::~MainWindow() = default;

void MainWindow::buildMenus()
{
    QMenu *file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&Open database..."), this, &MainWindow::chooseDatabase, QKeySequence::Open);
    m_recentMenu = file->addMenu(tr("Open &recent"));
    refreshRecentMenu();
    file->addSeparator();
    file->addAction(tr("&Import recording bundle..."), this, &MainWindow::chooseBundle);
    file->addAction(tr("&Export session as bundle..."), this, &MainWindow::exportSession);
    file->addAction(tr("Export current &view (PNG, SVG, PDF)..."), this, &MainWindow::exportView);
    file->addSeparator();
    file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);
    QMenu *view = menuBar()->addMenu(tr("&View"));
    view->setObjectName(QStringLiteral("ViewMenu"));
    view->addAction(tr("&Compare with session..."), this, &MainWindow::chooseComparison);
    view->addAction(tr("Close c&omparison"), this, [this] { compareWith(0); });
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
    const QString abs = QFileInfo(path).absoluteFilePath();
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

bool MainWindow::openDatabase(const QString &path)
{
    try {
        auto store = std::make_unique<SessionStore>(path);
        if (m_models->running() || m_diagnosis->running() || m_analysis->running()) {
            reportError(tr("A model fit or diagnosis is running on the open database; cancel it first"));
            return false;
        }
        m_models->setStore(nullptr);
        m_diagnosis->setStore(nullptr);
        m_analysis->setStore(nullptr);
        m_workspace->clear();
        m_comparison->clear();
        m_comparison->hide();
        m_store = std::move(store);
        setWindowTitle(tr("DriftLab - %1").arg(QFileInfo(path).fileName()));
        rememberDatabase(path);
        refreshSessions(0);
        statusBar()->showMessage(tr("%1: %n session(s)", nullptr, m_store->sessions().size()).arg(path));
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
    if (sessions.isEmpty())
        return;
    const qint64 id = select ? select : sessions.back().id;
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
    if (!m_store) {
        reportError(tr("Open a database before importing %1").arg(path));
        return false;
    }
    try {
        statusBar()->showMessage(tr("Importing %1...").arg(path));
        const qint64 id = BundleTransfer::importBundle(*m_store, path);
        refreshSessions(id);
        statusBar()->showMessage(tr("Imported %1 as session %2").arg(path).arg(id));
        return true;
    } catch (const std::exception &e) {
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

void MainWindow::dragEnterEvent(QDragEnterEvent *event)
{
    for (const QUrl &url : event->mimeData()->urls()) {
        if (url.isLocalFile() && isBundlePath(url.toLocalFile())) {
            event->acceptProposedAction();
            return;
        }
    }
}

void MainWindow::dropEvent(QDropEvent *event)
{
    for (const QUrl &url : event->mimeData()->urls()) {
        if (url.isLocalFile() && isBundlePath(url.toLocalFile()))
            importBundle(url.toLocalFile());
    }
    event->acceptProposedAction();
}

} // namespace driftlab

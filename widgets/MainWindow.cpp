#include "MainWindow.h"

#include "SessionBrowser.h"
#include "SessionStore.h"
#include "StorageError.h"
#include "TimeSeriesPlot.h"

#include <QAction>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenuBar>
#include <QSplitter>
#include <QStatusBar>

namespace driftlab {

namespace {
// Channels longer than this are drawn from decimated min/max levels.
constexpr qint64 kRawCurveLimit = 20000;
} // namespace

MainWindow::MainWindow(QWidget *parent)
    : QMainWindow(parent), m_browser(new SessionBrowser(this)), m_plot(new TimeSeriesPlot(this))
{
    setWindowTitle(tr("DriftLab"));
    auto *splitter = new QSplitter(this);
    splitter->addWidget(m_browser);
    splitter->addWidget(m_plot);
    splitter->setStretchFactor(1, 1);
    splitter->setSizes({300, 980});
    setCentralWidget(splitter);

    QMenu *file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&Open database..."), this, &MainWindow::chooseDatabase, QKeySequence::Open);
    file->addSeparator();
    file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);

    connect(m_browser, &SessionBrowser::sessionSelected, this, &MainWindow::showSession);
    connect(m_browser, &SessionBrowser::channelsChanged, this, &MainWindow::showChannels);
    resize(1280, 760);
    statusBar()->showMessage(tr("No database open"));
}

MainWindow::~MainWindow() = default;

void MainWindow::reportError(const QString &message)
{
    m_lastError = message;
    statusBar()->showMessage(message);
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
        const QVector<SessionInfo> sessions = store->sessions();
        m_store = std::move(store);
        m_browser->setSessions(sessions);
        setWindowTitle(tr("DriftLab - %1").arg(QFileInfo(path).fileName()));
        statusBar()->showMessage(tr("%1: %n session(s)", nullptr, sessions.size()).arg(path));
        if (!sessions.isEmpty()) {
            m_browser->selectSession(sessions.back().id);
            showSession(sessions.back().id);
        }
        return true;
    } catch (const StorageError &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

void MainWindow::showSession(qint64 sessionId)
{
    if (!m_store)
        return;
    try {
        const SessionInfo info = m_store->session(sessionId);
        const QVector<ChannelInfo> channels = m_store->channels(sessionId);
        m_sessionId = sessionId;
        // By default: temperatures and displacements, not the CNC's fast position/feed.
        QVector<qint64> shown;
        for (const ChannelInfo &c : channels) {
            if (c.kind == QLatin1String("temperature") || c.kind == QLatin1String("displacement"))
                shown.push_back(c.id);
        }
        m_browser->setChannels(channels, shown);
        m_plot->setTitle(info.name);
        showChannels(shown);
    } catch (const StorageError &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

void MainWindow::showChannels(const QVector<qint64> &channelIds)
{
    if (!m_store || m_sessionId == 0)
        return;
    try {
        m_plot->clearCurves();
        QString leftUnits, rightUnits;
        for (const ChannelInfo &c : m_store->channels(m_sessionId)) {
            if (!channelIds.contains(c.id))
                continue;
            const bool right = c.kind != QLatin1String("temperature");
            if (m_store->sampleCount(c.id) > kRawCurveLimit) {
                // Long channels: min/max per pixel column from the store's decimation levels.
                const SessionStore *store = m_store.get();
                const qint64 id = c.id;
                const DecimatedSeries whole = store->decimated(id, -1e300, 1e300, 1);
                const double tFirst = whole.tFirst.isEmpty() ? 0.0 : whole.tFirst.front();
                const double tLast = whole.tLast.isEmpty() ? 0.0 : whole.tLast.back();
                m_plot->addDecimatedCurve(
                    c.key, [store, id](double t0, double t1, int n) { return store->decimated(id, t0, t1, n); }, tFirst,
                    tLast, right);
            } else {
                const SampleBlock block = m_store->samples(c.id);
                m_plot->addCurve(c.key, block.t, block.v, right);
            }
            QString &units = right ? rightUnits : leftUnits;
            if (!units.contains(c.unit))
                units += (units.isEmpty() ? QString() : QStringLiteral(", ")) + c.unit;
        }
        m_plot->setAxisTitles(leftUnits.isEmpty() ? QString() : tr("temperature (%1)").arg(leftUnits),
                              rightUnits.isEmpty() ? QString() : rightUnits);
        m_plot->zoomToData();
    } catch (const StorageError &e) {
        reportError(QString::fromStdString(e.what()));
    }
}

} // namespace driftlab

// driftlab: the DriftLab desktop application.
// Exit codes as driftlab-cli's: 0 done, 1 failed, 2 bad usage or bad input (an unknown
// option, a session id the database does not hold, a held-out session that is also trained on).

#include "AnalysisPanel.h"
#include "DiagnosisPanel.h"
#include "AcquisitionPanel.h"
#include "HeapPolicy.h"
#include "LiveRecordingView.h"
#include "MainWindow.h"
#include "ModelsPanel.h"
#include "ReportDialog.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"
#include "Workbench.h"

#include <QAction>
#include <QApplication>
#include <QTabWidget>
#include <QCommandLineParser>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QImage>
#include <QScreen>
#include <QStatusBar>
#include <QStandardPaths>
#include <QTextStream>
#include <QTimer>

#include <cmath>
#include <functional>

using namespace driftlab;

namespace {

QTextStream &err()
{
    static QTextStream stream(stderr);
    return stream;
}

int usageError(const QString &message)
{
    err() << "driftlab: " << message << " (see 'driftlab --help')\n";
    err().flush();
    return 2;
}

// A session id the open database holds, else 0.
qint64 sessionArg(const MainWindow &window, const QString &text)
{
    bool ok = false;
    const qint64 id = text.trimmed().toLongLong(&ok);
    if (!ok || !window.workbench()->store())
        return 0;
    for (const SessionInfo &s : window.workbench()->sessions())
        if (s.id == id)
            return id;
    return 0;
}

// Shows the dock of a use case started from the command line, in front, with 55 % of the
// window's height (its plots need it).
void showTall(MainWindow &window, const QString &dockName)
{
    if (QDockWidget *d = window.dock(dockName)) {
        d->show();
        d->raise();
        QTimer::singleShot(0, &window, [&window, d] { window.resizeDocks({d}, {window.height() * 11 / 20}, Qt::Vertical); });
    }
}

} // namespace

int main(int argc, char **argv)
{
    HeapPolicy::keepLargeBlocksInHeap(); // a plot's first paint reuses pages instead of faulting new ones
    // Without a display Qt aborts; run offscreen instead, and refuse anything but a screenshot.
    const bool headless = qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY") &&
                          qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM");
    if (headless)
        qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("DriftLab"));
    QApplication::setApplicationVersion(QStringLiteral(DRIFTLAB_VERSION));

    QCommandLineParser p;
    p.setApplicationDescription(QStringLiteral("DriftLab: record, review and model machine-tool thermal errors."));
    const QCommandLineOption help = p.addHelpOption();
    const QCommandLineOption version = p.addVersionOption();
    // The options by name (QCommandLineParser finds them by name), then name, help and value of each.
    const QString db = QStringLiteral("db"), session = QStringLiteral("show-session"), screenshot = QStringLiteral("screenshot"),
                  view = QStringLiteral("view"), compare = QStringLiteral("compare"), fit = QStringLiteral("fit"),
                  diagnose = QStringLiteral("diagnose"), dock = QStringLiteral("dock"), analysis = QStringLiteral("analysis"),
                  central = QStringLiteral("central-view"), overlay = QStringLiteral("overlay"), record = QStringLiteral("record"),
                  liveLimit = QStringLiteral("live-limit");
    p.addOptions({
        {db, QStringLiteral("Session database to open (default: driftlab.sqlite in the user's data directory)."), QStringLiteral("file")},
        {session, QStringLiteral("Session id to show (QApplication reserves --session for X11 session management)."), QStringLiteral("id")},
        {screenshot,
         QStringLiteral("Render the main window (at the screen's size, the 3-D view included) to a PNG and exit; works headless "
                        "with QT_QPA_PLATFORM=offscreen."),
         QStringLiteral("png")},
        {view, QStringLiteral("Review view to show: error-3d, %1.").arg(ReviewWorkspace::viewNames().join(QStringLiteral(", "))),
         QStringLiteral("name")},
        {compare, QStringLiteral("Show this session id beside the first."), QStringLiteral("id")},
        {fit, QStringLiteral("Open the Models dock and fit the seed-000 model to these sessions: IDS[:HELDOUT], e.g. 1,2,3:4."),
         QStringLiteral("ids")},
        {diagnose, QStringLiteral("Open the Diagnosis dock and diagnose: TRAIN:VALIDATE session ids."), QStringLiteral("ids")},
        {dock, QStringLiteral("Show a dock: sessions, acquisition, models, diagnosis, analysis or compensation (repeatable)."),
         QStringLiteral("name")},
        {analysis,
         QStringLiteral("Open the Analysis dock: select sensitive points of TARGET in session ID, then fit the data-driven models "
                        "on hours 0..TRAIN_H and validate on the rest: ID:TARGET[:TRAIN_H[:select]] ('select': stop after the "
                        "selection)."),
         QStringLiteral("spec")},
        {central, QStringLiteral("Central tab to show: session, iso230, model-fit, diagnosis, analysis."), QStringLiteral("name")},
        {overlay, QStringLiteral("Overlay these sessions (comma-separated ids) on the time plot of --show-session."), QStringLiteral("ids")},
        {record,
         QStringLiteral("Start recording this rig (a preset name or rig file) into --db at 600x simulation speed; with "
                        "--screenshot, the picture is taken 3 s later."),
         QStringLiteral("rig")},
        {liveLimit, QStringLiteral("With --record: a high limit on a channel of the live view (KEY:HIGH)."), QStringLiteral("key:high")},
    });
    if (!p.parse(QApplication::arguments()))
        return usageError(p.errorText());
    if (p.isSet(help))
        p.showHelp(0);
    if (p.isSet(version))
        p.showVersion();
    if (!p.positionalArguments().isEmpty())
        return usageError(QStringLiteral("unexpected argument '%1'").arg(p.positionalArguments().first()));
    if (p.isSet(view) && !ReviewWorkspace::viewNames().contains(p.value(view)) && p.value(view) != QLatin1String("error-3d"))
        return usageError(QStringLiteral("--view must be error-3d or one of %1").arg(ReviewWorkspace::viewNames().join(QStringLiteral(", "))));

    if (headless && !p.isSet(screenshot)) {
        err() << "driftlab: no display (DISPLAY is not set): run it in a desktop session, or give --screenshot PNG\n";
        return 1;
    }

    QString path = p.value(db);
    if (path.isEmpty())
        path = QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).filePath(QStringLiteral("driftlab.sqlite"));

    MainWindow window;
    QObject::connect(window.reportAction(), &QAction::triggered, &window, [&window] {
        Workbench *bench = window.workbench();
        if (!bench->store() || bench->currentSession() <= 0) {
            window.statusBar()->showMessage(QObject::tr("Test report: choose a session first"), 5000);
            return;
        }
        ReportDialog dialog(bench->store(), bench->currentSession(), &window);
        dialog.exec();
    });
    if (QFileInfo::exists(path) || SessionStore::isCentral(path)) {
        if (!window.workbench()->openDatabase(path))
            return usageError(window.workbench()->lastError());
    } else if (p.isSet(db)) {
        return usageError(QStringLiteral("database %1 does not exist").arg(path));
    }
    const bool needStore = p.isSet(session) || p.isSet(compare) || p.isSet(fit) || p.isSet(diagnose) || p.isSet(analysis);
    if (needStore && !window.workbench()->store())
        return usageError(QStringLiteral("no database open (%1 does not exist): give --db FILE").arg(path));
    if (p.isSet(session)) {
        const qint64 id = sessionArg(window, p.value(session));
        if (!id)
            return usageError(QStringLiteral("--show-session: %1 has no session '%2'").arg(path, p.value(session)));
        window.workbench()->setCurrentSession(id);
    }
    if (p.isSet(compare)) {
        const qint64 id = sessionArg(window, p.value(compare));
        if (!id)
            return usageError(QStringLiteral("--compare: %1 has no session '%2'").arg(path, p.value(compare)));
        window.compareWith(id);
    }
    for (const QString &name : p.values(dock)) {
        const QString object = name.left(1).toUpper() + name.mid(1).toLower() + QStringLiteral("Dock");
        QDockWidget *d = window.dock(object);
        if (!d)
            return usageError(QStringLiteral("--dock: unknown dock '%1' (sessions, acquisition, models, diagnosis, analysis, compensation)").arg(name));
        d->show();
        QTimer::singleShot(0, d, &QDockWidget::raise); // a tab of the sessions dock comes to the front once shown
    }
    if (p.isSet(overlay)) {
        QVector<qint64> ids;
        for (const QString &part : p.value(overlay).split(QLatin1Char(','))) {
            const qint64 id = sessionArg(window, part.trimmed());
            if (!id)
                return usageError(QStringLiteral("--overlay: %1 has no session '%2'").arg(path, part));
            ids << id;
        }
        window.overlaySessions(ids);
    }
    if (p.isSet(central)) {
        QTabWidget *tabs = window.centralViews();
        int found = -1;
        for (int i = 0; i < tabs->count(); ++i)
            if (QString(tabs->tabText(i)).remove(QLatin1Char(' ')).compare(QString(p.value(central)).remove(QLatin1Char('-')),
                                                                          Qt::CaseInsensitive) == 0)
                found = i;
        if (found < 0)
            return usageError(QStringLiteral("--central-view: no tab '%1' (session, iso230, model-fit, diagnosis, analysis)")
                                  .arg(p.value(central)));
        tabs->setCurrentIndex(found);
    }
    if (p.isSet(view) && !window.workspace()->selectView(p.value(view)))
        err() << "driftlab: this session has no data for the view " << p.value(view) << '\n';
    if (p.isSet(screenshot)) {
        // The picture shows the window as it would fill this screen (a fresh layout, not the
        // one saved last time, so that screenshots are comparable).
        if (const QScreen *screen = QGuiApplication::primaryScreen())
            window.setGeometry(screen->availableGeometry());
    }
    window.show();

    std::function<void()> takeScreenshot = [&window, png = p.value(screenshot)] {
        QTimer::singleShot(400, &window, [&window, png] {
            const bool ok = window.snapshot().save(png, "PNG");
            err() << "driftlab: screenshot " << (ok ? "written to " : "FAILED: ") << QFileInfo(png).absoluteFilePath() << '\n';
            err().flush();
            QApplication::exit(ok ? 0 : 1);
        });
    };
    bool waiting = false; // a started use case takes the screenshot when it finishes
    const auto screenshotWhen = [&](auto *panel, auto finished) {
        if (p.isSet(screenshot) && !waiting) {
            waiting = true;
            QObject::connect(panel, finished, &window, takeScreenshot);
        }
    };
    if (p.isSet(fit)) {
        const QStringList parts = p.value(fit).split(QLatin1Char(':'));
        QVector<qint64> training;
        for (const QString &text : parts.first().split(QLatin1Char(','), Qt::SkipEmptyParts)) {
            const qint64 id = sessionArg(window, text);
            if (!id)
                return usageError(QStringLiteral("--fit: %1 has no session '%2'").arg(path, text));
            training.push_back(id);
        }
        qint64 heldOut = 0;
        if (parts.size() > 2 || (parts.size() == 2 && !(heldOut = sessionArg(window, parts.at(1)))))
            return usageError(QStringLiteral("--fit: expected IDS[:HELDOUT] with session ids of %1, got '%2'").arg(path, p.value(fit)));
        showTall(window, QStringLiteral("ModelsDock"));
        if (!window.models()->startFit(training, heldOut))
            return usageError(QStringLiteral("cannot fit: %1").arg(window.models()->lastError()));
        screenshotWhen(window.models(), &ModelsPanel::fitFinished);
    }
    if (p.isSet(diagnose)) {
        const QStringList ids = p.value(diagnose).split(QLatin1Char(':'));
        const qint64 train = ids.size() == 2 ? sessionArg(window, ids.at(0)) : 0;
        const qint64 validate = ids.size() == 2 ? sessionArg(window, ids.at(1)) : 0;
        if (!train || !validate)
            return usageError(QStringLiteral("--diagnose: expected TRAIN:VALIDATE session ids of %1, got '%2'").arg(path, p.value(diagnose)));
        showTall(window, QStringLiteral("DiagnosisDock"));
        if (!window.diagnosis()->start(train, validate))
            return usageError(QStringLiteral("cannot diagnose: %1").arg(window.diagnosis()->lastError()));
        screenshotWhen(window.diagnosis(), &DiagnosisPanel::finished);
    }
    if (p.isSet(analysis)) {
        const QStringList a = p.value(analysis).split(QLatin1Char(':'));
        const qint64 id = sessionArg(window, a.value(0));
        bool hoursOk = true;
        const double trainHours = a.size() > 2 ? a.at(2).toDouble(&hoursOk) : std::nan("");
        if (!id || a.size() < 2 || a.size() > 4 || a.at(1).isEmpty() || !hoursOk ||
            (a.size() == 4 && a.at(3) != QLatin1String("select")))
            return usageError(QStringLiteral("--analysis: expected ID:TARGET[:TRAIN_H[:select]] with a session id of %1, got '%2'")
                                  .arg(path, p.value(analysis)));
        showTall(window, QStringLiteral("AnalysisDock"));
        if (!window.analysis()->startWorkflow(id, a.at(1), trainHours, a.size() == 4))
            return usageError(QStringLiteral("cannot analyse: %1").arg(window.analysis()->lastError()));
        screenshotWhen(window.analysis(), &AnalysisPanel::workflowFinished);
    }
    if (p.isSet(record)) {
        if (window.workbench()->localPath().isEmpty())
            return usageError(QStringLiteral("--record needs --db with a local database"));
        if (p.isSet(liveLimit)) {
            const QStringList kv = p.value(liveLimit).split(QLatin1Char(':'));
            bool ok = false;
            const double high = kv.value(1).toDouble(&ok);
            if (kv.size() != 2 || kv.at(0).isEmpty() || !ok)
                return usageError(QStringLiteral("--live-limit: expected KEY:HIGH, got '%1'").arg(p.value(liveLimit)));
            // Applied once the recording's channels are known (the first refresh).
            QObject::connect(window.acquisition(), &AcquisitionPanel::recordingStarted, &window, [&window, key = kv.at(0), high] {
                LiveLimitMonitor::Limit l;
                l.high = high;
                QTimer::singleShot(300, &window, [&window, key, l] { window.acquisition()->liveView()->setLimit(key, l); });
            });
        }
        window.acquisition()->setRunDetails(QString(), QStringLiteral("screenshot"), 3600.0, QString());
        if (!window.acquisition()->startRecording(p.value(record), window.workbench()->localPath(), 600.0))
            return usageError(QStringLiteral("--record: %1").arg(window.acquisition()->lastError()));
        if (p.isSet(screenshot) && !waiting) {
            waiting = true;
            QTimer::singleShot(3000, &window, takeScreenshot);
        }
    }
    if (p.isSet(screenshot) && !waiting)
        takeScreenshot();
    return app.exec();
}

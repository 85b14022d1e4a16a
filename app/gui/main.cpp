// driftlab: the DriftLab desktop application.

#include "AnalysisPanel.h"
#include "DiagnosisPanel.h"
#include "MainWindow.h"
#include "ModelsPanel.h"

#include <QDockWidget>
#include "ReviewWorkspace.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QDir>
#include <QFileInfo>
#include <QPixmap>
#include <QStandardPaths>
#include <QTextStream>
#include <QTimer>

#include <cmath>

using namespace driftlab;

int main(int argc, char **argv)
{
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("DriftLab"));
    QApplication::setApplicationVersion(QStringLiteral(DRIFTLAB_VERSION));

    QCommandLineParser p;
    p.setApplicationDescription(QStringLiteral("DriftLab: record, review and model machine-tool thermal errors."));
    p.addHelpOption();
    p.addVersionOption();
    const QCommandLineOption db(QStringLiteral("db"),
                                QStringLiteral("Session database to open (default: driftlab.sqlite in the user's data directory)."),
                                QStringLiteral("file"));
    const QCommandLineOption session(QStringLiteral("show-session"),
                                   QStringLiteral("Session id to show (QApplication reserves --session for X11 session management)."),
                                   QStringLiteral("id"));
    const QCommandLineOption screenshot(QStringLiteral("screenshot"),
                                        QStringLiteral("Render the main window to a PNG and exit (works headless with "
                                                       "QT_QPA_PLATFORM=offscreen)."),
                                        QStringLiteral("png"));
    const QCommandLineOption view(QStringLiteral("view"),
                                  QStringLiteral("Review view to show: error-3d, %1.").arg(ReviewWorkspace::viewNames().join(QStringLiteral(", "))),
                                  QStringLiteral("name"));
    const QCommandLineOption compare(QStringLiteral("compare"), QStringLiteral("Show this session id beside the first."),
                                     QStringLiteral("id"));
    const QCommandLineOption fit(QStringLiteral("fit"),
                                 QStringLiteral("Open the Models dock and fit the seed-000 model to these sessions: "
                                                "IDS[:HELDOUT], e.g. 1,2,3:4."),
                                 QStringLiteral("ids"));
    const QCommandLineOption diagnose(QStringLiteral("diagnose"),
                                      QStringLiteral("Open the Diagnosis dock and diagnose: TRAIN:VALIDATE session ids."),
                                      QStringLiteral("ids"));
    const QCommandLineOption analysis(QStringLiteral("analysis"),
                                      QStringLiteral("Open the Analysis dock: select sensitive points of TARGET in session ID, "
                                                     "then fit the data-driven models on hours 0..TRAIN_H and validate on the "
                                                     "rest: ID:TARGET[:TRAIN_H[:select]] ('select': stop after the selection)."),
                                      QStringLiteral("spec"));
    p.addOptions({db, session, screenshot, view, compare, fit, diagnose, analysis});
    p.process(app);

    QTextStream err(stderr);
    QString path = p.value(db);
    if (path.isEmpty())
        path = QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).filePath(QStringLiteral("driftlab.sqlite"));

    MainWindow window;
    if (QFileInfo::exists(path)) {
        if (!window.openDatabase(path)) {
            err << "driftlab: " << window.lastError() << '\n';
            if (p.isSet(screenshot))
                return 2;
        }
    } else if (p.isSet(db)) {
        err << "driftlab: database " << path << " does not exist\n";
        return 2;
    }
    if (p.isSet(session)) {
        bool ok = false;
        const qint64 id = p.value(session).toLongLong(&ok);
        if (!ok) {
            err << "driftlab: --show-session must be a session id, got '" << p.value(session) << "'\n";
            return 2;
        }
        window.showSession(id);
    }
    if (p.isSet(compare))
        window.compareWith(p.value(compare).toLongLong());
    if (p.isSet(view)) {
        if (!ReviewWorkspace::viewNames().contains(p.value(view)) && p.value(view) != QLatin1String("error-3d")) {
            err << "driftlab: --view must be error-3d or one of " << ReviewWorkspace::viewNames().join(QStringLiteral(", "))
                << '\n';
            return 2;
        }
        if (!window.workspace()->selectView(p.value(view)))
            err << "driftlab: this session has no data for the view " << p.value(view) << '\n';
    }
    window.show();
    bool fitting = false;
    if (p.isSet(fit)) {
        const QStringList parts = p.value(fit).split(QLatin1Char(':'));
        QVector<qint64> training;
        for (const QString &id : parts.first().split(QLatin1Char(','), Qt::SkipEmptyParts))
            training.push_back(id.toLongLong());
        const qint64 heldOut = parts.size() > 1 ? parts.at(1).toLongLong() : 0;
        if (QDockWidget *dock = window.findChild<QDockWidget *>(QStringLiteral("ModelsDock")))
            dock->show();
        window.resize(1500, 1150);
        fitting = window.models()->startFit(training, heldOut);
        if (!fitting)
            err << "driftlab: cannot fit: " << window.models()->lastError() << '\n';
    }

    bool diagnosing = false;
    if (p.isSet(diagnose)) {
        const QStringList ids = p.value(diagnose).split(QLatin1Char(':'));
        if (QDockWidget *dock = window.findChild<QDockWidget *>(QStringLiteral("DiagnosisDock")))
            dock->show();
        window.resize(1500, 1150);
        diagnosing = ids.size() == 2 && window.diagnosis()->start(ids.at(0).toLongLong(), ids.at(1).toLongLong());
        if (!diagnosing)
            err << "driftlab: cannot diagnose: " << window.diagnosis()->lastError() << '\n';
    }
    bool analysing = false;
    if (p.isSet(analysis)) {
        const QStringList a = p.value(analysis).split(QLatin1Char(':'));
        if (QDockWidget *dock = window.findChild<QDockWidget *>(QStringLiteral("AnalysisDock")))
            dock->show();
        window.resize(1700, 1200);
        analysing = a.size() >= 2 && window.analysis()->startWorkflow(a.at(0).toLongLong(), a.at(1),
                                                                        a.size() > 2 ? a.at(2).toDouble() : std::nan(""),
                                                                        a.size() > 3 && a.at(3) == QLatin1String("select"));
        if (!analysing)
            err << "driftlab: cannot analyse: " << window.analysis()->lastError() << '\n';
    }
    if (p.isSet(screenshot) && analysing) {
        QObject::connect(window.analysis(), &AnalysisPanel::workflowFinished, &window, [&window, &err, png = p.value(screenshot)] {
            QTimer::singleShot(300, &window, [&window, &err, png] {
                const bool ok = window.grab().save(png, "PNG");
                err << "driftlab: screenshot " << (ok ? "written to " : "FAILED: ") << png << '\n';
                QApplication::exit(ok ? 0 : 1);
            });
        });
    } else if (p.isSet(screenshot) && diagnosing) {
        QObject::connect(window.diagnosis(), &DiagnosisPanel::finished, &window, [&window, &err, png = p.value(screenshot)] {
            QTimer::singleShot(300, &window, [&window, &err, png] {
                const bool ok = window.grab().save(png, "PNG");
                err << "driftlab: screenshot " << (ok ? "written to " : "FAILED: ") << png << '\n';
                QApplication::exit(ok ? 0 : 1);
            });
        });
    } else if (p.isSet(screenshot) && fitting) {
        // Wait for the fit, then take the picture.
        QObject::connect(window.models(), &ModelsPanel::fitFinished, &window, [&window, &err, png = p.value(screenshot)] {
            QTimer::singleShot(300, &window, [&window, &err, png] {
                const bool ok = window.grab().save(png, "PNG");
                err << "driftlab: screenshot " << (ok ? "written to " : "FAILED: ") << png << '\n';
                QApplication::exit(ok ? 0 : 1);
            });
        });
    } else if (p.isSet(screenshot)) {
        const QString png = p.value(screenshot);
        QTimer::singleShot(200, &window, [&window, png, &err] {
            const QPixmap pixmap = window.grab();
            if (!pixmap.save(png, "PNG")) {
                err << "driftlab: cannot write screenshot " << png << '\n';
                QApplication::exit(1);
                return;
            }
            err << "driftlab: screenshot written to " << QFileInfo(png).absoluteFilePath() << '\n';
            QApplication::exit(0);
        });
    }
    return app.exec();
}

// The Analysis workspace selects sensitive points and fits data-driven models in the
// background (progress, cancel), shows the same numbers the CLI computes and saves MODEL.json.
// Issue 32 (GUI side): several training and held-out sessions give the same stored fit as
// `driftlab-cli fit` (run as a process); "Auto" chooses what `fit --model auto` chooses and
// shows its table; the extrapolation warning is on the page, in the CLI's words; the stored
// fit names the GUI as its software.

#include "AnalysisPanel.h"
#include "../support/CliRunner.h"
#include "../support/GrabForDocs.h"
#include "DataDrivenFitRecord.h"
#include "ExtrapolationWarning.h"
#include "DataDrivenModelJson.h"
#include "ElapsedTimeBox.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include <QJsonDocument>
#include <QLabel>
#include <QSignalSpy>
#include <QTabWidget>
#include <QComboBox>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestAnalysisPanel : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void selectsAndFitsInBackground();
    void cancelStopsTheFits();
    void refusesIncompleteInput();
    void refusalsInTheDocksWords();
    void severalSessionsAsTheCli();
    void autoChoosesAsTheCli();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
    QString m_runsDb;
    std::unique_ptr<SessionStore> m_runs;
};

namespace {

// Every number of `b` equal to `a`'s within a relative 1e-9 (the same code in two processes);
// strings, booleans and the layout exactly. Keys in `skip` are left out at any depth.
void sameJson(const QJsonValue &a, const QJsonValue &b, const QString &where, const QStringList &skip, QStringList &diff)
{
    if (a.isDouble() && b.isDouble()) {
        const double x = a.toDouble(), y = b.toDouble();
        if (!(std::fabs(x - y) <= 1e-9 * std::max(1.0, std::fabs(x))))
            diff << QStringLiteral("%1: %2 != %3").arg(where).arg(x, 0, 'g', 17).arg(y, 0, 'g', 17);
    } else if (a.isObject() && b.isObject()) {
        const QJsonObject o = a.toObject(), p = b.toObject();
        QStringList keys = o.keys() + p.keys();
        keys.removeDuplicates();
        for (const QString &k : keys)
            if (!skip.contains(k))
                sameJson(o.value(k), p.value(k), where + QLatin1Char('.') + k, skip, diff);
    } else if (a.isArray() && b.isArray()) {
        const QJsonArray o = a.toArray(), p = b.toArray();
        if (o.size() != p.size())
            diff << QStringLiteral("%1: %2 items != %3").arg(where).arg(o.size()).arg(p.size());
        for (int i = 0; i < std::min(o.size(), p.size()); ++i)
            sameJson(o[i], p[i], QStringLiteral("%1[%2]").arg(where).arg(i), skip, diff);
    } else if (a != b) {
        diff << QStringLiteral("%1: %2 != %3").arg(where, QString::fromUtf8(QJsonDocument(QJsonArray{a}).toJson(QJsonDocument::Compact)),
                                                   QString::fromUtf8(QJsonDocument(QJsonArray{b}).toJson(QJsonDocument::Compact)));
    }
}

clirunner::Result cli(const QStringList &args)
{
    return clirunner::runProgram(QStringLiteral(DRIFTLAB_CLI), args, QString(), 300000);
}

FittedModel latestFit(const SessionStore &store, qint64 session)
{
    const QVector<FittedModel> fits = store.fittedModels(session);
    return fits.isEmpty() ? FittedModel() : fits.back();
}

} // namespace

void TestAnalysisPanel::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("analysis.sqlite")));
    RigConfig config;
    config.program = FeedProgram::seed000Table2(6000.0, config.travelLow_mm, config.travelHigh_mm);
    SimulatedRig rig(config);
    RigRecorder(*m_store, rig).record(QStringLiteral("baseline"), 2 * 3600.0);

    // Four runs of 90 min, each starting cold: three for training at 20, 21 and 22 C and
    // 6000 to 8000 mm/min, one held out at 26 C and 9000 mm/min (its absolute ambient
    // temperature lies 4 K above anything the training saw).
    m_runsDb = m_dir.filePath(QStringLiteral("runs.sqlite"));
    m_runs = std::make_unique<SessionStore>(m_runsDb);
    const double ambient[] = {20.0, 21.0, 22.0, 26.0};
    const double feed[] = {6000.0, 7000.0, 8000.0, 9000.0};
    for (int i = 0; i < 4; ++i) {
        RigConfig c;
        c.thermal.ambientMean_C = ambient[i];
        c.program = FeedProgram::seed000Table2(feed[i], c.travelLow_mm, c.travelHigh_mm);
        c.seed = static_cast<unsigned>(i + 1);
        SimulatedRig r(c);
        QVERIFY(RigRecorder(*m_runs, r).record(QStringLiteral("run %1").arg(i + 1), 1.5 * 3600.0) > 0);
    }
}

void TestAnalysisPanel::selectsAndFitsInBackground()
{
    AnalysisPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(panel.setSession(1, QStringLiteral("S1")));
    QSignalSpy selected(&panel, &AnalysisPanel::selectionFinished);
    QVERIFY2(panel.startSelection(), qPrintable(panel.lastError()));
    QVERIFY(panel.running());
    QVERIFY(!panel.startFits()); // one job at a time
    QVERIFY(selected.wait(60000));
    QVERIFY2(selected.last().at(0).toBool(), qPrintable(panel.lastError()));
    const QJsonObject s = panel.selection();
    const int k = s.value(QStringLiteral("k")).toInt();
    QVERIFY(k >= 2);
    QCOMPARE(s.value(QStringLiteral("chosen")).toArray().size(), k);
    QCOMPARE(panel.channelTable()->rowCount(), s.value(QStringLiteral("channels")).toArray().size());
    QCOMPARE(panel.silhouetteTable()->rowCount(), s.value(QStringLiteral("silhouettes")).toArray().size());
    // Stored with the session, like select-points does.
    QCOMPARE(m_store->latestAnalysisResult(1, QStringLiteral("sensitive-points")).value(QStringLiteral("chosen")),
             s.value(QStringLiteral("chosen")));

    QVERIFY2(panel.startWorkflow(1, QStringLiteral("S1"), 1.5, false), qPrintable(panel.lastError()));
    QSignalSpy workflow(&panel, &AnalysisPanel::workflowFinished);
    QVERIFY(workflow.wait(120000));
    QCOMPARE(panel.models().size(), std::size_t(4)); // mlr, ridge, exp, dynamic are checked by default
    QCOMPARE(panel.comparisonTable()->rowCount(), 4);
    for (int row = 0; row < 4; ++row) {
        const AnalysisPanel::ModelRow &r = panel.models()[static_cast<std::size_t>(row)];
        QVERIFY2(r.result.has_value(), qPrintable(r.model + QStringLiteral(": ") + r.error));
        QVERIFY(r.result->holdout.has_value());
        QCOMPARE(panel.comparisonTable()->item(row, AnalysisResultsView::HeldOutRmse)->text(),
                 QString::number(r.result->holdout->metrics.rmse, 'f', 3));
        QVERIFY(r.result->holdout->metrics.n > 0);
        // Fitting the checked families chooses none (no ranking by plain CV or held-out).
        QVERIFY(!panel.comparisonTable()->item(row, AnalysisResultsView::Note)->text().contains(QStringLiteral("chosen")));
    }
    QCOMPARE(panel.results()->currentModel(), 0);
    const QString file = m_dir.filePath(QStringLiteral("saved.json"));
    QVERIFY2(panel.saveModel(3, file), qPrintable(panel.lastError()));
    QJsonObject doc;
    const DataDrivenModel m = DataDrivenModelJson::read(file, &doc);
    QCOMPARE(QString::fromStdString(m.kind), panel.models()[3].model);
    QVERIFY(!panel.saveModel(7, file));
}

void TestAnalysisPanel::cancelStopsTheFits()
{
    AnalysisPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(panel.setSession(1, QStringLiteral("S1")));
    QSignalSpy fitted(&panel, &AnalysisPanel::fitsFinished);
    QVERIFY(panel.startFits({QStringLiteral("dynamic"), QStringLiteral("exp"), QStringLiteral("ridge")}));
    panel.cancel();
    QVERIFY(fitted.wait(60000));
    QCOMPARE(fitted.last().at(0).toBool(), false);
    QVERIFY(panel.models().size() < 3 || !panel.models().back().result);
    QVERIFY(!panel.running());
}

void TestAnalysisPanel::refusesIncompleteInput()
{
    AnalysisPanel panel;
    QVERIFY(!panel.startSelection()); // no database
    QVERIFY(!panel.lastError().isEmpty());
    QVERIFY(!panel.startFits({QStringLiteral("ridge")}));
    panel.setStore(m_store.get());
    QVERIFY(!panel.setSession(42));
    QVERIFY(!panel.startWorkflow(1, QStringLiteral("NOPE"), 1.0, true));
    QVERIFY(panel.lastError().contains(QStringLiteral("NOPE")));
    QVERIFY(!panel.running());
}

// A refusal the dock can provoke names the dock's fields and session time as it shows it, not
// the CLI's options and hours (the CLI's wording is tst_clirules').
void TestAnalysisPanel::refusalsInTheDocksWords()
{
    AnalysisPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(panel.setSession(1, QStringLiteral("S1")));
    const QList<ElapsedTimeBox *> boxes = panel.findChildren<ElapsedTimeBox *>();
    QCOMPARE(boxes.size(), 4); // training from / to, held-out from / to
    boxes[0]->setValue(0.0);
    boxes[1]->setValue(3600.0);
    boxes[2]->setValue(1800.0);
    boxes[3]->setValue(boxes[3]->minimum()); // "end"
    const auto firstError = [&panel]() -> QString {
        QSignalSpy fitted(&panel, &AnalysisPanel::fitsFinished);
        if (!panel.startFits({QStringLiteral("ridge")}))
            return panel.lastError();
        if (!fitted.wait(60000) || panel.models().empty())
            return QStringLiteral("(no row)");
        return panel.models().front().error;
    };
    QCOMPARE(firstError(), QStringLiteral("Training time 0:00:00 to 1:00:00 and held-out time 0:30:00 to end overlap "
                                          "(0:30:00 to 1:00:00 would be fitted and held out): held-out time must not be fitted"));
    if (!grabfordocs::dir().isEmpty()) // a picture of the refusal as the dock shows it, to look at
        QVERIFY(grabfordocs::maximised(panel, QStringLiteral("analysis-refused"), [] {}));
    boxes[1]->setValue(boxes[1]->minimum());  // training to "end"
    boxes[2]->setValue(3.0 * 3600.0);         // held out from 3:00:00, after the 2-h session
    boxes[1]->setValue(3600.0);
    const QString outside = firstError();
    QVERIFY2(outside.startsWith(QStringLiteral("Held-out time 3:00:00 to end lies outside session 1, which runs from 0:00:00 to ")),
             qPrintable(outside));
    QVERIFY2(!outside.contains(QStringLiteral("--")), qPrintable(outside));

    // The same session ticked under Training and under Held out.
    AnalysisPanel runs;
    runs.setStore(m_runs.get());
    QVERIFY(runs.setTrainingSessions({1, 2}));
    QVERIFY(runs.setHeldOutSessions({2}));
    QVERIFY(runs.setTarget(QStringLiteral("S1")));
    QSignalSpy fitted(&runs, &AnalysisPanel::fitsFinished);
    QString both;
    if (!runs.startFits({QStringLiteral("ridge")}))
        both = runs.lastError();
    else if (fitted.wait(60000) && !runs.models().empty())
        both = runs.models().front().error;
    QCOMPARE(both, QStringLiteral("Session 2 is ticked under Training and under Held out: held-out data must be a session the "
                                  "model was not fitted to (or untick it there and give a held-out time)"));
}

void TestAnalysisPanel::severalSessionsAsTheCli()
{
    AnalysisPanel panel;
    panel.resize(1366, 768);
    panel.show();
    panel.setStore(m_runs.get());
    QVERIFY(panel.setTrainingSessions({1, 2, 3}));
    QVERIFY(panel.setHeldOutSessions({4}));
    QVERIFY(panel.setTarget(QStringLiteral("S1")));
    QCOMPARE(panel.trainingSessions(), (QList<qint64>{1, 2, 3}));
    // The request `fit 1 2 3 --holdout 4 --target S1` builds.
    const DataDrivenFitRequest q = panel.request(QStringLiteral("lagridge"));
    QCOMPARE(q.sessions, (QList<qint64>{1, 2, 3}));
    QCOMPARE(q.holdoutSessions, (QList<qint64>{4}));
    QVERIFY(!q.holdoutRange);
    QSignalSpy fitted(&panel, &AnalysisPanel::fitsFinished);
    QVERIFY2(panel.startFits({QStringLiteral("lagridge")}), qPrintable(panel.lastError()));
    QVERIFY(fitted.wait(240000));
    QVERIFY2(fitted.last().at(0).toBool(), qPrintable(panel.lastError()));
    const DataDrivenFitResult &gui = *panel.models().front().result;
    QCOMPARE(gui.foldRule, QStringLiteral("leave-runs-out"));
    // Per session and pooled: 3 training + pooled, 1 held-out.
    QCOMPARE(panel.results()->sessionTable()->rowCount(), 5);
    QCOMPARE(panel.results()->sessionTable()->item(4, 0)->text(), QStringLiteral("held-out #4"));
    QCOMPARE(panel.results()->sessionTable()->item(4, 1)->text(), QString::number(gui.holdoutSessions.front().metrics.rmse, 'f', 3));
    QCOMPARE(panel.results()->sessionTable()->item(3, 1)->text(), QString::number(gui.training.metrics.rmse, 'f', 3));
    const FittedModel g = latestFit(*m_runs, 1);
    QCOMPARE(panel.storedFits().front(), g.id);
    // Item 4: the stored fit names the face that ran it.
    QCOMPARE(g.provenance.value(QStringLiteral("software")).toString(), DataDrivenFitRecord::software(DataDrivenFitRecord::Face::Gui));
    QVERIFY(g.provenance.value(QStringLiteral("software")).toString().startsWith(QStringLiteral("driftlab-gui ")));

    // The CLI on the same sessions stores the same coefficients and metrics.
    const QString out = m_dir.filePath(QStringLiteral("lagridge-cli.json"));
    const clirunner::Result r = cli({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("3"),
                                     QStringLiteral("--model"), QStringLiteral("lagridge"), QStringLiteral("--target"), QStringLiteral("S1"),
                                     QStringLiteral("--holdout"), QStringLiteral("4"), QStringLiteral("--db"), m_runsDb,
                                     QStringLiteral("--out"), out});
    QVERIFY2(r.code == 0, r.err.constData());
    m_runs = std::make_unique<SessionStore>(m_runsDb); // read what the other process wrote
    panel.setStore(m_runs.get());
    const FittedModel c = latestFit(*m_runs, 1);
    QVERIFY(c.id > g.id);
    QCOMPARE(c.provenance.value(QStringLiteral("software")).toString(), DataDrivenFitRecord::software(DataDrivenFitRecord::Face::Cli));
    QCOMPARE(c.model, g.model);
    QStringList diff;
    sameJson(g.parameters, c.parameters, QStringLiteral("parameters"), {}, diff);
    sameJson(g.metrics, c.metrics, QStringLiteral("metrics"), {}, diff);
    sameJson(g.uncertainties, c.uncertainties, QStringLiteral("uncertainties"), {}, diff);
    sameJson(g.provenance, c.provenance, QStringLiteral("provenance"), {QStringLiteral("software"), QStringLiteral("file")}, diff);
    QVERIFY2(diff.isEmpty(), qPrintable(diff.mid(0, 10).join(QLatin1Char('\n'))));
    QVERIFY(!g.parameters.value(QStringLiteral("linear")).toObject().value(QStringLiteral("terms")).toArray().isEmpty());

    // Item 3: absolute temperatures at 26 C leave the training range (20-22 C): the warning is
    // on the page (not a tooltip) and is the CLI's line.
    QCOMPARE(panel.results()->warningLabel()->isVisible(), !gui.holdoutSessions.front().extrapolated.isEmpty());
    QVERIFY(panel.setTrainingSessions({1, 2, 3}));
    QVERIFY(panel.setHeldOutSessions({4}));
    QVERIFY(panel.setTarget(QStringLiteral("S1")));
    const QStringList absolute{QStringLiteral("--reference"), QStringLiteral("absolute")};
    QSignalSpy again(&panel, &AnalysisPanel::fitsFinished);
    for (QComboBox *box : panel.findChildren<QComboBox *>())
        if (box->findData(QStringLiteral("absolute")) >= 0)
            box->setCurrentIndex(box->findData(QStringLiteral("absolute")));
    QCOMPARE(panel.request(QStringLiteral("ridge")).reference, QStringLiteral("absolute"));
    QVERIFY2(panel.startFits({QStringLiteral("ridge")}), qPrintable(panel.lastError()));
    QVERIFY(again.wait(240000));
    QVERIFY2(again.last().at(0).toBool(), qPrintable(panel.lastError()));
    const ValidationSeries &held = panel.models().front().result->holdoutSessions.front();
    QVERIFY(!held.extrapolated.isEmpty());
    QLabel *warning = panel.results()->warningLabel();
    QVERIFY(warning->isVisible());
    const QString line = ExtrapolationWarning::text(QStringLiteral("held-out session 4"), held.extrapolated.front(), held.extrapolatedFraction.front());
    QVERIFY2(warning->text().split(QLatin1Char('\n')).contains(line), qPrintable(warning->text()));
    const clirunner::Result rr = cli(QStringList{QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("3"),
                                      QStringLiteral("--model"), QStringLiteral("ridge"), QStringLiteral("--target"), QStringLiteral("S1"),
                                      QStringLiteral("--holdout"), QStringLiteral("4"), QStringLiteral("--db"), m_runsDb, QStringLiteral("--out"),
                                      m_dir.filePath(QStringLiteral("ridge-cli.json"))} + absolute);
    QVERIFY2(rr.code == 0, rr.err.constData());
    QVERIFY2(QString::fromUtf8(rr.err).contains(QStringLiteral("warning: ") + line), rr.err.constData());
    m_runs = std::make_unique<SessionStore>(m_runsDb);
    panel.setStore(m_runs.get());
}

void TestAnalysisPanel::autoChoosesAsTheCli()
{
    // Two cases: three training runs (whole-session CV), and one run (time-blocked CV) where the
    // family with the lowest plain CV (what the dock once ranked by) is not the rule's choice.
    struct Case {
        QList<qint64> training;
        bool disagrees;
    };
    for (const Case &k : {Case{{1, 2, 3}, false}, Case{{1}, true}}) {
        AnalysisPanel panel;
        panel.setStore(m_runs.get());
        QVERIFY(panel.setTrainingSessions(k.training));
        QVERIFY(panel.setHeldOutSessions({4}));
        QVERIFY(panel.setTarget(QStringLiteral("S1")));
        QSignalSpy fitted(&panel, &AnalysisPanel::fitsFinished);
        QVERIFY2(panel.startAuto(), qPrintable(panel.lastError()));
        QVERIFY(fitted.wait(300000));
        QVERIFY2(fitted.last().at(0).toBool(), qPrintable(panel.lastError()));
        // The comparison table of auto: one row per family, exactly one chosen, held-out shown.
        const std::vector<AnalysisPanel::ModelRow> &rows = panel.models();
        QTableWidget *table = panel.comparisonTable();
        QCOMPARE(table->rowCount(), static_cast<int>(rows.size()));
        QVERIFY(rows.size() >= 5);
        QString chosen, lowestNested, lowestPlain;
        double lowest = INFINITY, plain = INFINITY;
        int chosenRow = -1;
        for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
            const AnalysisPanel::ModelRow &r = rows[static_cast<std::size_t>(i)];
            QVERIFY(r.comparison.has_value());
            if (r.comparison->chosen) {
                QVERIFY(chosen.isEmpty());
                chosen = r.model;
                chosenRow = i;
                QVERIFY(r.result.has_value());
                QCOMPARE(table->item(i, AnalysisResultsView::Note)->text(), QStringLiteral("chosen by the rule"));
            }
            if (std::isfinite(r.comparison->nestedCvRmse) && r.comparison->nestedCvRmse < lowest) {
                lowest = r.comparison->nestedCvRmse;
                lowestNested = r.model;
            }
            if (std::isfinite(r.comparison->cvRmse) && r.comparison->cvRmse < plain) {
                plain = r.comparison->cvRmse;
                lowestPlain = r.model;
            }
            QCOMPARE(table->item(i, AnalysisResultsView::CvRmse)->text(), QString::number(r.comparison->cvRmse, 'f', 3));
            QCOMPARE(table->item(i, AnalysisResultsView::NestedCv)->text(), QString::number(r.comparison->nestedCvRmse, 'f', 3));
            QVERIFY(r.comparison->holdout.has_value()); // held-out shown for every family
            QCOMPARE(table->item(i, AnalysisResultsView::HeldOutRmse)->text(), QString::number(r.comparison->holdout->rmse, 'f', 3));
        }
        QVERIFY(!chosen.isEmpty());
        QCOMPARE(panel.results()->currentModel(), chosenRow);
        QVERIFY(!panel.results()->ruleLabel()->isHidden());
        QVERIFY(panel.results()->ruleLabel()->text().contains(QStringLiteral("never used to choose")));
        const FittedModel g = latestFit(*m_runs, k.training.front());
        QCOMPARE(g.model, QStringLiteral("driftlab-model/%1").arg(chosen));
        QCOMPARE(g.provenance.value(QStringLiteral("model_selection")).toObject().value(QStringLiteral("chosen")).toString(), chosen);

        QStringList args{QStringLiteral("fit")};
        for (qint64 id : k.training)
            args << QString::number(id);
        args << QStringList{QStringLiteral("--model"), QStringLiteral("auto"), QStringLiteral("--target"), QStringLiteral("S1"),
                            QStringLiteral("--holdout"), QStringLiteral("4"), QStringLiteral("--db"), m_runsDb, QStringLiteral("--out"),
                            m_dir.filePath(QStringLiteral("auto-cli-%1.json").arg(k.training.size())), QStringLiteral("--json"),
                            QStringLiteral("-")};
        const clirunner::Result r = cli(args);
        QVERIFY2(r.code == 0, r.err.constData());
        const QJsonObject selection = QJsonDocument::fromJson(r.out).object().value(QStringLiteral("model_selection")).toObject();
        QCOMPARE(selection.value(QStringLiteral("chosen")).toString(), chosen);
        QCOMPARE(selection.value(QStringLiteral("lowest_cv")).toString(), lowestNested);
        const QJsonArray families = selection.value(QStringLiteral("families")).toArray();
        QCOMPARE(families.size(), static_cast<int>(rows.size()));
        QStringList diff;
        for (int i = 0; i < families.size(); ++i) {
            const QJsonObject f = families[i].toObject();
            const FamilyComparison &c = *rows[static_cast<std::size_t>(i)].comparison;
            QCOMPARE(f.value(QStringLiteral("model")).toString(), rows[static_cast<std::size_t>(i)].model);
            QCOMPARE(f.value(QStringLiteral("chosen")).toBool(), c.chosen);
            sameJson(f.value(QStringLiteral("nested_cv_rmse_um")), c.nestedCvRmse, c.model + QStringLiteral(" nested"), {}, diff);
            sameJson(f.value(QStringLiteral("cross_validation_rmse_um")), c.cvRmse, c.model + QStringLiteral(" cv"), {}, diff);
        }
        QVERIFY2(diff.isEmpty(), qPrintable(diff.join(QLatin1Char('\n'))));
        qInfo("auto on runs %s, held out 4: chosen %s; lowest plain CV %s, lowest nested CV %s",
              qPrintable(args.mid(1, k.training.size()).join(QLatin1Char(','))), qPrintable(chosen), qPrintable(lowestPlain),
              qPrintable(lowestNested));
        if (k.disagrees) // the case item 2 asks for: a plain-CV ranking would have shown another family first
            QVERIFY2(lowestPlain != chosen, qPrintable(lowestPlain));
        m_runs = std::make_unique<SessionStore>(m_runsDb);
    }
}

QTEST_MAIN(TestAnalysisPanel)
#include "tst_analysispanel.moc"

// The data-driven commands through the executable: select-points on simulated rig sessions
// with known thermal groups (ambient, motor, nut housing: three PT100 each) picks one channel
// from each group; fit --model mlr|ridge|dynamic|exp|synthetic writes MODEL.json that validate
// reads back to the same held-out numbers; bad input exits 2 naming what is wrong and writes
// nothing; on FL_THERMAL (real data, ../shared/extdata; skipped without it) the seed-003
// pipeline gives the reference ~10 um on ch3 and the dynamic model at most 4 um held-out.
// Several sessions: fit on three rig sessions (CV leaves whole sessions out), validate on a
// held-out session at another ambient and feed, per session and pooled, in one JSON layout;
// `auto` chooses by the stated rule (nested CV, paired one-standard-error, plain references first),
// checked again from its own table.

#include "../support/CliRunner.h"
#include "../support/FlThermalBundle.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSet>
#include <QTemporaryDir>
#include <QTextStream>
#include <QtTest>

#include <cmath>

class TestDataDriven : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void selectionPicksOneChannelPerGroup();
    void fitAndValidateAgree();
    void syntheticOnInterferometerRuns();
    void plotsSelectionHeadless();
    void multiSessionFitAndValidate();
    void autoChoosesByTheStatedRule();
    void badInputExitsTwo();
    void flThermalHeldOut();

private:
    int run(const QStringList &args, QByteArray *out = nullptr, QByteArray *err = nullptr);
    QJsonObject json(const QStringList &args);
    QTemporaryDir m_dir;
    QString m_db;
};

int TestDataDriven::run(const QStringList &args, QByteArray *out, QByteArray *err)
{
    const clirunner::Result r = clirunner::run(args, QString(), 600000);
    if (out)
        *out = r.out;
    if (err)
        *err = r.err;
    return r.code;
}

QJsonObject TestDataDriven::json(const QStringList &args)
{
    QByteArray out, err;
    const int code = run(args + QStringList{QStringLiteral("--json"), QStringLiteral("-")}, &out, &err);
    if (code != 0)
        qWarning("%s", err.constData());
    return code == 0 ? QJsonDocument::fromJson(out).object() : QJsonObject();
}

void TestDataDriven::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_db = m_dir.filePath(QStringLiteral("dd.sqlite"));
    // Three truly distinct thermal groups: the drifting ambient, the motor (losses + its own
    // capacity) and the nut housing (friction heat), three PT100s each with different noise.
    QJsonArray pt100;
    for (const char *group : {"A", "M", "N"})
        for (int i = 1; i <= 3; ++i) {
            const QString location = group[0] == 'A' ? QStringLiteral("ambient")
                                                     : (group[0] == 'M' ? QStringLiteral("motor") : QStringLiteral("nut"));
            pt100.append(QJsonObject{{QStringLiteral("id"), QStringLiteral("%1%2").arg(QLatin1String(group)).arg(i)},
                                     {QStringLiteral("location"), location},
                                     {QStringLiteral("noise_K"), 0.02 * i * i}});
        }
    const QJsonObject rig{{QStringLiteral("format"), QStringLiteral("driftlab-rig")},
                          {QStringLiteral("version"), 1},
                          {QStringLiteral("name"), QStringLiteral("groups")},
                          // The nut housing warms with the screw under it (the baseline's
                          // housings are near-adiabatic, 0.05 W/K, so the housing would follow
                          // the ambient and the nut group would merge with it).
                          {QStringLiteral("thermal"),
                           QJsonObject{{QStringLiteral("nut_housing"), QJsonObject{{QStringLiteral("to_screw_W_K"), 0.5}}}}},
                          {QStringLiteral("sensors"),
                           QJsonObject{{QStringLiteral("pt100"), pt100},
                                       {QStringLiteral("infrared"), QJsonObject{{QStringLiteral("enabled"), false}}},
                                       {QStringLiteral("interferometer"), QJsonObject{{QStringLiteral("enabled"), false}}}}}};
    const QString rigFile = m_dir.filePath(QStringLiteral("groups.json"));
    QFile f(rigFile);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QJsonDocument(rig).toJson());
    f.close();
    for (const char *seed : {"1", "2"})
        QCOMPARE(run({QStringLiteral("record"), QStringLiteral("--rig"), rigFile, QStringLiteral("--seed"), QLatin1String(seed),
                      QStringLiteral("--duration"), QStringLiteral("3:00:00"), QStringLiteral("--out"), m_db}),
                 0);
    // Session 3: seed 002's instruments (screw PT100s T6, T7 and laser runs every 30 min).
    QCOMPARE(run({QStringLiteral("record"), QStringLiteral("--rig"), QStringLiteral("seed002-instruments"),
                  QStringLiteral("--duration"), QStringLiteral("3:00:00"), QStringLiteral("--out"), m_db}),
             0);
    // Sessions 4 and 5: the same rig 4 K warmer, running at 9000 mm/min (seed 000's Table-2 shape).
    QJsonObject warm = rig;
    QJsonObject thermal = warm.value(QStringLiteral("thermal")).toObject();
    thermal.insert(QStringLiteral("ambient"), QJsonObject{{QStringLiteral("mean_C"), 24.0}});
    warm.insert(QStringLiteral("thermal"), thermal);
    warm.insert(QStringLiteral("programme"),
                QJsonObject{{QStringLiteral("preset"), QStringLiteral("seed000-table2")}, {QStringLiteral("feed_mm_min"), 9000.0}});
    const QString warmFile = m_dir.filePath(QStringLiteral("groups-warm.json"));
    QFile w(warmFile);
    QVERIFY(w.open(QIODevice::WriteOnly));
    w.write(QJsonDocument(warm).toJson());
    w.close();
    for (const char *seed : {"3", "4"})
        QCOMPARE(run({QStringLiteral("record"), QStringLiteral("--rig"), warmFile, QStringLiteral("--seed"), QLatin1String(seed),
                      QStringLiteral("--duration"), QStringLiteral("2:00:00"), QStringLiteral("--out"), m_db}),
                 0);
}

void TestDataDriven::selectionPicksOneChannelPerGroup()
{
    for (const char *session : {"1", "2"}) {
        const QJsonObject r = json({QStringLiteral("select-points"), QLatin1String(session), QStringLiteral("--db"), m_db,
                                    QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--k-range"), QStringLiteral("2:6")});
        QCOMPARE(r.value(QStringLiteral("k")).toInt(), 3);
        QCOMPARE(r.value(QStringLiteral("silhouettes")).toArray().size(), 5);
        QSet<QChar> groups;
        for (const QJsonValue &c : r.value(QStringLiteral("chosen")).toArray())
            groups.insert(c.toString().at(0));
        QCOMPARE(groups, (QSet<QChar>{QLatin1Char('A'), QLatin1Char('M'), QLatin1Char('N')}));
        for (const QJsonValue &cluster : r.value(QStringLiteral("clusters")).toArray()) {
            const QJsonArray members = cluster.toArray();
            QCOMPARE(members.size(), 3);
            for (const QJsonValue &m : members)
                QCOMPARE(m.toString().at(0), members.first().toString().at(0));
        }
        // Every channel has a grade and a cluster.
        QCOMPARE(r.value(QStringLiteral("channels")).toArray().size(), 9);
    }
}

void TestDataDriven::fitAndValidateAgree()
{
    for (const char *model : {"mlr", "ridge", "dynamic", "exp"}) {
        const QString file = m_dir.filePath(QStringLiteral("%1.json").arg(QLatin1String(model)));
        const QJsonObject fit = json({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
                                      QLatin1String(model), QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout"),
                                      QStringLiteral("2"), QStringLiteral("--out"), file});
        QVERIFY2(!fit.isEmpty(), model);
        QFile f(file);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject doc = QJsonDocument::fromJson(f.readAll()).object();
        QCOMPARE(doc.value(QStringLiteral("format")).toString(), QStringLiteral("driftlab-model"));
        QCOMPARE(doc.value(QStringLiteral("version")).toInt(), 1);
        QCOMPARE(doc.value(QStringLiteral("model")).toString(), QLatin1String(model));
        QCOMPARE(doc.value(QStringLiteral("target")).toObject().value(QStringLiteral("channel")).toString(), QStringLiteral("S1"));
        QVERIFY(!doc.value(QStringLiteral("inputs")).toArray().isEmpty());
        QVERIFY(doc.contains(QStringLiteral("uncertainties")));
        const double heldOut = fit.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject()
                                   .value(QStringLiteral("rmse_um")).toDouble();
        QVERIFY(heldOut > 0);
        // validate --json has fit's layout: metrics.holdout.
        const QJsonObject v = json({QStringLiteral("validate"), file, QStringLiteral("2"), QStringLiteral("--db"), m_db})
                                  .value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject();
        QVERIFY2(std::fabs(v.value(QStringLiteral("rmse_um")).toDouble() - heldOut) < 1e-9 * heldOut, model);
        QCOMPARE(v.value(QStringLiteral("sessions")).toArray().first().toObject().value(QStringLiteral("session")).toInt(), 2);
        QCOMPARE(v.value(QStringLiteral("samples")).toInt(),
                 fit.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject().value(QStringLiteral("samples")).toInt());
        if (QLatin1String(model) == QLatin1String("mlr"))
            QCOMPARE(doc.value(QStringLiteral("selection")).toObject().value(QStringLiteral("chosen")).toArray().size(), 3);
        if (QLatin1String(model) == QLatin1String("exp")) {
            // The rig's elongation follows the feed: seed 001's model predicts the other session.
            const QJsonObject h = fit.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject();
            QVERIFY2(h.value(QStringLiteral("fitting_degree_pct")).toDouble() > 95, qPrintable(QString::number(heldOut)));
            const QJsonObject p = doc.value(QStringLiteral("uncertainties")).toObject().value(QStringLiteral("parameters")).toObject();
            QVERIFY(p.value(QStringLiteral("tau_warm_s")).toObject().value(QStringLiteral("standard_error")).toDouble() > 0);
        }
    }
}

void TestDataDriven::syntheticOnInterferometerRuns()
{
    const QString file = m_dir.filePath(QStringLiteral("synthetic.json"));
    const QJsonObject fit = json({QStringLiteral("fit"), QStringLiteral("3"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
                                  QStringLiteral("synthetic"), QStringLiteral("--target"), QStringLiteral("interferometer"),
                                  QStringLiteral("--train-range"), QStringLiteral("0:2"), QStringLiteral("--holdout-range"),
                                  QStringLiteral("2:"), QStringLiteral("--out"), file});
    QVERIFY(!fit.isEmpty());
    QJsonArray inputs;
    for (const QJsonValue &i : fit.value(QStringLiteral("inputs")).toArray())
        inputs.append(i.toObject().value(QStringLiteral("channel")));
    QCOMPARE(inputs, (QJsonArray{QStringLiteral("T6"), QStringLiteral("T7")}));
    const QJsonObject training = fit.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("training")).toObject();
    QVERIFY(training.value(QStringLiteral("samples")).toInt() >= 24);
    QVERIFY(training.value(QStringLiteral("fitting_degree_pct")).toDouble() > 80);
    const QJsonObject v = json({QStringLiteral("validate"), file, QStringLiteral("3"), QStringLiteral("--db"), m_db,
                                QStringLiteral("--range"), QStringLiteral("2:")})
                              .value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject();
    QCOMPARE(v.value(QStringLiteral("rmse_um")).toDouble(),
             fit.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject().value(QStringLiteral("rmse_um")).toDouble());
}

void TestDataDriven::plotsSelectionHeadless()
{
    QVERIFY(!json({QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--target"),
                   QStringLiteral("S1")})
                 .isEmpty());
    for (const char *view : {"selection-grades", "selection-clusters", "selection-points"}) {
        const QString png = m_dir.filePath(QStringLiteral("%1.png").arg(QLatin1String(view)));
        QCOMPARE(run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--view"),
                      QLatin1String(view), QStringLiteral("--out"), png}),
                 0);
        const QImage image(png);
        QVERIFY2(!image.isNull() && image.width() > 800, view);
    }
    // Session 3 has no stored selection: the views say so (exit 2).
    QByteArray err;
    QCOMPARE(run({QStringLiteral("plot"), QStringLiteral("3"), QStringLiteral("--db"), m_db, QStringLiteral("--view"),
                  QStringLiteral("selection-grades"), QStringLiteral("--out"), m_dir.filePath(QStringLiteral("x.png"))},
                 nullptr, &err),
             2);
    QVERIFY(err.contains("select-points"));
}

void TestDataDriven::multiSessionFitAndValidate()
{
    const QString file = m_dir.filePath(QStringLiteral("multi.json"));
    const QJsonObject fit = json({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("4"),
                                  QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("lagridge"),
                                  QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout"), QStringLiteral("5"),
                                  QStringLiteral("--out"), file});
    QVERIFY(!fit.isEmpty());
    const QJsonObject hyper = fit.value(QStringLiteral("hyperparameters")).toObject();
    QCOMPARE(hyper.value(QStringLiteral("fold_rule")).toString(), QStringLiteral("leave-runs-out"));
    QCOMPARE(hyper.value(QStringLiteral("folds")).toInt(), 3);
    QCOMPARE(fit.value(QStringLiteral("training")).toObject().value(QStringLiteral("sessions")).toArray().size(), 3);
    const QJsonObject metrics = fit.value(QStringLiteral("metrics")).toObject();
    const QJsonObject training = metrics.value(QStringLiteral("training")).toObject();
    const QJsonArray perSession = training.value(QStringLiteral("sessions")).toArray();
    QCOMPARE(perSession.size(), 3);
    int sum = 0;
    for (const QJsonValue &s : perSession)
        sum += s.toObject().value(QStringLiteral("samples")).toInt();
    QCOMPARE(training.value(QStringLiteral("samples")).toInt(), sum);
    const QJsonObject holdout = metrics.value(QStringLiteral("holdout")).toObject();
    QCOMPARE(holdout.value(QStringLiteral("sessions")).toArray().first().toObject().value(QStringLiteral("session")).toInt(), 5);
    // validate reads the model back to the same numbers: held out, and pooled over the training sessions.
    const QJsonObject v5 = json({QStringLiteral("validate"), file, QStringLiteral("5"), QStringLiteral("--db"), m_db})
                               .value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject();
    const double h = holdout.value(QStringLiteral("rmse_um")).toDouble();
    QVERIFY2(std::fabs(v5.value(QStringLiteral("rmse_um")).toDouble() - h) < 1e-9 * h, qPrintable(QString::number(h)));
    const QJsonObject vt = json({QStringLiteral("validate"), file, QStringLiteral("1,2"), QStringLiteral("4"), QStringLiteral("--db"), m_db})
                               .value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject();
    QCOMPARE(vt.value(QStringLiteral("sessions")).toArray().size(), 3);
    QCOMPARE(vt.value(QStringLiteral("samples")).toInt(), sum);
    const double tr = training.value(QStringLiteral("rmse_um")).toDouble();
    QVERIFY2(std::fabs(vt.value(QStringLiteral("rmse_um")).toDouble() - tr) < 1e-9 * tr, qPrintable(QString::number(tr)));
    // Every prediction's stated 1 sigma: the nested CV RMSE, in MODEL.json and in validate's layout
    // (pooled and per session) with the share of errors within it.
    const double sigma = fit.value(QStringLiteral("prediction_uncertainty")).toObject().value(QStringLiteral("sigma")).toDouble();
    QCOMPARE(sigma, hyper.value(QStringLiteral("nested_cv_rmse")).toDouble());
    QCOMPARE(v5.value(QStringLiteral("prediction_sigma_um")).toDouble(), sigma);
    const double within = v5.value(QStringLiteral("within_1sigma_pct")).toDouble();
    QVERIFY(within > 0.0 && within <= 100.0);
    QCOMPARE(v5.value(QStringLiteral("sessions")).toArray().first().toObject().value(QStringLiteral("within_1sigma_pct")).toDouble(), within);
    qInfo("lagridge: stated sigma %.3f um, %.1f %% of held-out session 5 within it", sigma, within);
    // A reduced model per input, each without its input and with the full model's reference.
    const QJsonArray inputsOfFit = fit.value(QStringLiteral("inputs")).toArray();
    const QJsonArray reduced = fit.value(QStringLiteral("reduced_models")).toArray();
    QCOMPARE(reduced.size(), inputsOfFit.size());
    for (int i = 0; i < reduced.size(); ++i) {
        const QJsonObject r = reduced[i].toObject();
        const QString without = r.value(QStringLiteral("without")).toString();
        QCOMPARE(without, inputsOfFit[i].toObject().value(QStringLiteral("channel")).toString());
        const QJsonArray rin = r.value(QStringLiteral("inputs")).toArray();
        QCOMPARE(rin.size(), inputsOfFit.size() - 1);
        for (const QJsonValue &c : rin)
            QVERIFY(c.toObject().value(QStringLiteral("channel")).toString() != without);
        QCOMPARE(r.value(QStringLiteral("reference")), fit.value(QStringLiteral("reference")));
        QVERIFY(r.value(QStringLiteral("prediction_uncertainty")).toObject().value(QStringLiteral("sigma")).toDouble() > 0.0);
    }
    qInfo("lagridge on sessions 1, 2, 4 (%s): CV %.3f um, held-out session 5 %.3f um",
          qPrintable(hyper.value(QStringLiteral("reference")).toString()),
          metrics.value(QStringLiteral("cross_validation_rmse_um")).toDouble(), h);
    // Several sessions for the sensitive points too.
    const QJsonObject sel = json({QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("--db"), m_db,
                                  QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--k-range"), QStringLiteral("2:6")});
    QCOMPARE(sel.value(QStringLiteral("sessions")).toArray().size(), 2);
    QVERIFY(!sel.value(QStringLiteral("chosen")).toArray().isEmpty());
}

void TestDataDriven::autoChoosesByTheStatedRule()
{
    const QString file = m_dir.filePath(QStringLiteral("auto.json"));
    const QJsonObject fit = json({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("4"),
                                  QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("auto"),
                                  QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout"), QStringLiteral("5"),
                                  QStringLiteral("--out"), file});
    QVERIFY(!fit.isEmpty());
    const QJsonObject sel = fit.value(QStringLiteral("model_selection")).toObject();
    const QJsonArray families = sel.value(QStringLiteral("families")).toArray();
    QStringList names;
    for (const QJsonValue &f : families)
        names << f.toObject().value(QStringLiteral("model")).toString();
    QCOMPARE(names, (QStringList{QStringLiteral("mean"), QStringLiteral("mlr"), QStringLiteral("ridge"), QStringLiteral("lagridge"),
                                 QStringLiteral("dynamic"), QStringLiteral("exp")}));
    // The rule, again from the table: nested CV; a family is as good as the lowest when within
    // one paired standard error of it; a plain reference (mean, lagridge) among those is chosen
    // first, else the fewest parameters.
    const auto nested = [](const QJsonObject &o) { return o.value(QStringLiteral("nested_cv_rmse_um")); };
    double lowest = INFINITY;
    for (const QJsonValue &f : families) {
        const QJsonObject o = f.toObject();
        if (nested(o).isDouble() && nested(o).toDouble() < lowest)
            lowest = nested(o).toDouble();
        QVERIFY2(o.contains(QStringLiteral("holdout")) || o.contains(QStringLiteral("error")), qPrintable(o.value(QStringLiteral("model")).toString()));
        const QString m = o.value(QStringLiteral("model")).toString();
        QCOMPARE(o.value(QStringLiteral("plain_reference")).toBool(), m == QLatin1String("mean") || m == QLatin1String("lagridge"));
        // Without a hyperparameter search (mean, exp) the nested CV is the plain CV.
        if (m == QLatin1String("mean") || m == QLatin1String("exp"))
            QCOMPARE(nested(o).toDouble(), o.value(QStringLiteral("cross_validation_rmse_um")).toDouble());
    }
    QVERIFY(std::isfinite(lowest));
    const auto within = [&](const QJsonObject &o) {
        return nested(o).isDouble() && nested(o).toDouble() <= lowest + o.value(QStringLiteral("paired_standard_error_um")).toDouble() + 1e-12;
    };
    QString chosen, bestReference;
    int chosenParameters = 0;
    double bestReferenceCv = INFINITY;
    for (const QJsonValue &f : families) {
        const QJsonObject o = f.toObject();
        if (o.value(QStringLiteral("chosen")).toBool()) {
            QVERIFY(chosen.isEmpty());
            chosen = o.value(QStringLiteral("model")).toString();
            chosenParameters = o.value(QStringLiteral("parameters")).toInt();
            QVERIFY(within(o));
        }
        if (within(o) && o.value(QStringLiteral("plain_reference")).toBool() && nested(o).toDouble() < bestReferenceCv) {
            bestReferenceCv = nested(o).toDouble();
            bestReference = o.value(QStringLiteral("model")).toString();
        }
    }
    if (!bestReference.isEmpty())
        QCOMPARE(chosen, bestReference);
    else
        for (const QJsonValue &f : families)
            if (within(f.toObject()))
                QVERIFY2(f.toObject().value(QStringLiteral("parameters")).toInt() >= chosenParameters,
                         qPrintable(f.toObject().value(QStringLiteral("model")).toString()));
    QCOMPARE(sel.value(QStringLiteral("chosen")).toString(), chosen);
    QCOMPARE(fit.value(QStringLiteral("model")).toString(), chosen);
    QFile f(file);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(QJsonDocument::fromJson(f.readAll()).object().contains(QStringLiteral("model_selection")));
    QStringList table;
    for (const QJsonValue &v : families) {
        const QJsonObject o = v.toObject();
        table << QStringLiteral("%1 CV %2 held-out %3").arg(o.value(QStringLiteral("model")).toString())
                     .arg(o.value(QStringLiteral("cross_validation_rmse_um")).toDouble(), 0, 'f', 3)
                     .arg(o.value(QStringLiteral("holdout")).toObject().value(QStringLiteral("rmse_um")).toDouble(), 0, 'f', 3);
    }
    qInfo("auto on sessions 1, 2, 4 -> %s; %s", qPrintable(chosen), qPrintable(table.join(QStringLiteral("; "))));
}

void TestDataDriven::badInputExitsTwo()
{
    QByteArray err;
    const QString out = m_dir.filePath(QStringLiteral("never.json"));
    auto expect2 = [&](const QStringList &args, const char *needle) {
        err.clear();
        const int code = run(args, nullptr, &err);
        QVERIFY2(code == 2, qPrintable(args.join(QLatin1Char(' ')) + QStringLiteral(" -> %1: ").arg(code) + QString::fromUtf8(err)));
        QVERIFY2(err.contains(needle), qPrintable(QString::fromUtf8(err)));
    };
    expect2({QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("--db"), m_db}, "--target");
    expect2({QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--target"),
             QStringLiteral("NOPE")},
            "NOPE");
    expect2({QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--target"),
             QStringLiteral("S1"), QStringLiteral("--k-range"), QStringLiteral("5:3")},
            "--k-range");
    expect2({QStringLiteral("select-points"), QStringLiteral("99"), QStringLiteral("--db"), m_db, QStringLiteral("--target"),
             QStringLiteral("S1")},
            "no session 99");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("dynamic"),
             QStringLiteral("--target"), QStringLiteral("S1")},
            "--out");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("exp"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--drive"), QStringLiteral("none"), QStringLiteral("--out"), out},
            "drive");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("ridge"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--train-range"), QStringLiteral("5:1"), QStringLiteral("--out"), out},
            "--train-range");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("mlr"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--points"), QStringLiteral("A1,Q7"), QStringLiteral("--out"), out},
            "Q7");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("ridge"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--train-range"), QStringLiteral("50:60"), QStringLiteral("--out"), out},
            "lies outside session 1");
    // The training session cannot be its own held-out data (issue 14: same rule as diagnose).
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("mlr"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout"), QStringLiteral("1"), QStringLiteral("--out"), out},
            "training session");
    // A data-driven target must be a displacement; a drive must be a drive (issue 32).
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("mlr"),
             QStringLiteral("--target"), QStringLiteral("A1"), QStringLiteral("--out"), out},
            "--target 'A1' is a temperature channel of session 1");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("exp"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--drive"), QStringLiteral("M1"), QStringLiteral("--out"), out},
            "channel 'M1' of session 1 is not a drive");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
             QStringLiteral("ridge"), QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--out"), out},
            "session 1 is given twice");
    expect2({QStringLiteral("fit"), QStringLiteral("1:2"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("ridge"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout"), QStringLiteral("2"), QStringLiteral("--out"), out},
            "session 2 is a training session");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
             QStringLiteral("ridge"), QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--reference"), QStringLiteral("warm"),
             QStringLiteral("--out"), out},
            "--reference");
    expect2({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
             QStringLiteral("ridge"), QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout"), QStringLiteral("3"),
             QStringLiteral("--out"), out},
            "session 3 has no channel");
    QVERIFY(!QFile::exists(out)); // nothing half-written
    // A model file of a newer format version, and a model whose input the session lacks.
    QFile m(m_dir.filePath(QStringLiteral("ridge.json")));
    QVERIFY(m.open(QIODevice::ReadOnly));
    QJsonObject doc = QJsonDocument::fromJson(m.readAll()).object();
    m.close();
    QJsonObject newer = doc;
    newer.insert(QStringLiteral("version"), 3);
    const QString newerFile = m_dir.filePath(QStringLiteral("newer.json"));
    QFile n(newerFile);
    QVERIFY(n.open(QIODevice::WriteOnly));
    n.write(QJsonDocument(newer).toJson());
    n.close();
    expect2({QStringLiteral("validate"), newerFile, QStringLiteral("1"), QStringLiteral("--db"), m_db}, "version");
    QJsonArray inputs = doc.value(QStringLiteral("inputs")).toArray();
    inputs[0] = QJsonObject{{QStringLiteral("channel"), QStringLiteral("T_missing")}, {QStringLiteral("unit"), QStringLiteral("degC")}};
    doc.insert(QStringLiteral("inputs"), inputs);
    doc.remove(QStringLiteral("reduced_models")); // they name the old channel (a mismatch the reader refuses by itself)
    const QString missingFile = m_dir.filePath(QStringLiteral("missing.json"));
    QFile mm(missingFile);
    QVERIFY(mm.open(QIODevice::WriteOnly));
    mm.write(QJsonDocument(doc).toJson());
    mm.close();
    expect2({QStringLiteral("validate"), missingFile, QStringLiteral("1"), QStringLiteral("--db"), m_db}, "T_missing");
    QFile broken(m_dir.filePath(QStringLiteral("broken.json")));
    QVERIFY(broken.open(QIODevice::WriteOnly));
    broken.write("{\"format\": \"driftlab-model\", \"version\": 1, \"model\": \"ridge\", \"target\": {\"channel\": \"S1\"}, "
                 "\"inputs\": [{\"channel\": \"A1\"}], \"linear\": {\"intercept\": 0, \"terms\": [{\"input\": 0, \"lags_s\": [0], "
                 "\"coefficients\": [1, 2]}]}}");
    broken.close();
    expect2({QStringLiteral("validate"), broken.fileName(), QStringLiteral("1"), QStringLiteral("--db"), m_db},
            "linear.terms[0].coefficients");
}

void TestDataDriven::flThermalHeldOut()
{
    const QString source = flthermal::sourcePath();
    if (!QFileInfo::exists(source))
        QSKIP("../shared/extdata is not beside this checkout");
    // A bundle with the agreed channel ids (t1..t16 degC, ch1..ch5 um, spindle_rpm role spindle).
    const QString bundle = m_dir.filePath(QStringLiteral("fl.bundle"));
    const flthermal::Bundle written = flthermal::writeBundle(source, bundle, QStringLiteral("FL_THERMAL"), true);
    QVERIFY2(written.error.isEmpty(), qPrintable(written.error));
    const QString db = m_dir.filePath(QStringLiteral("fl.sqlite"));
    QCOMPARE(run({QStringLiteral("import"), bundle, QStringLiteral("--db"), db}), 0);
    auto heldOut = [&](const char *model, const char *target) {
        const QJsonObject r = json({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--model"),
                                    QLatin1String(model), QStringLiteral("--target"), QLatin1String(target), QStringLiteral("--train-range"),
                                    QStringLiteral("0:24"), QStringLiteral("--holdout-range"), QStringLiteral("24:"), QStringLiteral("--out"),
                                    m_dir.filePath(QStringLiteral("fl-%1-%2.json").arg(QLatin1String(model), QLatin1String(target)))});
        return r.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject().value(QStringLiteral("rmse_um")).toDouble(-1);
    };
    // Issue 15's reference: the seed-003 pipeline gives about 9-10 um on ch3 (the training
    // mean 26.7 um); the goal for the best model is at most 4 um.
    const double a = heldOut("mlr", "ch3");
    QVERIFY2(a > 8 && a < 12, qPrintable(QString::number(a)));
    for (const char *target : {"ch3", "ch5"}) {
        const double c = heldOut("dynamic", target);
        QVERIFY2(c > 0 && c <= 4.0, qPrintable(QStringLiteral("%1: %2").arg(QLatin1String(target)).arg(c)));
    }
}

QTEST_GUILESS_MAIN(TestDataDriven)
#include "tst_datadriven.moc"

// Issue 6 end to end: the seed-000 Table-2 programme run on the simulated rig (an
// independent truth model, its physical effects off) at 3000, 6000 and 9000 mm/min is
// identified with `driftlab-cli fit` and predicts a held-out rig session at 7500 mm/min.
//
// Tolerances (stated and asserted): the paper's criterion is a fit residual within 15 % of
// the measured peak-to-valley; we require 10 % on the training data and 10 % on the
// held-out session, for both the interferometer thermal errors and the screw-end probe.

#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

class TestFitRig : public QObject {
    Q_OBJECT
private slots:
    void identifiesAndPredictsHeldOut();

private:
    int run(const QStringList &args, QByteArray *err = nullptr);
};

int TestFitRig::run(const QStringList &args, QByteArray *err)
{
    QProcess p;
    p.start(QStringLiteral(DRIFTLAB_CLI), args);
    if (!p.waitForFinished(300000))
        return -1;
    if (err)
        *err = p.readAllStandardError();
    return p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
}

void TestFitRig::identifiesAndPredictsHeldOut()
{
    QTemporaryDir dir;
    const QString db = dir.filePath(QStringLiteral("rig.sqlite"));
    for (const char *feed : {"3000", "6000", "9000", "7500"}) {
        QByteArray err;
        QVERIFY2(run({QStringLiteral("record"), QStringLiteral("--rig"), QStringLiteral("baseline"), QStringLiteral("--feed"),
                      QLatin1String(feed), QStringLiteral("--seed"), QLatin1String(feed), QStringLiteral("--duration"),
                      QStringLiteral("2:48:00"), QStringLiteral("--out"), db},
                     &err) == 0,
                 err.constData());
    }
    const QString json = dir.filePath(QStringLiteral("model.json"));
    QByteArray err;
    QVERIFY2(run({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("3"), QStringLiteral("--model"),
                  QStringLiteral("fdm"), QStringLiteral("--db"), db, QStringLiteral("--holdout"), QStringLiteral("4"),
                  QStringLiteral("--json"), json},
                 &err) == 0,
             err.constData());
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject model = QJsonDocument::fromJson(f.readAll()).object();
    QVERIFY(model.value(QStringLiteral("converged")).toBool());
    for (const char *part : {"fit", "validation"}) {
        const QJsonObject s = model.value(QLatin1String(part)).toObject();
        const double pv = s.value(QStringLiteral("interferometer_peak_to_valley_um")).toDouble();
        const double rms = s.value(QStringLiteral("interferometer_rms_um")).toDouble();
        const double peak = s.value(QStringLiteral("elongation_peak_um")).toDouble();
        const double erms = s.value(QStringLiteral("elongation_rms_um")).toDouble();
        qInfo("%s: interferometer RMS %.3f um of P-V %.1f um; probe RMS %.3f um of peak %.1f um", part, rms, pv, erms, peak);
        QVERIFY2(pv > 10.0 && peak > 10.0, part); // the programme really heats the screw
        QVERIFY2(rms < 0.10 * pv, part);
        QVERIFY2(erms < 0.10 * peak, part);
        QVERIFY(s.value(QStringLiteral("interferometer_points")).toInt() >= 50);
    }
}

QTEST_GUILESS_MAIN(TestFitRig)
#include "tst_fitrig.moc"

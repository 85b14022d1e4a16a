// FdmModelJson owns the seed-000 MODEL.json: one key per parameter in every object, a schema
// version, and readers that accept the files written before the keys were made one
// (schema 1: standard errors and flags under "lambda" and "P_f").

#include "ExportableModelJson.h"
#include "FdmModelJson.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestFdmModelJson : public QObject {
    Q_OBJECT
private slots:
    void oneKeySetAndReadBack();
    void readsSchemaOne();
    void refusesNewerSchema();
    void labelsForPeople();
};

namespace {
// A fit result as ScrewModelIdentifier returns it (names k1..k4, lambda, P_f; P_f held).
ScrewFitResult sample()
{
    ScrewFitResult f;
    f.identification.parameters.k1 = 0.0021;
    f.identification.parameters.k2 = 11.5;
    f.identification.parameters.k3 = 3.25;
    f.identification.parameters.k4 = 0.00075;
    f.identification.parameters.conductivity_W_mK = 2374.0;
    f.identification.parameters.fixedEndPosition_mm = -12.5;
    const char *names[] = {"k1", "k2", "k3", "k4", "lambda", "P_f"};
    const double values[] = {0.0021, 11.5, 3.25, 0.00075, 2374.0, -12.5};
    for (int i = 0; i < 6; ++i)
        f.identification.all.push_back({names[i], "", values[i], 0.1 * (i + 1), i == 2 || i == 3, i != 5});
    f.identification.correlationNames = {"k1", "k2", "lambda"};
    f.identification.correlation = Eigen::MatrixXd::Identity(3, 3);
    f.implausible.push_back({"lambda", 2374.0, 45.0, "conductivity 2374 W/(m K) is implausible"});
    f.poorlyIdentified.push_back({"k4", 0.00075, 0.0, "k4 poorly identified"});
    f.sessions = {3, 4};
    f.interferometer = true;
    return f;
}
} // namespace

void TestFdmModelJson::oneKeySetAndReadBack()
{
    const ScrewFitResult fit = sample();
    const QJsonObject doc = FdmModelJson::document(fit);
    QCOMPARE(doc.value(QStringLiteral("schema_version")).toInt(), FdmModelJson::kSchemaVersion);
    const QStringList keys = doc.value(QStringLiteral("parameters")).toObject().keys();
    QCOMPARE(keys, (QStringList{QStringLiteral("fixed_end_position_mm"), QStringLiteral("k1"), QStringLiteral("k2"),
                                QStringLiteral("k3"), QStringLiteral("k4"), QStringLiteral("lambda_W_mK")}));
    const QJsonObject errors = doc.value(QStringLiteral("standard_errors")).toObject();
    QCOMPARE(errors.keys(), keys);
    QCOMPARE(errors.value(QStringLiteral("lambda_W_mK")).toDouble(), 0.5);
    QVERIFY(errors.value(QStringLiteral("fixed_end_position_mm")).isNull()); // held
    QCOMPARE(doc.value(QStringLiteral("correlation")).toObject().value(QStringLiteral("names")).toArray().last().toString(),
             QStringLiteral("lambda_W_mK"));
    const QJsonObject plausibility = doc.value(QStringLiteral("plausibility")).toObject();
    QCOMPARE(plausibility.value(QStringLiteral("implausible")).toArray().first().toObject().value(QStringLiteral("parameter")).toString(),
             QStringLiteral("lambda_W_mK"));
    QCOMPARE(FdmModelJson::flags(plausibility, QStringLiteral("lambda_W_mK")), QStringList{QStringLiteral("IMPLAUSIBLE")});
    QCOMPARE(FdmModelJson::flags(plausibility, QStringLiteral("k4")), QStringList{QStringLiteral("POORLY IDENTIFIED")});
    QVERIFY(FdmModelJson::flags(plausibility, QStringLiteral("k2")).isEmpty());

    // The stored record carries the same parameters and errors, and the file reads back.
    const FittedModel stored = FdmModelJson::storedModel(doc);
    QCOMPARE(stored.parameters, doc.value(QStringLiteral("parameters")).toObject());
    QCOMPARE(stored.uncertainties.value(QStringLiteral("standard_errors")).toObject(), errors);
    QVERIFY(!stored.provenance.contains(QStringLiteral("database")));
    const ExportableModel m = ExportableModelJson::parse(QJsonDocument(doc).toJson(), QStringLiteral("MODEL.json"));
    QVERIFY(m.physics);
    QCOMPARE(m.parameters.conductivity_W_mK, 2374.0);
    QCOMPARE(m.parameters.fixedEndPosition_mm, -12.5);
    QCOMPARE(m.parameters.k4, 0.00075);
}

void TestFdmModelJson::readsSchemaOne()
{
    // As `fit` wrote it before: errors and flags under the identifier's names.
    const QJsonObject errors{{QStringLiteral("k1"), 0.1}, {QStringLiteral("lambda"), 1660.0}, {QStringLiteral("P_f"), 4.5},
                             {QStringLiteral("k3"), QJsonValue()}};
    QCOMPARE(FdmModelJson::standardError(errors, QStringLiteral("lambda_W_mK")).toDouble(), 1660.0);
    QCOMPARE(FdmModelJson::standardError(errors, QStringLiteral("fixed_end_position_mm")).toDouble(), 4.5);
    QCOMPARE(FdmModelJson::standardError(errors, QStringLiteral("k1")).toDouble(), 0.1);
    QVERIFY(FdmModelJson::standardError(errors, QStringLiteral("k3")).isNull());
    const QJsonObject plausibility{
        {QStringLiteral("implausible"),
         QJsonArray{QJsonObject{{QStringLiteral("parameter"), QStringLiteral("lambda")}, {QStringLiteral("message"), QStringLiteral("m")}}}}};
    QStringList messages;
    QCOMPARE(FdmModelJson::flags(plausibility, QStringLiteral("lambda_W_mK"), &messages), QStringList{QStringLiteral("IMPLAUSIBLE")});
    QCOMPARE(messages, QStringList{QStringLiteral("m")});
}

void TestFdmModelJson::refusesNewerSchema()
{
    QJsonObject doc = FdmModelJson::document(sample());
    doc.insert(QStringLiteral("schema_version"), FdmModelJson::kSchemaVersion + 1);
    try {
        ExportableModelJson::parse(QJsonDocument(doc).toJson(), QStringLiteral("new.json"));
        QFAIL("a newer schema was read");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("new.json: schema_version")), e.what());
    }
    doc.remove(QStringLiteral("schema_version")); // schema 1 files are read
    QCOMPARE(ExportableModelJson::parse(QJsonDocument(doc).toJson(), QStringLiteral("old.json")).parameters.k2, 11.5);
}

void TestFdmModelJson::labelsForPeople()
{
    QCOMPARE(FdmModelJson::parameterLabel(QStringLiteral("lambda_W_mK")), QStringLiteral("lambda, screw conductivity (W/(m K))"));
    QCOMPARE(FdmModelJson::parameterLabel(QStringLiteral("fixed_end_position_mm")), QStringLiteral("P_f, fixed-end position (mm)"));
    const QJsonObject metrics{{QStringLiteral("elongation_rms_um"), 1.25},
                              {QStringLiteral("plausibility"),
                               QJsonObject{{QStringLiteral("max_relative_standard_error"), 1.0 / 3.0},
                                           {QStringLiteral("note"), QString()},
                                           {QStringLiteral("implausible"), QJsonArray{}}}},
                              {QStringLiteral("validation"), QJsonObject{{QStringLiteral("session"), 4}}}};
    const QVector<QPair<QString, QString>> rows = FdmModelJson::metricRows(metrics);
    QCOMPARE(rows.size(), 3); // the empty note and the flag list are not rows
    for (const auto &r : rows)
        QVERIFY2(!r.first.contains(QLatin1Char('_')) && !r.first.contains(QLatin1Char('.')), qPrintable(r.first));
    QCOMPARE(rows[0].first, QStringLiteral("fit: screw-end elongation RMS residual (\u00b5m)"));
    QCOMPARE(rows[0].second, QStringLiteral("1.25"));
}

QTEST_MAIN(TestFdmModelJson)
#include "tst_fdmmodeljson.moc"

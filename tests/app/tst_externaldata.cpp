// The CLI on real data we did not make: the 46-hour FL_THERMAL spindle test
// (../shared/extdata/fl_thermal, MIT licence). The test turns its CSV into a recording
// bundle (its own minimal writer, independent of storage/), imports it, exports it again,
// checks every value survives, and renders a plot headless.

#include "../support/CliRunner.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QTextStream>
#include <QtTest>

#include <cmath>

class TestExternalData : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void importExportKeepsEveryValue();
    void plotsHeadless();

private:
    int run(const QStringList &args, QByteArray *out = nullptr);
    QTemporaryDir m_dir;
    QString m_source;
    QString m_db;
    QStringList m_header;
    int m_rows = 0;
};

int TestExternalData::run(const QStringList &args, QByteArray *out)
{
    const clirunner::Result r = clirunner::run(args, QString(), 300000);
    if (out)
        *out = r.out;
    if (r.code != 0)
        qWarning("%s", r.err.constData());
    return r.code;
}

void TestExternalData::initTestCase()
{
    m_source = QStringLiteral(DRIFTLAB_SHARED_DIR "/extdata/fl_thermal/fl_thermal_data.csv");
    if (!QFileInfo::exists(m_source))
        QSKIP("../shared/extdata is not beside this checkout");
    QFile in(m_source);
    QVERIFY(in.open(QIODevice::ReadOnly | QIODevice::Text));
    const QString bundle = m_dir.filePath(QStringLiteral("fl.bundle"));
    QVERIFY(QDir().mkpath(bundle));
    QFile channels(bundle + QStringLiteral("/channels.csv"));
    QVERIFY(channels.open(QIODevice::WriteOnly | QIODevice::Text));
    QTextStream src(&in), dst(&channels);
    m_header = src.readLine().split(QLatin1Char(','));
    QCOMPARE(m_header.first(), QStringLiteral("time_s"));
    dst << m_header.join(QLatin1Char(',')) << '\n';
    while (!src.atEnd()) {
        const QString line = src.readLine();
        if (!line.isEmpty()) {
            dst << line << '\n';
            ++m_rows;
        }
    }
    channels.close();
    QCOMPARE(m_rows, 11115);
    QJsonArray list;
    for (int i = 1; i < m_header.size(); ++i) {
        const QString id = m_header[i];
        const bool temp = id.endsWith(QLatin1String("_C"));
        const bool disp = id.endsWith(QLatin1String("_um"));
        list.append(QJsonObject{{QStringLiteral("id"), id},
                                {QStringLiteral("kind"), temp ? "temperature" : (disp ? "displacement" : "other")},
                                {QStringLiteral("sensor"), QStringLiteral("unknown")},
                                {QStringLiteral("unit"), temp ? "degC" : (disp ? "um" : "rpm")},
                                {QStringLiteral("role"), id == QLatin1String("spindle_rpm") ? "spindle" : ""}});
    }
    const QJsonObject manifest{
        {QStringLiteral("format"), QStringLiteral("thermal-error-bundle")},
        {QStringLiteral("version"), 1},
        {QStringLiteral("session"), QJsonObject{{QStringLiteral("name"), QStringLiteral("FL_THERMAL 46 h spindle test")},
                                                {QStringLiteral("started"), QStringLiteral("2024-05-23T00:00:00Z")}}},
        {QStringLiteral("machine"), QJsonObject{{QStringLiteral("name"), QStringLiteral("CNC spindle (FL_THERMAL)")}}},
        {QStringLiteral("channels"), list}};
    QFile m(bundle + QStringLiteral("/manifest.json"));
    QVERIFY(m.open(QIODevice::WriteOnly));
    m.write(QJsonDocument(manifest).toJson());
    m.close();
    m_db = m_dir.filePath(QStringLiteral("fl.sqlite"));
    QCOMPARE(run({QStringLiteral("import"), bundle, QStringLiteral("--db"), m_db}), 0);
}

void TestExternalData::importExportKeepsEveryValue()
{
    QByteArray out;
    QCOMPARE(run({QStringLiteral("info"), m_db, QStringLiteral("--json"), QStringLiteral("-")}, &out), 0);
    const QJsonObject s = QJsonDocument::fromJson(out).object().value(QStringLiteral("sessions")).toArray().at(0).toObject();
    const QJsonArray channels = s.value(QStringLiteral("channels")).toArray();
    QCOMPARE(channels.size(), m_header.size() - 1);
    for (const QJsonValue &c : channels) {
        QCOMPARE(c.toObject().value(QStringLiteral("samples")).toInt(), m_rows);
        QCOMPARE(c.toObject().value(QStringLiteral("t_last_s")).toDouble(), 166710.0);
    }
    const QString exported = m_dir.filePath(QStringLiteral("back.bundle"));
    QCOMPARE(run({QStringLiteral("export"), QString::number(s.value(QStringLiteral("id")).toInt()), exported,
                  QStringLiteral("--db"), m_db}),
             0);
    // Compare every cell numerically with the source (column order may differ).
    QFile a(m_source), b(exported + QStringLiteral("/channels.csv"));
    QVERIFY(a.open(QIODevice::ReadOnly | QIODevice::Text));
    QVERIFY(b.open(QIODevice::ReadOnly | QIODevice::Text));
    QTextStream sa(&a), sb(&b);
    const QStringList ha = sa.readLine().split(QLatin1Char(','));
    const QStringList hb = sb.readLine().split(QLatin1Char(','));
    QCOMPARE(hb.size(), ha.size());
    QVector<int> map;
    for (const QString &h : ha) {
        QVERIFY2(hb.contains(h), qPrintable(h));
        map.push_back(hb.indexOf(h));
    }
    int rows = 0;
    while (!sa.atEnd()) {
        const QStringList ra = sa.readLine().split(QLatin1Char(','));
        const QStringList rb = sb.readLine().split(QLatin1Char(','));
        QCOMPARE(rb.size(), ra.size());
        for (int i = 0; i < ra.size(); ++i) {
            const double va = ra[i].toDouble(), vb = rb[map[i]].toDouble();
            if (std::fabs(va - vb) > 1e-9 * std::max(1.0, std::fabs(va)))
                QFAIL(qPrintable(QStringLiteral("row %1 column %2: %3 became %4").arg(rows + 2).arg(ha[i], ra[i], rb[map[i]])));
        }
        ++rows;
    }
    QCOMPARE(rows, m_rows);
}

void TestExternalData::plotsHeadless()
{
    const QString png = m_dir.filePath(QStringLiteral("fl.png"));
    QCOMPARE(run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--view"),
                  QStringLiteral("timeseries"), QStringLiteral("--out"), png}),
             0);
    QImage image(png);
    QVERIFY(!image.isNull());
    QVERIFY(image.width() > 800);
    // No interferometer in this data: the error views say so with exit code 2.
    QCOMPARE(run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--view"),
                  QStringLiteral("error-surface"), QStringLiteral("--out"), png}),
             2);
}

QTEST_GUILESS_MAIN(TestExternalData)
#include "tst_externaldata.moc"

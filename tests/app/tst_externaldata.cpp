// The CLI on real data we did not make: the 46-hour FL_THERMAL spindle test
// (../shared/extdata/fl_thermal, MIT licence). The test turns its CSV into a recording
// bundle (its own minimal writer, independent of storage/), imports it, exports it again,
// checks every value survives, and renders a plot headless.

#include "../support/CliRunner.h"
#include "../support/FlThermalBundle.h"

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
    m_source = flthermal::sourcePath();
    if (!QFileInfo::exists(m_source))
        QSKIP("../shared/extdata is not beside this checkout");
    const QString bundle = m_dir.filePath(QStringLiteral("fl.bundle"));
    const flthermal::Bundle written =
        flthermal::writeBundle(m_source, bundle, QStringLiteral("FL_THERMAL 46 h spindle test"), false);
    QVERIFY2(written.error.isEmpty(), qPrintable(written.error));
    m_header = written.header;
    m_rows = written.rows;
    QCOMPARE(m_header.first(), QStringLiteral("time_s"));
    QCOMPARE(m_rows, 11115);
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
    // No interferometer in this data: the error views say so with exit code 2 and write nothing
    // (to a new file: an existing --out gives 2 for another reason, as this check did before).
    const QString surface = m_dir.filePath(QStringLiteral("fl-surface.png"));
    const clirunner::Result r = clirunner::run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db,
                                                QStringLiteral("--view"), QStringLiteral("error-surface"), QStringLiteral("--out"), surface});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("no data for the view 'error-surface'"), r.err.constData());
    QVERIFY(!QFileInfo::exists(surface));
}

QTEST_GUILESS_MAIN(TestExternalData)
#include "tst_externaldata.moc"

// The starting map the import dialog offers: dialect from the first bytes, kinds/units/roles
// and ids from header texts (the FL_THERMAL header gives the shipped map's channels), the
// time column with its unit or date-time format.

#include "CsvMapGuesser.h"

#include <QFile>
#include <QtTest>

using namespace driftlab;

class TestCsvMapGuesser : public QObject {
    Q_OBJECT
private slots:
    void dialect();
    void flThermalHeaderGivesTheShippedMap();
    void headerTexts_data();
    void headerTexts();
    void timeColumns();
};

void TestCsvMapGuesser::dialect()
{
    CsvColumnMap m;
    CsvMapGuesser::guessDialect("\xEF\xBB\xBFtime_s,a,b\r\n0,1.5,2\r\n1,1.5,2\r\n", m);
    QCOMPARE(m.separator, ',');
    QCOMPARE(m.decimal, '.');
    QCOMPARE(m.encoding, QStringLiteral("utf-8"));
    CsvMapGuesser::guessDialect("Zeit;Temp, Lager;Weg\n0;20,5;1,25\n1;20,75;1,5\n", m);
    QCOMPARE(m.separator, ';');
    QCOMPARE(m.decimal, ',');
    CsvMapGuesser::guessDialect("t\tx\n0\t1.5\n1\t2.5\n", m);
    QCOMPARE(m.separator, '\t');
    QCOMPARE(m.decimal, '.');
    CsvMapGuesser::guessDialect("time;T \xB0" "C\n0;20\n", m); // Latin-1 degree sign
    QCOMPARE(m.encoding, QStringLiteral("windows-1252"));
}

void TestCsvMapGuesser::flThermalHeaderGivesTheShippedMap()
{
    QFile f(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/maps/fl_thermal.json"));
    QVERIFY(f.open(QIODevice::ReadOnly));
    const CsvColumnMap shipped = CsvColumnMap::fromJson(f.readAll(), QStringLiteral("fl_thermal.json"));
    QStringList header{QStringLiteral("time_s"), QStringLiteral("spindle_rpm")};
    for (int i = 1; i <= 5; ++i)
        header << QStringLiteral("ch%1_um").arg(i);
    for (int i = 1; i <= 16; ++i)
        header << QStringLiteral("t%1_C").arg(i);
    QStringList zeros;
    for (int i = 0; i < header.size(); ++i)
        zeros << QStringLiteral("0");
    CsvColumnMap m;
    CsvMapGuesser::guessColumns(header, {zeros}, m);
    QCOMPARE(m.time.column, shipped.time.column);
    QCOMPARE(m.time.unit, shipped.time.unit);
    QCOMPARE(m.columns.size(), shipped.columns.size());
    for (int i = 0; i < m.columns.size(); ++i) {
        const CsvColumnSpec &g = m.columns[i], &s = shipped.columns[i];
        QCOMPARE(g.column, s.column);
        QCOMPARE(g.id, s.id);
        QCOMPARE(g.kind, s.kind);
        QCOMPARE(g.unit, s.unit);
        QCOMPARE(g.role, s.role);
        QCOMPARE(g.target, s.target);
    }
}

void TestCsvMapGuesser::headerTexts_data()
{
    QTest::addColumn<QString>("header");
    QTest::addColumn<QString>("id");
    QTest::addColumn<QString>("kind");
    QTest::addColumn<QString>("unit");
    QTest::addColumn<QString>("role");
    QTest::newRow("bracket K") << "T_amb (K)" << "T_amb" << "temperature" << "K" << "ambient";
    QTest::newRow("degree sign") << "Mutter [\u00b0C]" << "Mutter" << "temperature" << "\u00b0C" << "nut";
    QTest::newRow("probe mm") << "X-Sonde [mm]" << "X-Sonde" << "displacement" << "mm" << "";
    QTest::newRow("axis position") << "X [mm]" << "X" << "position" << "mm" << "axis_position";
    QTest::newRow("feed") << "F (mm/min)" << "F" << "feed" << "mm/min" << "feed_rate";
    QTest::newRow("no unit, temperature name") << "Temp motor" << "Temp_motor" << "temperature" << "degC" << "motor";
    QTest::newRow("other") << "Power [W]" << "Power" << "other" << "W" << "";
    QTest::newRow("empty") << "" << "col4" << "other" << "" << "";
}

void TestCsvMapGuesser::headerTexts()
{
    QFETCH(QString, header);
    QFETCH(QString, id);
    QFETCH(QString, kind);
    QFETCH(QString, unit);
    QFETCH(QString, role);
    const CsvColumnSpec s = CsvMapGuesser::guessColumn(header, 4);
    QCOMPARE(s.id, id);
    QCOMPARE(s.kind, kind);
    QCOMPARE(s.unit, unit);
    QCOMPARE(s.role, role);
    QCOMPARE(s.target, kind == QLatin1String("displacement"));
}

void TestCsvMapGuesser::timeColumns()
{
    CsvColumnMap m;
    CsvMapGuesser::guessColumns({QStringLiteral("T_amb"), QStringLiteral("Datum")}, {{QStringLiteral("20"), QStringLiteral("31.12.2024 23:59:30")}}, m);
    QCOMPARE(m.time.column, QStringLiteral("Datum"));
    QCOMPARE(m.time.format, QStringLiteral("dd.MM.yyyy HH:mm:ss"));
    CsvMapGuesser::guessColumns({QStringLiteral("t [min]"), QStringLiteral("x")}, {{QStringLiteral("0,5"), QStringLiteral("1")}}, m);
    QCOMPARE(m.time.unit, QStringLiteral("min"));
    CsvMapGuesser::guessColumns({QStringLiteral("timestamp"), QStringLiteral("x")}, {{QStringLiteral("1735689600250"), QStringLiteral("1")}}, m);
    QCOMPARE(m.time.unit, QStringLiteral("unix_ms"));
    CsvMapGuesser::guessColumns({QStringLiteral("when"), QStringLiteral("x")}, {{QStringLiteral("2025-01-01T08:00:00Z"), QStringLiteral("1")}}, m);
    QCOMPARE(m.time.column, QStringLiteral("when")); // no time-like name: the first column
    QCOMPARE(m.time.format, QStringLiteral("iso8601"));
    QCOMPARE(m.columns.size(), 1);
}

QTEST_APPLESS_MAIN(TestCsvMapGuesser)
#include "tst_csvmapguesser.moc"

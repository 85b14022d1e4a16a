// The starting map the import dialog offers: dialect from the first bytes, kinds/units/roles
// and ids from header texts (the FL_THERMAL header gives the shipped map's channels), the
// time column with its unit or date-time format.

#include "CsvMapGuesser.h"
#include "CsvReader.h"
#include "CsvRowDecoder.h"

#include <QFile>
#include <QJsonDocument>
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
    void loggerFiles_data();
    void loggerFiles();
    void preambleAndHeaderlessTables();
    void tablesWithoutATimeColumn();
    void runColumn();
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
    QTest::newRow("spindle temperature is no drive") << "Spindle Temp (C)" << "Spindle_Temp" << "temperature" << "degC" << "";
    QTest::newRow("German speed") << "Drehzahl [1/min]" << "Drehzahl" << "other" << "1/min" << "spindle";
    // A temperature's place from a word of its name (2026-11-28; before, none of these had a role).
    QTest::newRow("fixed bearing") << "T_fixed_bearing (C)" << "T_fixed_bearing" << "temperature" << "degC" << "fixed_bearing";
    QTest::newRow("Festlager") << "Festlager [\u00b0C]" << "Festlager" << "temperature" << "\u00b0C" << "fixed_bearing";
    QTest::newRow("Loslager") << "T Loslager [\u00b0C]" << "T_Loslager" << "temperature" << "\u00b0C" << "free_bearing";
    QTest::newRow("free end") << "temp free end" << "temp_free_end" << "temperature" << "degC" << "free_bearing";
    QTest::newRow("bed") << "Bett links [\u00b0C]" << "Bett_links" << "temperature" << "\u00b0C" << "structure";
    QTest::newRow("St\u00e4nder") << "St\u00e4nder [\u00b0C]" << "St\u00e4nder" << "temperature" << "\u00b0C" << "structure";
    QTest::newRow("screw") << "T_screw_mid (C)" << "T_screw_mid" << "temperature" << "degC" << "screw_surface";
    QTest::newRow("which bearing is not said") << "T Lager [\u00b0C]" << "T_Lager" << "temperature" << "\u00b0C" << "";
    QTest::newRow("a word, not a part of one") << "T_freezer (C)" << "T_freezer" << "temperature" << "degC" << "";
    QTest::newRow("a displacement at the bed is no temperature place") << "Bett [\u00b5m]" << "Bett" << "displacement" << "\u00b5m" << "";
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

// The fixtures in tests/data/csv (written for these tests, see its README): the whole guess,
// dialect then columns from the header and rows the guessed dialect reads, as the dialog runs it.
void TestCsvMapGuesser::loggerFiles_data()
{
    QTest::addColumn<QString>("file");
    QTest::addColumn<char>("separator");
    QTest::addColumn<char>("decimal");
    QTest::addColumn<QString>("encoding");
    QTest::addColumn<int>("skip");
    QTest::addColumn<QString>("timeColumn");
    QTest::addColumn<QString>("timeFormatOrUnit");
    QTest::addColumn<QStringList>("kinds");
    QTest::addColumn<QStringList>("units");
    QTest::addColumn<QStringList>("roles");
    QTest::newRow("German logger") << "german_logger.csv" << ';' << ',' << "windows-1252" << 3 << "Datum" << "dd.MM.yyyy HH:mm:ss"
                                   << QStringList{"temperature", "temperature", "displacement", "other"}
                                   << QStringList{"\u00b0C", "\u00b0C", "\u00b5m", "1/min"}
                                   << QStringList{"", "ambient", "", "spindle"};
    QTest::newRow("US logger") << "us_logger.csv" << ',' << '.' << "utf-8" << 1 << "Timestamp" << "MM/dd/yyyy HH:mm:ss"
                               << QStringList{"temperature", "temperature", "displacement", "other"}
                               << QStringList{"degC", "degC", "um", "rpm"} << QStringList{"", "ambient", "", "spindle"};
    QTest::newRow("semicolon, decimal comma") << "semicolon_comma.csv" << ';' << ',' << "utf-8" << 0 << "Zeit [min]" << "min"
                                              << QStringList{"temperature", "temperature", "displacement"}
                                              << QStringList{"\u00b0C", "\u00b0C", "mm"} << QStringList{"motor", "nut", ""};
}

void TestCsvMapGuesser::loggerFiles()
{
    QFETCH(QString, file);
    QFETCH(char, separator);
    QFETCH(char, decimal);
    QFETCH(QString, encoding);
    QFETCH(int, skip);
    QFETCH(QString, timeColumn);
    QFETCH(QString, timeFormatOrUnit);
    QFETCH(QStringList, kinds);
    QFETCH(QStringList, units);
    QFETCH(QStringList, roles);
    // The whole guess from the file (the dialect, then the header and rows as it reads them).
    const CsvColumnMap m = CsvMapGuesser::guessFile(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/csv/") + file);
    QCOMPARE(m.separator, separator);
    QCOMPARE(m.decimal, decimal);
    QCOMPARE(m.encoding, encoding);
    QCOMPARE(m.skipLines, skip);
    QVERIFY(m.header);
    QCOMPARE(m.time.column, timeColumn);
    QCOMPARE(m.time.format.isEmpty() ? m.time.unit : m.time.format, timeFormatOrUnit);
    QCOMPARE(m.columns.size(), kinds.size());
    for (int i = 0; i < kinds.size(); ++i) {
        QCOMPARE(m.columns[i].kind, kinds[i]);
        QCOMPARE(m.columns[i].unit, units[i]);
        QCOMPARE(m.columns[i].role, roles[i]);
    }
    // The guess imports: every row decodes (numbers, dates, units) with no error.
    QFile f(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/csv/") + file);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray bytes = f.readAll();
    CsvRowDecoder check(CsvColumnMap::fromJson(QJsonDocument(m.toJson()).toJson(), QStringLiteral("guess.json")), file);
    for (const CsvRecord &r : CsvReader::parse(bytes, file, m.separator))
        check.accept(r);
    QCOMPARE(check.rows(), qint64(12));
    QVERIFY(check.row().time_s > 0);
}

void TestCsvMapGuesser::preambleAndHeaderlessTables()
{
    CsvColumnMap m;
    // A preamble line with as many separators as the table is still not the header: the last
    // text line before the data is.
    CsvMapGuesser::guessDialect("Messung 17;Spindel 3;Halle 2\nZeit;T1;T2\n0;20,5;21,0\n1;20,6;21,1\n", m);
    QCOMPARE(m.separator, ';');
    QCOMPARE(m.decimal, ',');
    QCOMPARE(m.skipLines, 1);
    QVERIFY(m.header);
    // Numbers from the first line: no header.
    CsvMapGuesser::guessDialect("0,20.5,1.25\n1,20.6,1.5\n2,20.7,1.75\n", m);
    QCOMPARE(m.separator, ',');
    QCOMPARE(m.skipLines, 0);
    QVERIFY(!m.header);
    // Dates with points are not decimal points: the numbers decide.
    CsvMapGuesser::guessDialect("Datum;T\n01.03.2025 08:00;20,5\n01.03.2025 08:01;20,6\n", m);
    QCOMPARE(m.decimal, ',');
}

// A logger that writes one row per interval has no time column: its first column is a
// channel (named like one, or its values go down), and the guess is a row interval for the
// user to set; a first column that counts up under a neutral name stays the time.
void TestCsvMapGuesser::tablesWithoutATimeColumn()
{
    const QVector<QStringList> rising{{QStringLiteral("20.5"), QStringLiteral("0.1")}, {QStringLiteral("20.6"), QStringLiteral("0.3")},
                                      {QStringLiteral("20.8"), QStringLiteral("0.6")}};
    CsvColumnMap m;
    CsvMapGuesser::guessColumns({QStringLiteral("T_bearing_C"), QStringLiteral("probe_um")}, rising, m);
    QVERIFY(m.time.fromRows());
    QCOMPARE(m.time.interval_s, 60.0);
    QCOMPARE(m.columns.size(), 2); // the temperature is a channel, not the clock
    QCOMPARE(m.columns[0].kind, QStringLiteral("temperature"));
    // A neutral name whose values go down is no clock either.
    const QVector<QStringList> falling{{QStringLiteral("5"), QStringLiteral("1")}, {QStringLiteral("4"), QStringLiteral("2")}};
    CsvMapGuesser::guessColumns({QStringLiteral("Kanal 1"), QStringLiteral("Kanal 2")}, falling, m);
    QVERIFY(m.time.fromRows());
    // Counting up under a neutral name, or a time unit in the header: the time column.
    const QVector<QStringList> counting{{QStringLiteral("0"), QStringLiteral("1")}, {QStringLiteral("15"), QStringLiteral("2")}};
    CsvMapGuesser::guessColumns({QStringLiteral("Messpunkt"), QStringLiteral("T1")}, counting, m);
    QVERIFY(!m.time.fromRows());
    QCOMPARE(m.time.column, QStringLiteral("Messpunkt"));
    CsvMapGuesser::guessColumns({QStringLiteral("Dauer [min]"), QStringLiteral("T1")}, falling, m);
    QCOMPARE(m.time.column, QStringLiteral("Dauer [min]"));
    QCOMPARE(m.time.unit, QStringLiteral("min"));
    // The interval guess is a map the importer reads (and writes back) as such.
    CsvMapGuesser::guessColumns({QStringLiteral("T_bearing_C"), QStringLiteral("probe_um")}, rising, m);
    const CsvColumnMap back = CsvColumnMap::fromJson(QJsonDocument(m.toJson()).toJson(), QStringLiteral("guess.json"));
    QCOMPARE(back.time.interval_s, 60.0);
    QCOMPARE(back.columns.size(), 2);
}

// A campaign in one file: a "run" column whose value names the run of each row (in blocks)
// is the run column, not a channel; a column named so that changes on most rows is data.
void TestCsvMapGuesser::runColumn()
{
    QVector<QStringList> rows;
    for (int run = 1; run <= 2; ++run)
        for (int k = 0; k < 6; ++k)
            rows << QStringList{QString::number(60 * k), QString::number(run), QStringLiteral("20.%1").arg(k)};
    CsvColumnMap m;
    CsvMapGuesser::guessColumns({QStringLiteral("time_s"), QStringLiteral("Run"), QStringLiteral("T1_C")}, rows, m);
    QCOMPARE(m.runColumn, QStringLiteral("Run"));
    QCOMPARE(m.columns.size(), 1);
    QCOMPARE(m.columns[0].id, QStringLiteral("T1"));
    const CsvColumnMap back = CsvColumnMap::fromJson(QJsonDocument(m.toJson()).toJson(), QStringLiteral("guess.json"));
    QCOMPARE(back.runColumn, QStringLiteral("Run"));
    for (int r = 0; r < rows.size(); ++r)
        rows[r][1] = QString::number(r); // a new value every row: not runs
    CsvMapGuesser::guessColumns({QStringLiteral("time_s"), QStringLiteral("Run"), QStringLiteral("T1_C")}, rows, m);
    QVERIFY(m.runColumn.isEmpty());
    QCOMPARE(m.columns.size(), 2);
}

QTEST_APPLESS_MAIN(TestCsvMapGuesser)
#include "tst_csvmapguesser.moc"

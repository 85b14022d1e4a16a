// Column maps and CSV import: map checks name the field; tables with a BOM, CRLF, ';' and
// decimal commas, date-time and epoch clocks, unit conversion, scale/offset and missing
// cells import to the values worked out here; every bad row is refused with file, line and
// column and leaves the database exactly as it was; a cancelled import leaves nothing.

#include "CsvColumnMap.h"
#include "CsvError.h"
#include "CsvImporter.h"
#include "SessionStore.h"
#include "../support/DatabaseHash.h"
#include "../support/TestFiles.h"

#include <QCryptographicHash>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QSqlRecord>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {

using testdb::contentHash;

CsvColumnMap mapOf(const QByteArray &json)
{
    return CsvColumnMap::fromJson(json, QStringLiteral("m.json"));
}

// A map with the usual header and the given csv/time blocks and columns.
QByteArray mapJson(const QByteArray &csv, const QByteArray &time, const QByteArray &columns, const QByteArray &extra = QByteArray())
{
    return "{\"format\":\"driftlab-csv-map\",\"version\":1," + (csv.isEmpty() ? QByteArray() : "\"csv\":" + csv + ",") + "\"time\":" + time +
           ",\"columns\":" + columns + extra + "}";
}

} // namespace

class TestCsvImporter : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void mapRoundTrip();
    void mapErrorsNameTheField_data();
    void mapErrorsNameTheField();
    void bomCrlfUnitsRolesAndTargets();
    void semicolonAndDecimalComma();
    void dateTimeAndEpochClocks();
    void badRowsChangeNothing_data();
    void badRowsChangeNothing();
    void cancelLeavesNothing();
    void intervalClock();
    void runColumnSplitsSessions();
    void severalFilesOneTransaction();
    void startFromFileName();

private:
    QString write(const QString &name, const QByteArray &bytes);
    QTemporaryDir m_dir;
    QString m_db;
};

QString TestCsvImporter::write(const QString &name, const QByteArray &bytes)
{
    return testfiles::write(m_dir.path(), name, bytes);
}

void TestCsvImporter::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_db = m_dir.filePath(QStringLiteral("csv.sqlite"));
}

void TestCsvImporter::mapRoundTrip()
{
    QFile shipped(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/maps/fl_thermal.json"));
    QVERIFY(shipped.open(QIODevice::ReadOnly));
    const CsvColumnMap m = CsvColumnMap::fromJson(shipped.readAll(), QStringLiteral("fl_thermal.json"));
    QCOMPARE(m.columns.size(), 22);
    QCOMPARE(m.time.column, QStringLiteral("time_s"));
    int targets = 0;
    for (const CsvColumnSpec &c : m.columns)
        targets += c.target ? 1 : 0;
    QCOMPARE(targets, 5);
    const CsvColumnMap back = mapOf(QJsonDocument(m.toJson()).toJson());
    QCOMPARE(back.toJson(), m.toJson());
    const CsvColumnMap semi = mapOf(mapJson(R"({"separator":"tab","decimal":",","encoding":"Latin-1","missing":["NA"]})",
                                            R"({"index":1,"format":"dd.MM.yyyy HH:mm","timezone":"+01:00"})",
                                            R"([{"index":2,"id":"x","kind":"position","unit":"m","scale":2,"offset":-1}])"));
    QCOMPARE(semi.separator, '\t');
    QCOMPARE(semi.encoding, QStringLiteral("latin1"));
    QCOMPARE(mapOf(QJsonDocument(semi.toJson()).toJson()).toJson(), semi.toJson());
}

void TestCsvImporter::mapErrorsNameTheField_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("message");
    const QByteArray time = R"({"column":"t"})";
    const QByteArray col = R"([{"column":"a","id":"a","kind":"temperature"}])";
    QTest::newRow("format") << QByteArray(R"({"format":"x","version":1})") << QStringLiteral("m.json: field 'format': must be \"driftlab-csv-map\"");
    QTest::newRow("version") << QByteArray(R"({"format":"driftlab-csv-map","version":2})")
                             << QStringLiteral("m.json: field 'version': unsupported version 2 (this DriftLab reads version 1)");
    QTest::newRow("json") << QByteArray("{\n\"format\":\n}") << QStringLiteral("m.json: line 3: invalid JSON: object is missing after a comma");
    QTest::newRow("typo") << mapJson(R"({"seperator":";"})", time, col)
                          << QStringLiteral("m.json: field 'csv.seperator': unknown key (expected one of: separator, decimal, encoding, "
                                            "skip_lines, header, missing, unmapped_columns)");
    QTest::newRow("separator") << mapJson(R"({"separator":"ab"})", time, col)
                               << QStringLiteral("m.json: field 'csv.separator': must be one ASCII punctuation character, \"tab\" or \"space\", got 'ab'");
    QTest::newRow("decimal = separator") << mapJson(R"({"decimal":","})", time, col)
                                         << QStringLiteral("m.json: field 'csv.decimal': the decimal mark and the separator are both ',' "
                                                           "(a decimal comma needs another separator, e.g. ';')");
    QTest::newRow("encoding") << mapJson(R"({"encoding":"ebcdic"})", time, col)
                              << QStringLiteral("m.json: field 'csv.encoding': unknown encoding 'ebcdic' (utf-8, latin1, windows-1252)");
    QTest::newRow("no time") << QByteArray(R"({"format":"driftlab-csv-map","version":1,"columns":[]})")
                             << QStringLiteral("m.json: field 'time': missing: say which column holds the time, or give the row \"interval\"");
    QTest::newRow("time unit") << mapJson({}, R"({"column":"t","unit":"days"})", col)
                               << QStringLiteral("m.json: field 'time.unit': unknown unit 'days' (s, ms, min, h, unix_s, unix_ms)");
    QTest::newRow("unit and format") << mapJson({}, R"({"column":"t","unit":"s","format":"iso8601"})", col)
                                     << QStringLiteral("m.json: field 'time': give either \"unit\" (numbers) or \"format\" (date-times), not both");
    QTest::newRow("timezone") << mapJson({}, R"({"column":"t","format":"iso8601","timezone":"CET"})", col)
                              << QStringLiteral("m.json: field 'time.timezone': must be \"UTC\", \"local\" or an offset like \"+01:00\", got 'CET'");
    QTest::newRow("both refs") << mapJson({}, R"({"column":"t","index":1})", col)
                               << QStringLiteral("m.json: field 'time': give exactly one of \"column\" (header text) and \"index\" (1-based column number)");
    QTest::newRow("no columns") << mapJson({}, time, "[]") << QStringLiteral("m.json: field 'columns': missing or empty: map at least one column to a channel");
    QTest::newRow("kind") << mapJson({}, time, R"([{"column":"a","id":"a","kind":"temp"}])")
                          << QStringLiteral("m.json: field 'columns[0].kind': unknown kind 'temp' (expected temperature, displacement, position, feed, other)");
    QTest::newRow("unit") << mapJson({}, time, R"([{"column":"a","id":"a","kind":"displacement","unit":"inch"}])")
                          << QStringLiteral("m.json: field 'columns[0].unit': unit 'inch' is not one for kind displacement (accepted: um, \u00b5m, nm, mm, m, \u03bcm)");
    QTest::newRow("target kind") << mapJson({}, time, R"([{"column":"a","id":"a","kind":"temperature","target":true}])")
                                 << QStringLiteral("m.json: field 'columns[0].target': only a displacement channel can be a target (kind is temperature)");
    QTest::newRow("duplicate id") << mapJson({}, time, R"([{"column":"a","id":"a"},{"column":"b","id":"a"}])")
                                  << QStringLiteral("m.json: field 'columns[1].id': duplicate channel id 'a'");
    QTest::newRow("bad id") << mapJson({}, time, R"([{"column":"a","id":"a,b"}])")
                            << QStringLiteral("m.json: field 'columns[0].id': invalid channel id 'a,b' (non-empty, no comma, quote or outer spaces, not time_s)");
    QTest::newRow("time mapped") << mapJson({}, time, R"([{"column":"t","id":"a"}])")
                                 << QStringLiteral("m.json: field 'columns[0]': column 't' is mapped twice (or is the time or run column)");
    QTest::newRow("scale 0") << mapJson({}, time, R"([{"column":"a","id":"a","scale":0}])")
                             << QStringLiteral("m.json: field 'columns[0].scale': must not be 0");
    QTest::newRow("started") << mapJson({}, time, col, R"(,"session":{"started":"yesterday"})")
                             << QStringLiteral("m.json: field 'session.started': 'yesterday' is not an ISO 8601 date-time");
    // The clock from the row number, the run column and the start from the file name.
    const QString interval = QStringLiteral("m.json: field 'time.interval': '%1' is not an interval: a positive number and a unit s, "
                                            "min or h, e.g. \"1 min\" or \"15 s\"");
    QTest::newRow("interval unit") << mapJson({}, R"({"interval":"1 minute"})", col) << interval.arg(QStringLiteral("1 minute"));
    QTest::newRow("interval zero") << mapJson({}, R"({"interval":"0 s"})", col) << interval.arg(QStringLiteral("0 s"));
    QTest::newRow("interval negative") << mapJson({}, R"({"interval":"-1 min"})", col) << interval.arg(QStringLiteral("-1 min"));
    QTest::newRow("interval number") << mapJson({}, R"({"interval":60})", col) << QStringLiteral("m.json: field 'time.interval': must be a string");
    QTest::newRow("interval and column") << mapJson({}, R"({"interval":"1 min","column":"t"})", col)
                                         << QStringLiteral("m.json: field 'time.column': not with \"interval\" (the time is the row number "
                                                           "times the interval; give one or the other)");
    QTest::newRow("run without column") << mapJson({}, time, col, R"(,"run":{})")
                                        << QStringLiteral("m.json: field 'run': give exactly one of \"column\" (header text) and \"index\" "
                                                          "(1-based column number)");
    QTest::newRow("run key") << mapJson({}, time, col, R"(,"run":{"column":"r","values":[1]})")
                             << QStringLiteral("m.json: field 'run.values': unknown key (expected one of: column, index)");
    QTest::newRow("run is time") << mapJson({}, time, col, R"(,"run":{"column":"t"})")
                                 << QStringLiteral("m.json: field 'run': column 't' is the time column");
    QTest::newRow("run mapped") << mapJson({}, time, col, R"(,"run":{"column":"a"})")
                                << QStringLiteral("m.json: field 'columns[0]': column 'a' is mapped twice (or is the time or run column)");
    QTest::newRow("start pattern") << mapJson({}, time, col, R"(,"session":{"started_from_file_name":"HHmmss"})")
                                   << QStringLiteral("m.json: field 'session.started_from_file_name': 'HHmmss' is not a date-time pattern: "
                                                     "it needs yyyy, MM and dd (and may hold HH, mm, ss, e.g. \"yyyyMMdd_HHmmss\")");
    QTest::newRow("two starts") << mapJson({}, time, col, R"(,"session":{"started":"2025-01-01T00:00:00Z","started_from_file_name":"yyyyMMdd"})")
                                << QStringLiteral("m.json: field 'session': give either \"started\" or \"started_from_file_name\", not both");
}

void TestCsvImporter::mapErrorsNameTheField()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, message);
    try {
        mapOf(json);
        QFAIL("accepted");
    } catch (const CsvError &e) {
        QCOMPARE(QString::fromUtf8(e.what()), message);
    }
}

void TestCsvImporter::bomCrlfUnitsRolesAndTargets()
{
    // A logger's export: BOM, CRLF, minutes, Kelvin, a probe in mm with a zero offset, an
    // empty cell and an "NA", a column the map leaves out.
    const QString csv = write(QStringLiteral("logger.csv"), "\xEF\xBB\xBFminutes,T_amb (K),probe [mm],rpm,comment\r\n"
                                                             "0,293.15,0.0100,0,start\r\n"
                                                             "0.5,293.65,0.0125,1000,\r\n"
                                                             "1.0,,0.0150,1000,x\r\n"
                                                             "1.5,294.65,NA,2000,\r\n");
    const CsvColumnMap map = mapOf(mapJson(R"({"missing":["","NA"]})", R"({"column":"minutes","unit":"min"})",
                                           R"J([{"column":"T_amb (K)","id":"T_amb","kind":"temperature","unit":"K","role":"ambient","sensor":"PT100"},
                                               {"column":"probe [mm]","id":"S1","kind":"displacement","unit":"mm","offset":-0.01,"target":true,"role":"screw_elongation"},
                                               {"column":"rpm","id":"spindle_rpm","unit":"rpm","role":"spindle","scale":0.001}])J",
                                           R"(,"session":{"name":"logger test","started":"2025-03-01T08:00:00Z","operator":"ana"},"machine":{"name":"mill"})"));
    SessionStore store(m_db);
    const CsvImportResult r = CsvImporter::importFile(store, csv, map);
    QVERIFY(r.sessionId > 0);
    QCOMPARE(r.rows, qint64(4));
    QCOMPARE(r.channels, 3);
    QCOMPARE(r.samples, qint64(3 + 3 + 4));
    QCOMPARE(r.ignoredColumns, QStringList{QStringLiteral("comment")});
    QCOMPARE(r.targets, QStringList{QStringLiteral("S1")});
    QCOMPARE(r.startedFrom, QStringLiteral("map"));
    const SessionInfo info = store.session(r.sessionId);
    QCOMPARE(info.name, QStringLiteral("logger test"));
    QCOMPARE(info.started, QStringLiteral("2025-03-01T08:00:00Z"));
    QCOMPARE(info.operatorName, QStringLiteral("ana"));
    QCOMPARE(info.machine.value(QStringLiteral("name")).toString(), QStringLiteral("mill"));
    QCOMPARE(info.manifest.value(QStringLiteral("targets")).toArray(), QJsonArray{QStringLiteral("S1")});
    QCOMPARE(info.manifest.value(QStringLiteral("imported_from")).toObject().value(QStringLiteral("file")).toString(), QStringLiteral("logger.csv"));
    const QVector<ChannelInfo> ch = store.channels(r.sessionId);
    QCOMPARE(ch.size(), 3);
    QCOMPARE(ch[0].key, QStringLiteral("T_amb"));
    QCOMPARE(ch[0].unit, QStringLiteral("degC"));
    QCOMPARE(ch[0].role, QStringLiteral("ambient"));
    QCOMPARE(ch[0].sensor, QStringLiteral("PT100"));
    QCOMPARE(ch[1].unit, QStringLiteral("um"));
    QCOMPARE(ch[2].kind, QStringLiteral("other"));
    QCOMPARE(ch[2].unit, QStringLiteral("rpm"));
    const SampleBlock t = store.samples(ch[0].id), s = store.samples(ch[1].id), n = store.samples(ch[2].id);
    QCOMPARE(t.t, (QVector<double>{0, 30, 90}));
    QVERIFY(std::fabs(t.v[0] - 20.0) < 1e-9 && std::fabs(t.v[1] - 20.5) < 1e-9 && std::fabs(t.v[2] - 21.5) < 1e-9);
    QCOMPARE(s.t, (QVector<double>{0, 30, 60}));
    QVERIFY(std::fabs(s.v[0]) < 1e-9 && std::fabs(s.v[1] - 2.5) < 1e-9 && std::fabs(s.v[2] - 5.0) < 1e-9); // (mm - 0.01) * 1000
    QCOMPARE(n.v, (QVector<double>{0, 1, 1, 2}));
}

void TestCsvImporter::semicolonAndDecimalComma()
{
    // A German spreadsheet export: ';', decimal commas, quoted header with the separator.
    const QString csv = write(QStringLiteral("de.csv"), "Zeit [s];\"Temp; Lager\";Weg\n"
                                                        "0;20,5;-1,25\n"
                                                        "10;21;1e-1\n"
                                                        "20;+21,75;0\n");
    const CsvColumnMap map = mapOf(mapJson(R"({"separator":";","decimal":","})", R"({"column":"Zeit [s]"})",
                                           R"([{"column":"Temp; Lager","id":"T2","kind":"temperature","role":"fixed_bearing"},
                                               {"index":3,"id":"S1","kind":"displacement"}])"));
    SessionStore store(m_db);
    CsvImportOptions options;
    options.started = QStringLiteral("2025-01-02T03:04:05Z");
    options.sessionName = QStringLiteral("override");
    const CsvImportResult r = CsvImporter::importFile(store, csv, map, options);
    QCOMPARE(store.session(r.sessionId).name, QStringLiteral("override"));
    QCOMPARE(store.session(r.sessionId).started, QStringLiteral("2025-01-02T03:04:05Z"));
    const QVector<ChannelInfo> ch = store.channels(r.sessionId);
    QCOMPARE(store.samples(ch[0].id).v, (QVector<double>{20.5, 21.0, 21.75}));
    QCOMPARE(store.samples(ch[1].id).v, (QVector<double>{-1.25, 0.1, 0.0}));
    QCOMPARE(store.samples(ch[1].id).t, (QVector<double>{0, 10, 20}));
}

void TestCsvImporter::dateTimeAndEpochClocks()
{
    SessionStore store(m_db);
    // Local time at UTC+01:00, a Latin-1 header ("°C" as one byte 0xB0).
    const QString csv = write(QStringLiteral("dt.csv"), "# logger 7\n# export\nDatum;T \xB0" "C\n"
                                                        "31.12.2024 23:59:30;20,0\n"
                                                        "01.01.2025 00:00:30;20,5\n");
    const CsvColumnMap map = mapOf(mapJson(R"({"separator":";","decimal":",","encoding":"latin1","skip_lines":2})",
                                           R"({"column":"Datum","format":"dd.MM.yyyy HH:mm:ss","timezone":"+01:00"})",
                                           "[{\"column\":\"T \u00b0C\",\"id\":\"T1\",\"kind\":\"temperature\",\"unit\":\"\u00b0C\"}]"));
    const CsvImportResult r = CsvImporter::importFile(store, csv, map);
    QCOMPARE(r.startedFrom, QStringLiteral("time column"));
    QCOMPARE(store.session(r.sessionId).started, QStringLiteral("2024-12-31T22:59:30Z"));
    QCOMPARE(store.samples(store.channels(r.sessionId)[0].id).t, (QVector<double>{0, 60}));

    const QString epoch = write(QStringLiteral("epoch.csv"), "ms,x\n1735689600250,1\n1735689601250,2\n");
    const CsvImportResult e = CsvImporter::importFile(
        store, epoch, mapOf(mapJson({}, R"({"column":"ms","unit":"unix_ms"})", R"([{"column":"x","id":"x"}])")));
    QCOMPARE(store.session(e.sessionId).started, QStringLiteral("2025-01-01T00:00:00.250Z"));
    QCOMPARE(store.samples(store.channels(e.sessionId)[0].id).t, (QVector<double>{0, 1}));
    QCOMPARE(e.lastTime_s, 1.0);
}

void TestCsvImporter::badRowsChangeNothing_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QByteArray>("csvBlock");
    QTest::addColumn<QString>("message");
    const QByteArray head = "time_s,T1,S1\n0,20,0\n1,20.1,0.5\n";
    QTest::newRow("non-numeric") << head + "2,abc,1\n" << QByteArray() << QStringLiteral("bad.csv: line 4, column 2 (T1): non-numeric value 'abc'");
    QTest::newRow("decimal comma hint") << head + "2,\"20,2\",1\n" << QByteArray()
                                        << QStringLiteral("bad.csv: line 4, column 2 (T1): non-numeric value '20,2' (a decimal comma? set csv.decimal to \",\")");
    QTest::newRow("point with decimal comma") << QByteArray("time_s;T1;S1\n0;20,5;0\n1;20.5;0\n") << QByteArray(R"({"separator":";","decimal":","})")
                                              << QStringLiteral("bad.csv: line 3, column 2 (T1): '20.5': a '.' in a number, but the map's decimal mark is ','");
    QTest::newRow("truncated") << head + "2,20.2\n" << QByteArray()
                               << QStringLiteral("bad.csv: line 4: expected 3 fields, found 2 (truncated or malformed line)");
    QTest::newRow("backwards") << head + "0.5,20.2,1\n" << QByteArray()
                               << QStringLiteral("bad.csv: line 4, column 1 (time_s): time goes backwards (0.5 s after 1 s)");
    QTest::newRow("empty time") << head + ",20.2,1\n" << QByteArray() << QStringLiteral("bad.csv: line 4, column 1 (time_s): empty time");
    QTest::newRow("out of range") << head + "2,1e999,1\n" << QByteArray()
                                  << QStringLiteral("bad.csv: line 4, column 2 (T1): value '1e999' out of range (not a finite number)");
    QTest::newRow("unterminated quote") << head + "2,\"20,1\n" << QByteArray()
                                        << QStringLiteral("bad.csv: line 4, column 2: quoted field not closed before the end of the file");
    QTest::newRow("missing column") << QByteArray("time_s,T1\n0,1\n") << QByteArray()
                                    << QStringLiteral("bad.csv: field 'columns[1]': no column 'S1' in the header (columns: time_s, T1)");
    QTest::newRow("header only") << QByteArray("time_s,T1,S1\r\n") << QByteArray() << QStringLiteral("bad.csv: no data rows after the header");
    QTest::newRow("empty") << QByteArray("\xEF\xBB\xBF") << QByteArray() << QStringLiteral("bad.csv: empty file: no header line");
    QTest::newRow("unmapped") << QByteArray("time_s,T1,S1,extra\n0,1,2,3\n") << QByteArray(R"({"unmapped_columns":"error"})")
                              << QStringLiteral("bad.csv: line 1, column 4 (extra): column not in the map (csv.unmapped_columns is \"error\")");
    QTest::newRow("latin1 header as utf-8") << QByteArray("time_s,T1,S1,T \xB0" "C\n0,1,2,3\n") << QByteArray()
                                            << QStringLiteral("bad.csv: line 1, column 4 (T \ufffdC): header text is not valid utf-8 (set csv.encoding, e.g. to latin1 or windows-1252)");
}

void TestCsvImporter::badRowsChangeNothing()
{
    QFETCH(QByteArray, text);
    QFETCH(QByteArray, csvBlock);
    QFETCH(QString, message);
    const QString csv = write(QStringLiteral("bad.csv"), text);
    const CsvColumnMap map = mapOf(mapJson(csvBlock, R"({"column":"time_s"})",
                                           R"([{"column":"T1","id":"T1","kind":"temperature"},{"column":"S1","id":"S1","kind":"displacement"}])"));
    {
        SessionStore store(m_db);
        if (store.sessions().isEmpty()) // something to keep
            CsvImporter::importFile(store, write(QStringLiteral("good.csv"), "time_s,T1,S1\n0,20,0\n"), map);
    }
    const QByteArray before = contentHash(m_db);
    {
        SessionStore store(m_db);
        const int sessions = store.sessions().size();
        try {
            CsvImporter::importFile(store, csv, map);
            QFAIL("accepted");
        } catch (const CsvError &e) {
            QCOMPARE(QString::fromUtf8(e.what()).replace(m_dir.path() + QLatin1Char('/'), QString()), message);
        }
        QCOMPARE(store.sessions().size(), sessions);
    }
    QCOMPARE(contentHash(m_db), before);
}

void TestCsvImporter::cancelLeavesNothing()
{
    // Big enough for several chunks (256 kB each); cancel after the second.
    QByteArray text = "time_s,T1,S1\n";
    for (int i = 0; i < 60000; ++i)
        text += QByteArray::number(i) + ",20." + QByteArray::number(i % 1000) + "," + QByteArray::number(i % 77) + "\n";
    const QString csv = write(QStringLiteral("big.csv"), text);
    const CsvColumnMap map = mapOf(mapJson({}, R"({"column":"time_s"})",
                                           R"([{"column":"T1","id":"T1","kind":"temperature"},{"column":"S1","id":"S1","kind":"displacement"}])"));
    const QByteArray before = contentHash(m_db);
    {
        SessionStore store(m_db);
        int calls = 0;
        qint64 last = 0;
        bool monotonic = true;
        CsvImportOptions options;
        options.progress = [&](qint64 done, qint64 total) {
            monotonic = monotonic && done > last && total == text.size();
            last = done;
            return ++calls < 2;
        };
        const CsvImportResult r = CsvImporter::importFile(store, csv, map, options);
        QVERIFY(r.cancelled);
        QCOMPARE(r.sessionId, qint64(0));
        QCOMPARE(calls, 2);
        QVERIFY(monotonic);
    }
    QCOMPARE(contentHash(m_db), before);
    // The same file without cancelling: every row.
    SessionStore store(m_db);
    const CsvImportResult r = CsvImporter::importFile(store, csv, map);
    QCOMPARE(r.rows, qint64(60000));
    QCOMPARE(store.sampleCount(store.channels(r.sessionId)[1].id), qint64(60000));
    QCOMPARE(store.samples(store.channels(r.sessionId)[0].id, 59999, 59999).v, QVector<double>{20.999});
}

void TestCsvImporter::intervalClock()
{
    // A logger writing one row a minute and no time column; the start from the option.
    const QString csv = write(QStringLiteral("interval.csv"), "T1;S1\n20,0;0,0\n20,5;1,5\n21,0;3,0\n");
    const CsvColumnMap map = mapOf(mapJson(R"({"separator":";","decimal":","})", R"({"interval":"1 min"})",
                                           R"([{"column":"T1","id":"T1","kind":"temperature"},{"column":"S1","id":"S1","kind":"displacement"}])"));
    QCOMPARE(map.time.interval_s, 60.0);
    QCOMPARE(mapOf(QJsonDocument(map.toJson()).toJson()).toJson(), map.toJson());
    SessionStore store(m_db);
    CsvImportOptions options;
    options.started = QStringLiteral("2025-04-01T06:00:00Z");
    const CsvImportResult r = CsvImporter::importFile(store, csv, map, options);
    QCOMPARE(r.sessions.size(), 1);
    QCOMPARE(r.rows, qint64(3));
    QCOMPARE(r.lastTime_s, 120.0);
    QCOMPARE(r.startedFrom, QStringLiteral("option"));
    QVERIFY(r.warnings.isEmpty());
    QCOMPARE(store.session(r.sessionId).started, QStringLiteral("2025-04-01T06:00:00Z"));
    const QVector<ChannelInfo> ch = store.channels(r.sessionId);
    QCOMPARE(ch.size(), 2);
    QCOMPARE(store.samples(ch[0].id).t, (QVector<double>{0, 60, 120}));
    QCOMPARE(store.samples(ch[1].id).v, (QVector<double>{0.0, 1.5, 3.0}));
    // Half an hour and 15 s.
    QCOMPARE(CsvColumnMap::parseInterval(QStringLiteral("0.5 h")), 1800.0);
    QCOMPARE(CsvColumnMap::parseInterval(QStringLiteral("15s")), 15.0);
    QCOMPARE(CsvColumnMap::parseInterval(QStringLiteral("1,5 min")), 0.0);
}

void TestCsvImporter::runColumnSplitsSessions()
{
    // Three runs in one file, each starting cold: date-time clock, so each run starts at its
    // own first row. Run "B" comes back after "C": its rows join its session.
    const QString csv = write(QStringLiteral("runs.csv"), "run,time,T1\n"
                                                          "A,2025-03-01 08:00:00,20.0\n"
                                                          "A,2025-03-01 08:01:00,20.5\n"
                                                          "B,2025-03-02 09:00:00,19.0\n"
                                                          "C,2025-03-03 10:00:00,18.0\n"
                                                          "B,2025-03-02 09:02:00,19.8\n");
    const CsvColumnMap map = mapOf(mapJson({}, R"({"column":"time","format":"yyyy-MM-dd HH:mm:ss","timezone":"+01:00"})",
                                           R"([{"column":"T1","id":"T1","kind":"temperature"}])", R"(,"run":{"column":"run"})"));
    SessionStore store(m_db);
    const int before = store.sessions().size();
    const CsvImportResult r = CsvImporter::importFile(store, csv, map);
    QCOMPARE(store.sessions().size(), before + 3);
    QCOMPARE(r.sessions.size(), 3);
    QCOMPARE(r.rows, qint64(5));
    const QStringList runs{QStringLiteral("A"), QStringLiteral("B"), QStringLiteral("C")};
    const QStringList starts{QStringLiteral("2025-03-01T07:00:00Z"), QStringLiteral("2025-03-02T08:00:00Z"),
                             QStringLiteral("2025-03-03T09:00:00Z")};
    const QVector<QVector<double>> times{{0, 60}, {0, 120}, {0}};
    const QVector<QVector<double>> values{{20.0, 20.5}, {19.0, 19.8}, {18.0}};
    for (int i = 0; i < 3; ++i) {
        const CsvImportedSession &s = r.sessions[i];
        QCOMPARE(s.run, runs[i]);
        QCOMPARE(s.startedFrom, QStringLiteral("time column"));
        const SessionInfo info = store.session(s.sessionId);
        QCOMPARE(info.name, QStringLiteral("runs run ") + runs[i]);
        QCOMPARE(info.started, starts[i]);
        QCOMPARE(info.manifest.value(QStringLiteral("imported_from")).toObject().value(QStringLiteral("run")).toString(), runs[i]);
        const QVector<ChannelInfo> ch = store.channels(s.sessionId);
        QCOMPARE(ch.size(), 1); // the run column is no channel
        QCOMPARE(store.samples(ch[0].id).t, times[i]);
        QCOMPARE(store.samples(ch[0].id).v, values[i]);
    }
    QVERIFY(r.warnings.isEmpty());
    // Time going backwards is checked within each run, and names the run; an empty run value
    // is refused.
    const QByteArray hash = contentHash(m_db);
    for (const QByteArray &bad : {QByteArray("run,time,T1\nA,2025-03-01 08:01:00,1\nB,2025-03-01 07:00:00,1\nA,2025-03-01 08:00:00,1\n"),
                                  QByteArray("run,time,T1\nA,2025-03-01 08:01:00,1\n ,2025-03-01 08:02:00,1\n")}) {
        try {
            SessionStore s2(m_db);
            CsvImporter::importFile(s2, write(QStringLiteral("badruns.csv"), bad), map);
            QFAIL("accepted");
        } catch (const CsvError &e) {
            const QString m = QString::fromUtf8(e.what());
            QVERIFY2(m.contains(QStringLiteral("line 4, column 2 (time): time goes backwards (-60 s after 0 s in run 'A')")) ||
                         m.contains(QStringLiteral("line 3, column 1 (run): empty run value")),
                     qPrintable(m));
        }
    }
    QCOMPARE(contentHash(m_db), hash);
    // An interval clock with runs: the row number counts within each run, and a run begins at
    // its first row's number times the interval after the given start.
    const QString relative = write(QStringLiteral("relruns.csv"), "Lauf;T1\n1;20\n1;21\n2;19\n2;19,5\n2;20\n");
    const CsvColumnMap rel = mapOf(mapJson(R"({"separator":";","decimal":","})", R"({"interval":"15 s"})",
                                           R"([{"column":"T1","id":"T1","kind":"temperature"}])", R"(,"run":{"column":"Lauf"})"));
    CsvImportOptions options;
    options.started = QStringLiteral("2025-05-05T05:05:05Z");
    const CsvImportResult rr = CsvImporter::importFile(store, relative, rel, options);
    QCOMPARE(rr.sessions.size(), 2);
    QCOMPARE(store.samples(store.channels(rr.sessions[1].sessionId)[0].id).t, (QVector<double>{0, 15, 30}));
    QCOMPARE(rr.sessions[1].lastTime_s, 30.0);
    QCOMPARE(rr.sessions[0].started, QStringLiteral("2025-05-05T05:05:05Z"));
    QCOMPARE(rr.sessions[1].started, QStringLiteral("2025-05-05T05:05:35Z"));
    QVERIFY(rr.warnings.isEmpty());
    // A seconds clock with runs: each run counts from its first time, and begins there.
    const CsvColumnMap secs = mapOf(mapJson(R"({"separator":";","decimal":","})", R"({"column":"t"})",
                                            R"([{"column":"T1","id":"T1","kind":"temperature"}])", R"(,"run":{"column":"Lauf"})"));
    const CsvImportResult cont = CsvImporter::importFile(
        store, write(QStringLiteral("continuous.csv"), "Lauf;t;T1\nA;100;20\nA;160;21\nB;220;19\nB;280;19,5\n"), secs, options);
    QCOMPARE(cont.sessions[1].started, QStringLiteral("2025-05-05T05:08:45Z")); // + 220 s
    QCOMPARE(store.samples(store.channels(cont.sessions[1].sessionId)[0].id).t, (QVector<double>{0, 60}));
    QCOMPARE(store.samples(store.channels(cont.sessions[0].sessionId)[0].id).t, (QVector<double>{0, 60}));
    QVERIFY(cont.warnings.isEmpty());
    // A clock restarting at 0 in every run: the runs share the start, and the result says so.
    const CsvImportResult restart = CsvImporter::importFile(
        store, write(QStringLiteral("restart.csv"), "Lauf;t;T1\nA;0;20\nA;60;21\nB;0;19\nB;60;19,5\n"), secs, options);
    QCOMPARE(restart.sessions[1].started, QStringLiteral("2025-05-05T05:05:05Z"));
    QCOMPARE(restart.warnings.size(), 1);
    QVERIFY2(restart.warnings[0].startsWith(QStringLiteral("2 sessions share the start 2025-05-05T05:05:05Z")), qPrintable(restart.warnings[0]));
}

void TestCsvImporter::severalFilesOneTransaction()
{
    const CsvColumnMap map = mapOf(mapJson({}, R"({"column":"t","unit":"min"})", R"([{"column":"T1","id":"T1","kind":"temperature"}])",
                                           R"(,"session":{"name":"warm-up"})"));
    const QString a = write(QStringLiteral("day1.csv"), "t,T1\n0,20\n1,21\n");
    const QString b = write(QStringLiteral("day2.csv"), "t,T1\n0,19\n1,20\n2,21\n");
    const QString bad = write(QStringLiteral("day3.csv"), "t,T1\n0,19\n1,x\n");
    const QByteArray hash = contentHash(m_db);
    {
        SessionStore store(m_db);
        try {
            CsvImporter::importFiles(store, {a, b, bad}, map);
            QFAIL("accepted");
        } catch (const CsvError &e) {
            QCOMPARE(QString::fromUtf8(e.what()).replace(m_dir.path() + QLatin1Char('/'), QString()),
                     QStringLiteral("day3.csv: line 3, column 2 (T1): non-numeric value 'x'"));
        }
    }
    QCOMPARE(contentHash(m_db), hash); // the two good files are not imported either
    SessionStore store(m_db);
    const CsvImportResult r = CsvImporter::importFiles(store, {a, b}, map);
    QCOMPARE(r.sessions.size(), 2);
    QCOMPARE(r.rows, qint64(5));
    QCOMPARE(store.session(r.sessions[0].sessionId).name, QStringLiteral("warm-up (day1)"));
    QCOMPARE(store.session(r.sessions[1].sessionId).name, QStringLiteral("warm-up (day2)"));
    QCOMPARE(r.sessions[1].lastTime_s, 120.0);
    // No start anywhere: each file's modification time, with a warning naming the file.
    QCOMPARE(r.sessions[0].startedFrom, QStringLiteral("file modification time"));
    QCOMPARE(r.warnings.filter(QStringLiteral("guessed from the file's modification time")).size(), 2);
    QVERIFY(r.warnings[0].startsWith(QStringLiteral("day1.csv: no session start")));
}

void TestCsvImporter::startFromFileName()
{
    const CsvColumnMap map = mapOf(mapJson({}, R"({"column":"t","timezone":"+01:00"})", R"([{"column":"T1","id":"T1","kind":"temperature"}])",
                                           R"(,"session":{"started_from_file_name":"yyyyMMdd_HHmm"})"));
    const QString good = write(QStringLiteral("spindle3_20250301_0815.csv"), "t,T1\n0,20\n");
    SessionStore store(m_db);
    const CsvImportResult r = CsvImporter::importFile(store, good, map);
    QCOMPARE(r.startedFrom, QStringLiteral("file name"));
    QCOMPARE(store.session(r.sessionId).started, QStringLiteral("2025-03-01T07:15:00Z"));
    QVERIFY(r.warnings.isEmpty());
    // A name without the pattern, or an impossible date: refused before anything is imported.
    const QByteArray hash = contentHash(m_db);
    for (const QString &name : {QStringLiteral("spindle3.csv"), QStringLiteral("log_20251301_0815.csv")}) {
        const QString bad = write(name, "t,T1\n0,20\n");
        try {
            SessionStore s2(m_db);
            CsvImporter::importFiles(s2, {good, bad}, map);
            QFAIL("accepted");
        } catch (const CsvError &e) {
            QCOMPARE(e.field(), QStringLiteral("session.started_from_file_name"));
            QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("holds no date-time 'yyyyMMdd_HHmm'")), e.what());
        }
    }
    QCOMPARE(contentHash(m_db), hash);
}

QTEST_GUILESS_MAIN(TestCsvImporter)
#include "tst_csvimporter.moc"

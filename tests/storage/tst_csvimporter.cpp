// Column maps and CSV import: map checks name the field; tables with a BOM, CRLF, ';' and
// decimal commas, date-time and epoch clocks, unit conversion, scale/offset and missing
// cells import to the values worked out here; every bad row is refused with file, line and
// column and leaves the database exactly as it was; a cancelled import leaves nothing.

#include "CsvColumnMap.h"
#include "CsvError.h"
#include "CsvImporter.h"
#include "SessionStore.h"

#include <QCryptographicHash>
#include <QJsonArray>
#include <QJsonDocument>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QSqlRecord>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {

// Content hash of every table (own connection), to prove a refused import changed nothing.
QByteArray contentHash(const QString &path)
{
    QByteArray h;
    {
        QSqlDatabase d = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("hash"));
        d.setDatabaseName(path);
        if (!d.open())
            qFatal("cannot open %s", qPrintable(path));
        QCryptographicHash hash(QCryptographicHash::Sha256);
        QSqlQuery tables(QStringLiteral("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name"), d);
        QStringList names;
        while (tables.next())
            names << tables.value(0).toString();
        for (const QString &t : names) {
            QSqlQuery q(QStringLiteral("SELECT * FROM %1 ORDER BY rowid").arg(t), d);
            while (q.next()) {
                for (int i = 0; i < q.record().count(); ++i)
                    hash.addData(q.value(i).toByteArray() + '\x1f');
            }
            hash.addData(t.toUtf8());
        }
        h = hash.result();
        d.close();
    }
    QSqlDatabase::removeDatabase(QStringLiteral("hash"));
    return h;
}

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

private:
    QString write(const QString &name, const QByteArray &bytes);
    QTemporaryDir m_dir;
    QString m_db;
};

QString TestCsvImporter::write(const QString &name, const QByteArray &bytes)
{
    const QString path = m_dir.filePath(name);
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size())
        qFatal("cannot write %s", qPrintable(path));
    return path;
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
                             << QStringLiteral("m.json: field 'time': missing: say which column holds the time");
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
                                 << QStringLiteral("m.json: field 'columns[0]': column 't' is mapped twice (or is the time column)");
    QTest::newRow("scale 0") << mapJson({}, time, R"([{"column":"a","id":"a","scale":0}])")
                             << QStringLiteral("m.json: field 'columns[0].scale': must not be 0");
    QTest::newRow("started") << mapJson({}, time, col, R"(,"session":{"started":"yesterday"})")
                             << QStringLiteral("m.json: field 'session.started': 'yesterday' is not an ISO 8601 date-time");
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

QTEST_GUILESS_MAIN(TestCsvImporter)
#include "tst_csvimporter.moc"

// `driftlab-cli import-csv` as a user runs it: the real 46-hour FL_THERMAL spindle test
// (../shared/extdata/fl_thermal, MIT licence; skipped without ../shared) through the shipped
// map resources/maps/fl_thermal.json, and the awkward files a lab's loggers write (BOM, CRLF,
// ';' with decimal commas), and bad input refused with exit code 2, file, line and column,
// and nothing imported.

#include "SessionStore.h"

#include <QDir>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include "../support/CliRunner.h"
#include "../support/TestFiles.h"

#include <cmath>
#include <cstdio>

using namespace driftlab;

class TestCsvImportCli : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void flThermalThroughTheShippedMap();
    void loggerQuirks();
    void badInputExitsTwoAndImportsNothing_data();
    void badInputExitsTwoAndImportsNothing();
    void usageErrorsExitTwo();
    void guessedMapImports();
    void severalFilesRunsAndInterval();
    void utf8Messages_data();
    void utf8Messages();

private:
    using Result = clirunner::Result;
    Result run(const QStringList &args) { return clirunner::run(args, m_dir.filePath(QStringLiteral("data"))); }
    QString write(const QString &name, const QByteArray &bytes);
    QTemporaryDir m_dir;
    const QString m_map = QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/maps/fl_thermal.json");
};


QString TestCsvImportCli::write(const QString &name, const QByteArray &bytes)
{
    return testfiles::write(m_dir.path(), name, bytes);
}

void TestCsvImportCli::initTestCase()
{
    QVERIFY(m_dir.isValid());
    const Result help = run({QStringLiteral("import-csv"), QStringLiteral("--help")});
    QCOMPARE(help.code, 0);
    QVERIFY(help.out.contains("driftlab-cli import-csv"));
    QVERIFY(help.out.contains("--map"));
}

void TestCsvImportCli::flThermalThroughTheShippedMap()
{
    const QString source = QStringLiteral(DRIFTLAB_SHARED_DIR "/extdata/fl_thermal/fl_thermal_data.csv");
    if (!QFileInfo::exists(source))
        QSKIP("../shared/extdata is not beside this checkout");
    // The source read independently: header, first and last rows.
    QFile in(source);
    QVERIFY(in.open(QIODevice::ReadOnly | QIODevice::Text));
    const QList<QByteArray> header = in.readLine().trimmed().split(',');
    QList<QByteArray> first, last;
    int rows = 0;
    while (!in.atEnd()) {
        const QByteArray line = in.readLine().trimmed();
        if (line.isEmpty())
            continue;
        (rows++ == 0 ? first : last) = line.split(',');
    }
    QCOMPARE(rows, 11115);

    const QString db = m_dir.filePath(QStringLiteral("fl.sqlite"));
    const Result r = run({QStringLiteral("import-csv"), source, QStringLiteral("--map"), m_map, QStringLiteral("--db"), db,
                          QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(j.value(QStringLiteral("rows")).toInt(), 11115);
    QCOMPARE(j.value(QStringLiteral("channels")).toInt(), 22);
    QCOMPARE(j.value(QStringLiteral("samples")).toDouble(), 22.0 * 11115);
    QCOMPARE(j.value(QStringLiteral("duration_s")).toDouble(), 166710.0);
    QCOMPARE(j.value(QStringLiteral("started")).toString(), QStringLiteral("2024-05-23T00:00:00Z"));
    QCOMPARE(j.value(QStringLiteral("ignored_columns")).toArray().size(), 0);
    QCOMPARE(j.value(QStringLiteral("targets")).toArray(),
             (QJsonArray{QStringLiteral("ch1"), QStringLiteral("ch2"), QStringLiteral("ch3"), QStringLiteral("ch4"), QStringLiteral("ch5")}));

    // The agreed channel ids, kinds, units and roles, and values equal to the source's.
    SessionStore store(db);
    const qint64 id = j.value(QStringLiteral("session")).toInt();
    const QVector<ChannelInfo> channels = store.channels(id);
    QCOMPARE(channels.size(), 22);
    int temperatures = 0, displacements = 0;
    for (const ChannelInfo &c : channels) {
        QString column;
        if (c.key == QLatin1String("spindle_rpm")) {
            QCOMPARE(c.kind, QStringLiteral("other"));
            QCOMPARE(c.role, QStringLiteral("spindle"));
            QCOMPARE(c.unit, QStringLiteral("rpm"));
            column = c.key;
        } else if (c.key.startsWith(QLatin1Char('t'))) {
            QCOMPARE(c.kind, QStringLiteral("temperature"));
            QCOMPARE(c.unit, QStringLiteral("degC"));
            const int n = c.key.midRef(1).toInt();
            QVERIFY(n >= 1 && n <= 16);
            column = c.key + QStringLiteral("_C");
            ++temperatures;
        } else {
            QVERIFY2(c.key.startsWith(QLatin1String("ch")), qPrintable(c.key));
            QCOMPARE(c.kind, QStringLiteral("displacement"));
            QCOMPARE(c.unit, QStringLiteral("um"));
            column = c.key + QStringLiteral("_um");
            ++displacements;
        }
        const int col = header.indexOf(column.toUtf8());
        QVERIFY2(col > 0, qPrintable(column));
        const SampleBlock s = store.samples(c.id);
        QCOMPARE(s.t.size(), 11115);
        QCOMPARE(s.t.front(), 0.0);
        QCOMPARE(s.t.back(), 166710.0);
        QCOMPARE(s.v.front(), first[col].toDouble());
        QCOMPARE(s.v.back(), last[col].toDouble());
    }
    QCOMPARE(temperatures, 16);
    QCOMPARE(displacements, 5);
    const QJsonObject manifest = store.session(id).manifest;
    QCOMPARE(manifest.value(QStringLiteral("targets")).toArray().size(), 5);
    QCOMPARE(manifest.value(QStringLiteral("imported_from")).toObject().value(QStringLiteral("file")).toString(),
             QStringLiteral("fl_thermal_data.csv"));
}

void TestCsvImportCli::loggerQuirks()
{
    const QString db = m_dir.filePath(QStringLiteral("quirks.sqlite"));
    // BOM + CRLF with the shipped map's dialect (the map's columns subset).
    const QString crlf = write(QStringLiteral("crlf.csv"), "\xEF\xBB\xBFtime_s,T\r\n0,20.5\r\n15,20.75\r\n");
    const QString map1 = write(QStringLiteral("crlf.json"), R"({"format":"driftlab-csv-map","version":1,"time":{"column":"time_s"},
        "session":{"started":"2025-01-01T00:00:00Z"},"columns":[{"column":"T","id":"T1","kind":"temperature"}]})");
    Result r = run({QStringLiteral("import-csv"), crlf, QStringLiteral("--map"), map1, QStringLiteral("--db"), db, QStringLiteral("--name"),
                    QStringLiteral("crlf test")});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY2(r.out.startsWith("session 1 in "), r.out.constData()); // like `record`
    QVERIFY(r.out.contains("2 rows"));
    // The span as h:mm:ss like every time on screen (issue 33; "over 0.00 h" until 2026-11-28).
    QVERIFY2(r.out.contains("samples over 0:00:15"), r.out.constData());
    QCOMPARE(SessionStore(db).session(1).name, QStringLiteral("crlf test"));
    // ';' and decimal commas, minutes, a displacement in mm marked as the target.
    const QString semi = write(QStringLiteral("semi.csv"), "t [min];X-Sonde [mm]\n0;0,001\n1,5;0,0035\n");
    const QString map2 = write(QStringLiteral("semi.json"), R"({"format":"driftlab-csv-map","version":1,
        "csv":{"separator":";","decimal":","},"time":{"column":"t [min]","unit":"min"},
        "columns":[{"column":"X-Sonde [mm]","id":"S1","kind":"displacement","unit":"mm","target":true}]})");
    r = run({QStringLiteral("import-csv"), semi, QStringLiteral("--map"), map2, QStringLiteral("--db"), db, QStringLiteral("--started"),
             QStringLiteral("2025-02-03T10:00:00Z"), QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(j.value(QStringLiteral("targets")).toArray(), QJsonArray{QStringLiteral("S1")});
    QCOMPARE(j.value(QStringLiteral("started_from")).toString(), QStringLiteral("option"));
    SessionStore store(db);
    const SampleBlock s = store.samples(store.channels(2).front().id);
    QCOMPARE(s.t, (QVector<double>{0.0, 90.0}));
    QVERIFY(std::fabs(s.v[0] - 1.0) < 1e-9 && std::fabs(s.v[1] - 3.5) < 1e-9);
    QCOMPARE(store.session(2).started, QStringLiteral("2025-02-03T10:00:00Z"));
}

void TestCsvImportCli::badInputExitsTwoAndImportsNothing_data()
{
    QTest::addColumn<QByteArray>("csv");
    QTest::addColumn<QByteArray>("map");
    QTest::addColumn<QString>("message");
    const QByteArray map = R"({"format":"driftlab-csv-map","version":1,"time":{"column":"time_s"},
        "columns":[{"column":"T1","id":"T1","kind":"temperature"},{"column":"S1","id":"S1","kind":"displacement","target":true}]})";
    QTest::newRow("bad cell") << QByteArray("time_s,T1,S1\r\n0,20,0\r\n15,2O.1,0.5\r\n") << map
                              << QStringLiteral("bad.csv: line 3, column 2 (T1): non-numeric value '2O.1' (nothing imported)");
    QTest::newRow("semicolon without the map saying so") << QByteArray("time_s;T1;S1\n0;20,5;0\n") << map
                                                         << QStringLiteral("bad.csv: field 'time': no column 'time_s' in the header (columns: time_s;T1;S1; the header is one column "
                                                                            "holding ';': set csv.separator)");
    QTest::newRow("map error") << QByteArray("time_s,T1,S1\n0,20,0\n")
                               << QByteArray(R"({"format":"driftlab-csv-map","version":1,"time":{"column":"time_s"},"columns":[{"column":"T1","id":"T1","kind":"heat"}]})")
                               << QStringLiteral("map.json: field 'columns[0].kind': unknown kind 'heat'");
}

void TestCsvImportCli::badInputExitsTwoAndImportsNothing()
{
    QFETCH(QByteArray, csv);
    QFETCH(QByteArray, map);
    QFETCH(QString, message);
    const QString db = m_dir.filePath(QStringLiteral("bad.sqlite"));
    const QString file = write(QStringLiteral("bad.csv"), csv);
    const QString mapFile = write(QStringLiteral("map.json"), map);
    const Result r = run({QStringLiteral("import-csv"), file, QStringLiteral("--map"), mapFile, QStringLiteral("--db"), db});
    QCOMPARE(r.code, 2);
    QVERIFY2(QString::fromUtf8(r.err).replace(m_dir.path() + QLatin1Char('/'), QString()).contains(message), r.err.constData());
    QVERIFY(r.out.isEmpty());
    if (QFileInfo::exists(db))
        QCOMPARE(SessionStore(db).sessions().size(), 0);
}

void TestCsvImportCli::usageErrorsExitTwo()
{
    const QString file = write(QStringLiteral("ok.csv"), "time_s,T1\n0,20\n");
    QCOMPARE(run({QStringLiteral("import-csv"), file}).code, 2); // no --map
    QCOMPARE(run({QStringLiteral("import-csv"), QStringLiteral("/nonexistent.csv"), QStringLiteral("--map"), m_map}).code, 2);
    const Result r = run({QStringLiteral("import-csv"), file, QStringLiteral("--map"), m_dir.filePath(QStringLiteral("missing.json"))});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("missing.json: cannot open the column map"), r.err.constData());
}

// A table nobody has mapped: --guess-map writes the map the import dialog would start from
// (German logger: preamble, ';', decimal commas, Latin-1 units, a date-time column), imports
// nothing, and the map then imports every row with the values the file holds.
void TestCsvImportCli::guessedMapImports()
{
    const QString source = QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/csv/german_logger.csv");
    const QString map = m_dir.filePath(QStringLiteral("guessed.json"));
    const QString db = m_dir.filePath(QStringLiteral("guessed.sqlite"));
    const auto slurp = [](const QString &path) {
        QFile f(path);
        return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
    };
    Result r = run({QStringLiteral("import-csv"), source, QStringLiteral("--guess-map"), map, QStringLiteral("--db"), db});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY(!QFileInfo::exists(db)); // nothing imported, no database made
    QVERIFY2(r.err.contains("separator ';', decimal ','"), r.err.constData());
    QVERIFY2(r.err.contains("time: 'Datum' (dd.MM.yyyy HH:mm:ss)"), r.err.constData());
    const QString told = QString::fromUtf8(r.err);
    QVERIFY2(told.contains(QStringLiteral("'T Lager [°C]' -> T_Lager: kind temperature, unit °C")), r.err.constData());
    QVERIFY2(told.contains(QStringLiteral("'Weg X [µm]' -> Weg_X: kind displacement, unit µm")), r.err.constData());
    QVERIFY2(r.err.contains("--map " + map.toUtf8()), r.err.constData());
    const QJsonObject written = QJsonDocument::fromJson(slurp(map)).object();
    QCOMPARE(written.value(QStringLiteral("format")).toString(), QStringLiteral("driftlab-csv-map"));

    // Never overwritten silently; --map and --guess-map together is bad usage; no map at all
    // names the way to one.
    const QByteArray before = slurp(map);
    r = run({QStringLiteral("import-csv"), source, QStringLiteral("--guess-map"), map});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("already exists"), r.err.constData());
    QCOMPARE(slurp(map), before);
    QCOMPARE(run({QStringLiteral("import-csv"), source, QStringLiteral("--guess-map"), map, QStringLiteral("--map"), map}).code, 2);
    r = run({QStringLiteral("import-csv"), source});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--guess-map MAP.json"), r.err.constData());

    // The guessed map imports the file: the rows and the first values as the file writes them
    // (21,50 degC bearing, 0,0 um at 08:00:00).
    r = run({QStringLiteral("import-csv"), source, QStringLiteral("--map"), map, QStringLiteral("--db"), db, QStringLiteral("--json"),
             QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(j.value(QStringLiteral("rows")).toInt(), 12);
    SessionStore store(db);
    bool sawBearing = false;
    for (const ChannelInfo &c : store.channels(1)) {
        if (c.key != QLatin1String("T_Lager"))
            continue;
        sawBearing = true;
        const SampleBlock s = store.samples(c.id);
        QCOMPARE(s.t.front(), 0.0);
        QVERIFY(std::fabs(s.v.front() - 21.5) < 1e-9);
    }
    QVERIFY(sawBearing);
}

// Issue 32 item 5: a logger with no time column (one row a minute), a run column splitting a
// file into sessions, several files in one call, and a bad row in the last file refusing the
// whole call.
void TestCsvImportCli::severalFilesRunsAndInterval()
{
    const QString map = write(QStringLiteral("runs.json"), R"({"format":"driftlab-csv-map","version":1,
        "csv":{"separator":";","decimal":","},"time":{"interval":"1 min"},"run":{"column":"Lauf"},
        "columns":[{"column":"T1","id":"T1","kind":"temperature"},{"column":"S1","id":"S1","kind":"displacement","target":true}]})");
    const QString a = write(QStringLiteral("campaign_a.csv"), "Lauf;T1;S1\n1;20;0\n1;21;1,5\n2;19;0\n2;19,5;0,5\n2;20;1\n");
    const QString b = write(QStringLiteral("campaign_b.csv"), "Lauf;T1;S1\n7;22;0\n7;23;2\n");
    const QString bad = write(QStringLiteral("campaign_c.csv"), "Lauf;T1;S1\n8;22;0\n8;2x;2\n");
    const QString db = m_dir.filePath(QStringLiteral("runs.sqlite"));
    Result r = run({QStringLiteral("import-csv"), a, b, bad, QStringLiteral("--map"), map, QStringLiteral("--db"), db});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("campaign_c.csv: line 3, column 2 (T1): non-numeric value '2x' (nothing imported)"), r.err.constData());
    if (QFileInfo::exists(db))
        QCOMPARE(SessionStore(db).sessions().size(), 0);

    r = run({QStringLiteral("import-csv"), a, b, QStringLiteral("--map"), map, QStringLiteral("--db"), db, QStringLiteral("--json"),
             QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    // No start anywhere: guessed, and said so on standard error.
    QVERIFY2(r.err.contains("warning: campaign_a.csv: no session start in the table, the map or an option: guessed from the file's "
                            "modification time"),
             r.err.constData());
    QVERIFY2(r.err.contains("warning: campaign_b.csv: no session start"), r.err.constData());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object();
    const QJsonArray sessions = j.value(QStringLiteral("sessions")).toArray();
    QCOMPARE(sessions.size(), 3);
    QCOMPARE(j.value(QStringLiteral("rows")).toInt(), 7);
    QVERIFY(j.value(QStringLiteral("warnings")).toArray().size() >= 2);
    const QStringList runs{QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("7")};
    const QVector<double> durations{60, 120, 60};
    SessionStore store(db);
    QCOMPARE(store.sessions().size(), 3);
    for (int i = 0; i < 3; ++i) {
        const QJsonObject s = sessions[i].toObject();
        QCOMPARE(s.value(QStringLiteral("run")).toString(), runs[i]);
        QCOMPARE(s.value(QStringLiteral("duration_s")).toDouble(), durations[i]);
        QCOMPARE(s.value(QStringLiteral("started_from")).toString(), QStringLiteral("file modification time"));
        if (i == 1) // run 2 begins at the file's third row: two minutes after run 1
            QCOMPARE(QDateTime::fromString(s.value(QStringLiteral("started")).toString(), Qt::ISODate)
                         .secsTo(QDateTime::fromString(sessions[0].toObject().value(QStringLiteral("started")).toString(), Qt::ISODate)),
                     qint64(-120));
        QCOMPARE(store.session(s.value(QStringLiteral("session")).toInt()).name,
                 QStringLiteral("campaign_%1 run %2").arg(i < 2 ? QStringLiteral("a") : QStringLiteral("b"), runs[i]));
    }
    const qint64 second = sessions[1].toObject().value(QStringLiteral("session")).toInt();
    QCOMPARE(store.samples(store.channels(second)[1].id).v, (QVector<double>{0.0, 0.5, 1.0}));
    QCOMPARE(store.samples(store.channels(second)[1].id).t, (QVector<double>{0, 60, 120}));

    // --start (alias of --started) gives every session that start: no guess, one warning.
    const QString db2 = m_dir.filePath(QStringLiteral("runs2.sqlite"));
    r = run({QStringLiteral("import-csv"), b, QStringLiteral("--map"), map, QStringLiteral("--db"), db2, QStringLiteral("--start"),
             QStringLiteral("2025-03-01T08:00:00+01:00")});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY2(!r.err.contains("warning"), r.err.constData());
    QVERIFY2(r.out.contains("session 1 in ") && r.out.contains("2 rows") && r.out.contains("(run 7)"), r.out.constData());
    QCOMPARE(SessionStore(db2).session(1).started, QStringLiteral("2025-03-01T07:00:00Z"));
    // A bad --started is bad usage, decided before any work.
    r = run({QStringLiteral("import-csv"), b, QStringLiteral("--map"), map, QStringLiteral("--db"), db2, QStringLiteral("--started"),
             QStringLiteral("yesterday")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--started 'yesterday' is not an ISO 8601 date-time"), r.err.constData());
    QCOMPARE(SessionStore(db2).sessions().size(), 1);
}

// Every CLI message is UTF-8 whatever the locale: a map naming "T [°C]" against a header with
// "Weg [µm]", from a file whose name holds "ü". Before the fix, e.what() went through
// QTextStream's const char * operator (Latin-1): "Â°C", "Âµm".
void TestCsvImportCli::utf8Messages_data()
{
    QTest::addColumn<QString>("lang");
    QTest::newRow("C") << "C";
    QTest::newRow("C.UTF-8") << "C.UTF-8";
}

void TestCsvImportCli::utf8Messages()
{
    QFETCH(QString, lang);
    const QByteArray name = "Pr\xC3\xBC" "fstand.csv";
    {
        // The name's bytes as UTF-8, whatever this test's own locale.
        const QByteArray full = QFile::encodeName(m_dir.path()) + '/' + name;
        FILE *f = std::fopen(full.constData(), "wb");
        QVERIFY(f);
        const QByteArray text = "time_s,Weg [\xC2\xB5m]\n0,1\n";
        QCOMPARE(std::fwrite(text.constData(), 1, static_cast<size_t>(text.size()), f), static_cast<size_t>(text.size()));
        std::fclose(f);
    }
    const QString map = write(QStringLiteral("utf8.json"), "{\"format\":\"driftlab-csv-map\",\"version\":1,\"time\":{\"column\":\"time_s\"},"
                                                           "\"columns\":[{\"column\":\"T [\xC2\xB0" "C]\",\"id\":\"T\",\"kind\":\"temperature\"}]}");
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    for (const QString &k : env.keys()) {
        if (k.startsWith(QLatin1String("LC_")) || k == QLatin1String("LANG") || k == QLatin1String("LANGUAGE"))
            env.remove(k);
    }
    env.insert(QStringLiteral("LANG"), lang);
    env.insert(QStringLiteral("LC_ALL"), lang);
    env.insert(QStringLiteral("XDG_DATA_HOME"), m_dir.filePath(QStringLiteral("data")));
    p.setProcessEnvironment(env);
    p.setWorkingDirectory(m_dir.path());
    p.start(QStringLiteral(DRIFTLAB_CLI), {QStringLiteral("import-csv"), QString::fromUtf8(name), QStringLiteral("--map"), map,
                                           QStringLiteral("--db"), m_dir.filePath(QStringLiteral("utf8.sqlite"))});
    QVERIFY(p.waitForFinished(60000));
    const QByteArray err = p.readAllStandardError();
    QCOMPARE(p.exitCode(), 2);
    QVERIFY2(err.contains("Pr\xC3\xBC" "fstand.csv: field 'columns[0]': no column 'T [\xC2\xB0" "C]' in the header (columns: time_s, Weg [\xC2\xB5m])"),
             err.constData());
    QVERIFY2(!err.contains("\xC3\x82"), err.constData()); // no "Â": not encoded twice
    QVERIFY2(err.contains("\xC2\xB0") && err.contains("\xC2\xB5"), err.constData());
}

QTEST_GUILESS_MAIN(TestCsvImportCli)
#include "tst_csvimportcli.moc"

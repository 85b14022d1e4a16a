// The streaming CSV tokenizer: line ends, BOM, quotes, line numbers, chunk-size invariance
// and the inputs it refuses (each naming line and column).

#include "CsvReader.h"

#include <QtTest>

#include <random>

using namespace driftlab;

namespace {

QString flat(const QVector<CsvRecord> &records)
{
    QStringList out;
    for (const CsvRecord &r : records) {
        QStringList f;
        for (const QByteArray &b : r.fields)
            f << QString::fromUtf8(b);
        out << QStringLiteral("%1:%2").arg(r.line).arg(f.join(QLatin1Char('|')));
    }
    return out.join(QLatin1Char('/'));
}

QString errorOf(const QByteArray &text, char sep = ',', int maxBytes = CsvReader::kDefaultMaxRecordBytes)
{
    try {
        CsvReader reader(QStringLiteral("t.csv"), sep, maxBytes);
        const CsvReader::Sink sink = [](const CsvRecord &) {};
        reader.feed(text, sink);
        reader.finish(sink);
    } catch (const CsvError &e) {
        return QString::fromUtf8(e.what());
    }
    return QString();
}

} // namespace

class TestCsvReader : public QObject {
    Q_OBJECT
private slots:
    void lineEndsAndEmptyLines();
    void byteOrderMark();
    void quotedFields();
    void separators();
    void chunkSizeDoesNotMatter();
    void refusesWhatIsNotATable_data();
    void refusesWhatIsNotATable();
};

void TestCsvReader::lineEndsAndEmptyLines()
{
    QCOMPARE(flat(CsvReader::parse("a,b\n1,2\n", QStringLiteral("t"))), QStringLiteral("1:a|b/2:1|2"));
    QCOMPARE(flat(CsvReader::parse("a,b\r\n1,2\r\n", QStringLiteral("t"))), QStringLiteral("1:a|b/2:1|2"));
    QCOMPARE(flat(CsvReader::parse("a,b\r1,2\r", QStringLiteral("t"))), QStringLiteral("1:a|b/2:1|2"));
    // No final line break; empty lines (LF, CRLF, CR) yield nothing but count.
    QCOMPARE(flat(CsvReader::parse("a,b\n\r\n\r\n1,2\n\n3,", QStringLiteral("t"))), QStringLiteral("1:a|b/4:1|2/6:3|"));
    // Empty trailing fields are fields.
    QCOMPARE(flat(CsvReader::parse(",\n,,\n", QStringLiteral("t"))), QStringLiteral("1:|/2:||"));
    QVERIFY(CsvReader::parse("", QStringLiteral("t")).isEmpty());
    QVERIFY(CsvReader::parse("\n\r\n", QStringLiteral("t")).isEmpty());
}

void TestCsvReader::byteOrderMark()
{
    QCOMPARE(flat(CsvReader::parse("\xEF\xBB\xBFtime_s,x\r\n0,1\r\n", QStringLiteral("t"))), QStringLiteral("1:time_s|x/2:0|1"));
    // Bytes that only start like a BOM are data.
    QCOMPARE(CsvReader::parse("\xEF\xBBz,1", QStringLiteral("t")).front().fields.front(), QByteArray("\xEF\xBBz"));
    QCOMPARE(CsvReader::parse("\xEF\xBB", QStringLiteral("t")).front().fields.front(), QByteArray("\xEF\xBB"));
    // Only at the start of the file.
    QCOMPARE(CsvReader::parse("a\n\xEF\xBB\xBF", QStringLiteral("t")).back().fields.front(), QByteArray("\xEF\xBB\xBF"));
}

void TestCsvReader::quotedFields()
{
    QCOMPARE(flat(CsvReader::parse("\"a,b\",\"say \"\"hi\"\"\", \"c\" ,d\"e\n", QStringLiteral("t"))),
             QStringLiteral("1:a,b|say \"hi\"|c|d\"e"));
    // A quoted line break (CRLF reads as LF) belongs to the field; the record keeps its first line.
    QCOMPARE(flat(CsvReader::parse("x,\"two\r\nlines\"\n1,2\n", QStringLiteral("t"))), QStringLiteral("1:x|two\nlines/3:1|2"));
    QCOMPARE(flat(CsvReader::parse("\"\"\n", QStringLiteral("t"))), QStringLiteral("1:"));
}

void TestCsvReader::separators()
{
    QCOMPARE(flat(CsvReader::parse("a;b\n1,5;2,25\n", QStringLiteral("t"), ';')), QStringLiteral("1:a|b/2:1,5|2,25"));
    QCOMPARE(flat(CsvReader::parse("a\tb\n1\t\"2\t3\"\n", QStringLiteral("t"), '\t')), QStringLiteral("1:a|b/2:1|2\t3"));
    QVERIFY_EXCEPTION_THROWN(CsvReader(QStringLiteral("t"), '"'), CsvError);
}

void TestCsvReader::chunkSizeDoesNotMatter()
{
    const QByteArray text = "\xEF\xBB\xBFtime,\"name, quoted\",v\r\n"
                            "0,\"multi\r\nline\",1.5\r\n\r\n"
                            "1,\"q\"\"q\",2\r"
                            "2,plain,3\n"
                            "3,,\n"
                            "4,\"end\",5";
    const QString whole = flat(CsvReader::parse(text, QStringLiteral("t")));
    QCOMPARE(whole, QStringLiteral("1:time|name, quoted|v/2:0|multi\nline|1.5/5:1|q\"q|2/6:2|plain|3/7:3||/8:4|end|5"));
    std::mt19937 rng(3);
    for (int trial = 0; trial < 50; ++trial) {
        QVector<CsvRecord> out;
        CsvReader reader(QStringLiteral("t"));
        const CsvReader::Sink sink = [&out](const CsvRecord &r) { out.push_back(r); };
        int pos = 0;
        while (pos < text.size()) {
            const int n = trial == 0 ? 1 : std::uniform_int_distribution<int>(1, 9)(rng);
            reader.feed(text.constData() + pos, std::min(n, text.size() - pos), sink);
            pos += n;
        }
        reader.finish(sink);
        QCOMPARE(flat(out), whole);
        QCOMPARE(reader.bytesConsumed(), qint64(text.size()));
    }
}

void TestCsvReader::refusesWhatIsNotATable_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<int>("maxBytes");
    QTest::addColumn<QString>("message");
    QTest::newRow("unterminated quote") << QByteArray("a,b\n1,\"open\n2,3\n") << 1000
                                        << QStringLiteral("t.csv: line 2, column 2: quoted field not closed before the end of the file");
    QTest::newRow("text after closing quote") << QByteArray("a,b\n\"x\"y,2\n") << 1000
                                              << QStringLiteral("t.csv: line 2, column 1: unexpected 'y' after a closing quote");
    QTest::newRow("UTF-16 LE") << QByteArray("\xFF\xFEt\0i\0", 6) << 1000
                               << QStringLiteral("t.csv: line 1: UTF-16 or UTF-32 text (byte-order mark): save the file as UTF-8 or an 8-bit encoding");
    QTest::newRow("NUL byte") << QByteArray("a,b\n1,\0", 7) << 1000
                              << QStringLiteral("t.csv: line 2, column 2: NUL byte: not a text table (a UTF-16 file must be saved as UTF-8)");
    QTest::newRow("record too long") << QByteArray("a,b\n") + QByteArray(200, 'x') << 100
                                     << QStringLiteral("t.csv: line 2, column 1: record longer than 100 bytes: not a text table, or a quote left open");
}

void TestCsvReader::refusesWhatIsNotATable()
{
    QFETCH(QByteArray, text);
    QFETCH(int, maxBytes);
    QFETCH(QString, message);
    QCOMPARE(errorOf(text, ',', maxBytes), message);
}

QTEST_APPLESS_MAIN(TestCsvReader)
#include "tst_csvreader.moc"

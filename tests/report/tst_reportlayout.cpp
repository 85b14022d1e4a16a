// Issue 33: "report tables break words ('temperat ure'); the HTML report is 9 MB". The report
// of a 10-hour recording of the baseline rig (971,039 samples, 240 interferometer points, 121
// infrared frames, as `driftlab-cli record --sim --duration 10:00:00`):
// - its HTML stays under a stated size (4.25 MB before 2026-11-27: each surface's contour
//   lines were ~12,600 separate two-point SVG polylines, now joined; see docs/report.md);
// - every table block laid out as the PDF lays it out (ReportWriter::layOutBlock, A4 text
//   width) breaks no word of a header or a cell across two lines (QTextLayout lines: a line
//   that ends and the next that starts with a letter or digit inside one word).

#include "ReportBuilder.h"
#include "ReportDocument.h"
#include "ReportTemplate.h"
#include "ReportWriter.h"
#include "SessionStore.h"

#include "../support/WidgetTestSetup.h"

#include <QTemporaryDir>
#include <QTextBlock>
#include <QTextCursor>
#include <QTextDocument>
#include <QTextLayout>
#include <QTextTable>
#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {
// The words of `block` that its layout breaks across lines ("temperat|ure").
QStringList brokenWords(const QTextBlock &block)
{
    QStringList out;
    const QTextLayout *layout = block.layout();
    const QString text = block.text();
    for (int i = 1; layout && i < layout->lineCount(); ++i) {
        const int at = layout->lineAt(i).textStart();
        if (at <= 0 || at >= text.size())
            continue;
        if (text.at(at - 1).isLetterOrNumber() && text.at(at).isLetterOrNumber()) {
            int a = at, b = at;
            while (a > 0 && !text.at(a - 1).isSpace())
                --a;
            while (b < text.size() && !text.at(b).isSpace())
                ++b;
            out << text.mid(a, at - a) + QLatin1Char('|') + text.mid(at, b - at);
        }
    }
    return out;
}
} // namespace

class TestReportLayout : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void htmlStaysSmall();
    void tablesBreakNoWord();
    void timesReadAsElapsedClock();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
    qint64 m_session = 0;
    ReportDocument m_doc;
    ReportTemplate m_look = ReportTemplate::load();
};

void TestReportLayout::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("long.sqlite")));
    m_session = widgettest::record(*m_store, widgettest::baselineRig(), QStringLiteral("ten hours"), 10 * 3600.0);
    QVERIFY(m_session > 0);
    m_doc = ReportBuilder(*m_store, m_session, m_look).build();
}

void TestReportLayout::htmlStaysSmall()
{
    const QByteArray html = ReportWriter(m_doc, m_look).html();
    int figures = 0;
    for (const ReportBlock &b : m_doc.blocks)
        figures += b.kind == ReportBlock::Kind::Figure ? 1 : 0;
    qInfo("HTML report of 10 h: %.2f MB, %d figures", html.size() / 1e6, figures);
    QVERIFY(figures >= 6); // the surfaces are there: the bound is not met by leaving them out
    QVERIFY2(html.size() < 2'500'000, qPrintable(QStringLiteral("%1 bytes").arg(html.size())));
    // No figure's SVG draws its contours segment by segment.
    for (const ReportBlock &b : m_doc.blocks) {
        if (b.kind != ReportBlock::Kind::Figure)
            continue;
        const int polylines = b.svg.count("<polyline");
        qInfo("%-60s %7.0f kB, %5d polylines", qPrintable(b.text.left(60)), b.svg.size() / 1e3, polylines);
        QVERIFY2(polylines < 3000, qPrintable(b.text));
    }
}

void TestReportLayout::tablesBreakNoWord()
{
    ReportWriter writer(m_doc, m_look);
    QStringList broken;
    int tables = 0, cells = 0;
    for (int i = 0; i < m_doc.blocks.size(); ++i) {
        const ReportBlock &b = m_doc.blocks[i];
        if (b.kind != ReportBlock::Kind::Html || !b.text.contains(QLatin1String("<table")))
            continue;
        QTextDocument d;
        writer.layOutBlock(i, d);
        for (QTextFrame *frame : d.rootFrame()->childFrames()) {
            auto *table = qobject_cast<QTextTable *>(frame);
            if (!table)
                continue;
            ++tables;
            for (int r = 0; r < table->rows(); ++r) {
                for (int c = 0; c < table->columns(); ++c) {
                    const QTextTableCell cell = table->cellAt(r, c);
                    ++cells;
                    for (QTextBlock tb = cell.firstCursorPosition().block(); tb.isValid() && tb.position() <= cell.lastPosition(); tb = tb.next())
                        for (const QString &w : brokenWords(tb))
                            broken << QStringLiteral("%1 row %2: %3").arg(r == 0 ? QStringLiteral("header") : QStringLiteral("cell")).arg(r).arg(w);
                }
            }
        }
    }
    qInfo("%d tables, %d cells at %.0f px", tables, cells, ReportWriter::pdfTextWidth());
    QVERIFY(tables >= 3);
    QVERIFY2(broken.isEmpty(), qPrintable(broken.join(QStringLiteral("\n  "))));
}

// Issue 33 item 3, one time format everywhere: the report's times are elapsed h:mm:ss like every
// time axis and readout (until 2026-11-28 its events read "t (s)" and "t (h)": 7200.0 and 2.00,
// the duration "10.00 h"). Each stored event's time, written here by hand, is in the events table.
void TestReportLayout::timesReadAsElapsedClock()
{
    const auto clock = [](double t_s) {
        const qint64 s = std::llround(t_s);
        return QStringLiteral("%1:%2:%3").arg(s / 3600).arg(s / 60 % 60, 2, 10, QLatin1Char('0')).arg(s % 60, 2, 10, QLatin1Char('0'));
    };
    QString tables;
    for (const ReportBlock &b : m_doc.blocks)
        if (b.kind == ReportBlock::Kind::Html && b.text.contains(QLatin1String("<table")))
            tables += b.text;
    QVERIFY(!tables.isEmpty());
    for (const char *header : {"t (s)", "t (h)", "(h)</th>", "(s)</th>"})
        QVERIFY2(!tables.contains(QLatin1String(header)), header);
    const QVector<EventRecord> events = m_store->events(m_session);
    QVERIFY(events.size() >= 3);
    for (const EventRecord &e : events)
        QVERIFY2(tables.contains(QStringLiteral("<td>%1</td>").arg(clock(e.t))), qPrintable(clock(e.t) + QStringLiteral(" ") + e.label));
    // The duration of the ten hours (the last sample 1 s before 10:00:00 or at it).
    QVERIFY2(tables.contains(QLatin1String("<td>9:59:59</td>")) || tables.contains(QLatin1String("<td>10:00:00</td>")), "duration");
}

QTEST_MAIN(TestReportLayout)
#include "tst_reportlayout.moc"

// The GUI's report dialog on the example bundle: the preview shows every section heading and
// the figures (as images drawn from the report's SVG), saving writes the PDF and HTML that
// `driftlab-cli report` writes, and a bad template leaves a message instead of a report.
// DRIFTLAB_TEST_SCREENSHOTS=DIR writes a picture of the dialog there.

#include "BundleTransfer.h"
#include "ReportDialog.h"
#include "SessionStore.h"

#include <QLabel>
#include <QPrinter>
#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QScrollBar>
#include <QTemporaryDir>
#include <QTextBrowser>
#include <QtTest>

using namespace driftlab;

class TestReportDialog : public QObject {
    Q_OBJECT
private slots:
    void previewsAndSaves();
    void printsTheSavedPages();
};

void TestReportDialog::previewsAndSaves()
{
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    SessionStore store(dir.filePath(QStringLiteral("t.sqlite")));
    const qint64 id = BundleTransfer::importBundle(store, QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"));
    ReportDialog dialog(&store, id);
    dialog.resize(640, 760);
    dialog.show();
    QVERIFY2(dialog.message().startsWith(QStringLiteral("Report built")), qPrintable(dialog.message()));
    // The preview opens at the title, not scrolled to the end (issue 33).
    QVERIFY(QTest::qWaitForWindowExposed(&dialog));
    QApplication::processEvents();
    QVERIFY(dialog.preview()->verticalScrollBar()->maximum() > 0);
    QCOMPARE(dialog.preview()->verticalScrollBar()->value(), 0);
    const QString text = dialog.preview()->toPlainText();
    for (const char *h : {"Session", "Sensors", "Figures", "Thermal error surface", "ISO 230-2 positioning and ISO 230-3 drift",
                          "Fitted models", "Left out: no model has been fitted"})
        QVERIFY2(text.contains(QLatin1String(h)), h);
    int figures = 0;
    for (int i = 0; i < 200; ++i)
        figures += dialog.preview()->document()->resource(QTextDocument::ImageResource, QUrl(QStringLiteral("figure%1").arg(i))).isValid();
    QCOMPARE(figures, 8); // the seed-002 set of the example and the ISO 230-2 and 230-3 plots (no selection or model yet)
    const QByteArray shots = qgetenv("DRIFTLAB_TEST_SCREENSHOTS");
    if (!shots.isEmpty()) {
        dialog.preview()->verticalScrollBar()->setValue(dialog.preview()->verticalScrollBar()->maximum() / 4);
        QVERIFY(dialog.grab().save(QString::fromLocal8Bit(shots) + QStringLiteral("/report-dialog.png")));
    }
    for (const char *name : {"r.pdf", "r.html"}) {
        QVERIFY(dialog.save(dir.filePath(QLatin1String(name))));
        QVERIFY(QFileInfo(dir.filePath(QLatin1String(name))).size() > 10000);
    }
    QFile html(dir.filePath(QStringLiteral("r.html")));
    QVERIFY(html.open(QIODevice::ReadOnly));
    QCOMPARE(html.readAll().count("<figure>"), 8);
    QVERIFY(!dialog.save(dir.filePath(QStringLiteral("r.doc"))));
    QVERIFY(dialog.message().contains(QStringLiteral(".pdf or .html")));
    QVERIFY(!dialog.rebuild(dir.filePath(QStringLiteral("no-such-template"))));
    QVERIFY(dialog.message().contains(QStringLiteral("does not exist")));
}

namespace {
// Standard output of a poppler tool (empty when it is not installed).
QString poppler(const QString &tool, const QStringList &args)
{
    QProcess p;
    p.start(tool, args);
    if (!p.waitForFinished(60000) || p.exitCode() != 0)
        return QString();
    return QString::fromUtf8(p.readAllStandardOutput());
}

int pages(const QString &pdf)
{
    const QRegularExpressionMatch m = QRegularExpression(QStringLiteral("Pages:\\s+(\\d+)")).match(poppler(QStringLiteral("pdfinfo"), {pdf}));
    return m.hasMatch() ? m.captured(1).toInt() : -1;
}
} // namespace

void TestReportDialog::printsTheSavedPages()
{
    // File > Test report > Print...: the printer gets the saved PDF's pages (same layout, same
    // text, the ISO 230 section included). Printed to a PDF file, the two are compared by
    // poppler's pdfinfo and pdftotext.
    if (QStandardPaths::findExecutable(QStringLiteral("pdfinfo")).isEmpty() || QStandardPaths::findExecutable(QStringLiteral("pdftotext")).isEmpty())
        QSKIP("poppler-utils (pdfinfo, pdftotext) not installed");
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    SessionStore store(dir.filePath(QStringLiteral("t.sqlite")));
    const qint64 id = BundleTransfer::importBundle(store, QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"));
    ReportDialog dialog(&store, id);
    const QString saved = dir.filePath(QStringLiteral("saved.pdf")), printed = dir.filePath(QStringLiteral("printed.pdf"));
    QVERIFY(dialog.save(saved));
    QPrinter printer(QPrinter::HighResolution);
    printer.setOutputFormat(QPrinter::PdfFormat);
    printer.setOutputFileName(printed);
    QVERIFY2(dialog.print(printer), qPrintable(dialog.message()));
    QVERIFY2(dialog.message().contains(printed), qPrintable(dialog.message()));
    const int savedPages = pages(saved);
    QVERIFY(savedPages >= 3);
    QCOMPARE(pages(printed), savedPages);
    const auto words = [](const QString &pdf) {
        return poppler(QStringLiteral("pdftotext"), {pdf, QStringLiteral("-")}).simplified();
    };
    const QString printedText = words(printed);
    QVERIFY(printedText.contains(QLatin1String("ISO 230-2 positioning and ISO 230-3 drift")));
    QCOMPARE(printedText, words(saved));
}

QTEST_MAIN(TestReportDialog)
#include "tst_reportdialog.moc"

// Issue 33: "Help (F1) points to a source folder". F1 in the main window opens the user
// documentation shipped inside the application (the :/docs resources the driftlab binary
// links, driftlab_userdocs), run from a working directory that holds no checkout: every
// document of docs/ and README.md is there, shown from qrc:, with no path of the source tree
// in what is shown; following README's links to "docs/x.md" with the keyboard (Tab to the
// link, Enter) shows that document, and a link to a source file opens nothing.

#include "HelpBrowser.h"
#include "MainWindow.h"
#include "../support/WidgetTestSetup.h"

#include <QDir>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTextBrowser>
#include <QtTest>

using namespace driftlab;

namespace {
// The first heading of a Markdown file, as its rendered text starts.
QString firstHeading(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return QString();
    const QString text = QString::fromUtf8(f.readAll());
    const QRegularExpressionMatch m = QRegularExpression(QStringLiteral("^#+\\s+([^\\n`*\\[]+)"), QRegularExpression::MultilineOption).match(text);
    return m.hasMatch() ? m.captured(1).trimmed() : QString();
}
} // namespace

class TestHelpBrowser : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void f1ShowsTheShippedDocumentation();

private:
    QTemporaryDir m_dir;
};

void TestHelpBrowser::initTestCase()
{
    QVERIFY(m_dir.isValid());
    widgettest::privateSettings(m_dir);
    // Run where no checkout is: nothing can be found relative to the working directory.
    QVERIFY(QDir::setCurrent(m_dir.path()));
}

void TestHelpBrowser::f1ShowsTheShippedDocumentation()
{
    MainWindow window;
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::keyClick(&window, Qt::Key_F1);
    HelpBrowser *help = nullptr;
    QTRY_VERIFY((help = window.findChild<HelpBrowser *>()) && help->isVisible());

    // Every user document of the checkout, and nothing else (the test knows the source tree).
    QStringList expected = QDir(QStringLiteral(DRIFTLAB_SOURCE_DIR "/docs")).entryList({QStringLiteral("*.md")}, QDir::Files, QDir::Name);
    expected.prepend(QStringLiteral("README.md"));
    QCOMPARE(help->documents(), expected);
    QCOMPARE(help->currentDocument(), QStringLiteral("README.md"));
    const QString sourceDir = QStringLiteral(DRIFTLAB_SOURCE_DIR);
    auto checkShown = [&](const QString &name) {
        const QUrl source = help->browser()->source();
        QCOMPARE(source.scheme(), QStringLiteral("qrc"));
        QVERIFY2(!source.toString().contains(sourceDir), qPrintable(source.toString()));
        QVERIFY2(!help->windowTitle().contains(sourceDir), qPrintable(help->windowTitle()));
        const QString heading = firstHeading(name == QLatin1String("README.md") ? sourceDir + QStringLiteral("/README.md")
                                                                                 : sourceDir + QStringLiteral("/docs/") + name);
        QVERIFY(!heading.isEmpty());
        QVERIFY2(help->browser()->toPlainText().startsWith(heading),
                 qPrintable(name + QStringLiteral(": '") + help->browser()->toPlainText().left(80) + QStringLiteral("' should start with '") + heading + QLatin1Char('\'')));
    };
    checkShown(QStringLiteral("README.md"));

    // README's links name "docs/x.md": Tab to the first, Enter follows it.
    QTextBrowser *browser = help->browser();
    browser->setFocus();
    QTRY_VERIFY(browser->hasFocus());
    QString href;
    for (int i = 0; i < 200 && !href.startsWith(QLatin1String("docs/")); ++i) {
        QTest::keyClick(browser, Qt::Key_Tab);
        href = browser->textCursor().charFormat().anchorHref();
    }
    QVERIFY2(href.startsWith(QLatin1String("docs/")) && href.contains(QLatin1String(".md")), qPrintable(href));
    const QString target = QFileInfo(QUrl(href).path()).fileName();
    QTest::keyClick(browser, Qt::Key_Return);
    QTRY_COMPARE(help->currentDocument(), target);
    checkShown(target);

    // Every document opens from the list; a link to a file of the source tree opens nothing.
    for (const QString &name : expected) {
        QVERIFY(help->showDocument(name));
        checkShown(name);
    }
    QVERIFY(help->showDocument(QStringLiteral("report.md")));
    QVERIFY(!help->followLink(QUrl(QStringLiteral("../resources/report/template.json"))));
    QVERIFY(!help->followLink(QUrl(QStringLiteral("../widgets/HelpBrowser.cpp"))));
    QCOMPARE(help->currentDocument(), QStringLiteral("report.md"));
    QVERIFY(help->followLink(QUrl(QStringLiteral("docs/storage.md"))));
    checkShown(QStringLiteral("storage.md"));
}

QTEST_MAIN(TestHelpBrowser)
#include "tst_helpbrowser.moc"

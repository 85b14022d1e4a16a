// Issue 33: one name per quantity across GUI, CLI, reports and docs (docs/glossary.md). Every
// string the user sees is read and none may use a forbidden synonym: the main window on a
// recorded session with every dock and every central view shown, the Rig setup, model
// export, measurement-run and CSV import dialogs (labels, buttons, group boxes, tabs, table
// headers, window titles, tooltips, plot titles and axis titles); `driftlab-cli --help`,
// every command's --help and the text of info, list and iso230; the HTML report of the
// session; docs/*.md and README.md (skipped without the source tree).

#include "CsvImportDialog.h"
#include "MainWindow.h"
#include "MeasurementRunDialog.h"
#include "ModelExportDialog.h"
#include "ReportBuilder.h"
#include "ReportTemplate.h"
#include "ReportWriter.h"
#include "RigSetupDialog.h"
#include "SessionStore.h"
#include "Workbench.h"
#include "../support/WidgetTestSetup.h"

#include <QAbstractButton>
#include <QAbstractItemView>
#include <QDir>
#include <QDockWidget>
#include <QGroupBox>
#include <QHeaderView>
#include <QLabel>
#include <QProcess>
#include <QRegularExpression>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTextDocument>
#include <QtTest>

#include <qwt_plot.h>
#include <qwt_text.h>

using namespace driftlab;

namespace {
// The synonyms docs/glossary.md forbids, with the name to use instead.
struct Forbidden {
    QRegularExpression pattern;
    QString use;
};
const QVector<Forbidden> &forbidden()
{
    static const QVector<Forbidden> list{
        {QRegularExpression(QStringLiteral("positioning deviation"), QRegularExpression::CaseInsensitiveOption), QStringLiteral("positional deviation")},
        {QRegularExpression(QStringLiteral("(?<![A-Za-z] )\\bdeviation \\((um|µm)\\)"), QRegularExpression::CaseInsensitiveOption), QStringLiteral("thermal error (µm)")},
        {QRegularExpression(QStringLiteral("displacement \\((um|µm)\\)"), QRegularExpression::CaseInsensitiveOption), QStringLiteral("elongation (µm)")},
        {QRegularExpression(QStringLiteral("thermal deviation|drift error"), QRegularExpression::CaseInsensitiveOption), QStringLiteral("thermal error")},
        // The unit: "um" is the stored unit code (JSON keys, "unit": "um", map files), µm the
        // displayed one. A word "um" after a blank, "(" or a digit is the unit written for a
        // reader; a list of accepted spellings ("um, µm, nm") names the input tokens.
        {QRegularExpression(QStringLiteral("(?<=[\\s(\\d])um(?![A-Za-z0-9_\"'`]|, \u00b5m)")), QStringLiteral("\u00b5m")},
    };
    return list;
}

// "where: text -> use ..." for each forbidden synonym in `text`.
void check(const QString &where, const QString &text, QStringList &found)
{
    for (const Forbidden &f : forbidden()) {
        const QRegularExpressionMatch m = f.pattern.match(text);
        if (m.hasMatch())
            found << QStringLiteral("%1: '%2' in '...%3...' (use '%4')")
                         .arg(where, m.captured(0), text.mid(std::max(0, m.capturedStart() - 40), m.capturedLength() + 60).simplified(), f.use);
    }
}

QString plain(const QString &text)
{
    if (!Qt::mightBeRichText(text))
        return text;
    QTextDocument d;
    d.setHtml(text);
    return d.toPlainText();
}

// Every string a user sees in `top` and its children.
int sweep(QWidget *top, const QString &name, QStringList &found)
{
    int strings = 0;
    auto see = [&](const QString &where, const QString &text) {
        if (text.trimmed().isEmpty())
            return;
        ++strings;
        check(name + QStringLiteral(" ") + where, plain(text), found);
    };
    see(QStringLiteral("window title"), top->windowTitle());
    QList<QWidget *> widgets = top->findChildren<QWidget *>();
    widgets.prepend(top);
    for (QWidget *w : widgets) {
        const QString cls = QLatin1String(w->metaObject()->className());
        see(cls + QStringLiteral(" tooltip"), w->toolTip());
        if (auto *l = qobject_cast<QLabel *>(w))
            see(QStringLiteral("label"), l->text());
        else if (auto *b = qobject_cast<QAbstractButton *>(w))
            see(QStringLiteral("button"), b->text());
        else if (auto *g = qobject_cast<QGroupBox *>(w))
            see(QStringLiteral("group"), g->title());
        else if (auto *d = qobject_cast<QDockWidget *>(w))
            see(QStringLiteral("dock"), d->windowTitle());
        if (auto *t = qobject_cast<QTabWidget *>(w))
            for (int i = 0; i < t->count(); ++i)
                see(QStringLiteral("tab"), t->tabText(i));
        if (auto *v = qobject_cast<QAbstractItemView *>(w); v && v->model()) {
            for (int c = 0; c < v->model()->columnCount(); ++c)
                see(QStringLiteral("%1 header").arg(cls), v->model()->headerData(c, Qt::Horizontal).toString());
            for (int r = 0; r < std::min(v->model()->rowCount(), 50); ++r)
                see(QStringLiteral("%1 row").arg(cls), v->model()->headerData(r, Qt::Vertical).toString());
        }
        if (auto *p = qobject_cast<QwtPlot *>(w)) {
            see(QStringLiteral("plot title"), p->title().text());
            for (int axis = 0; axis < QwtPlot::axisCnt; ++axis)
                if (p->axisEnabled(axis))
                    see(QStringLiteral("plot '%1' axis").arg(p->title().text()), p->axisTitle(axis).text());
        }
    }
    return strings;
}

QString runCli(const QStringList &args)
{
    QProcess p;
    p.start(QStringLiteral(DRIFTLAB_CLI), args);
    if (!p.waitForFinished(60000))
        return QString();
    return QString::fromUtf8(p.readAllStandardOutput() + p.readAllStandardError());
}
} // namespace

class TestVocabulary : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void guiUsesOneNamePerQuantity();
    void cliUsesOneNamePerQuantity();
    void reportUsesOneNamePerQuantity();
    void docsUseOneNamePerQuantity();
    void theSweepFindsASynonym();

private:
    QTemporaryDir m_dir;
    QString m_db;
    qint64 m_session = 0;
};

void TestVocabulary::initTestCase()
{
    QVERIFY(m_dir.isValid());
    widgettest::privateSettings(m_dir);
    m_db = m_dir.filePath(QStringLiteral("words.sqlite"));
    SessionStore store(m_db);
    m_session = widgettest::record(store, widgettest::baselineRig(), QStringLiteral("words"), 2 * 3600.0);
    QVERIFY(m_session > 0);
}

void TestVocabulary::guiUsesOneNamePerQuantity()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QStringList found;
    int strings = 0;
    for (QDockWidget *d : window.findChildren<QDockWidget *>()) {
        d->show();
        d->raise();
    }
    QTabWidget *views = window.centralViews();
    for (int i = 0; i < views->count(); ++i) {
        views->setCurrentIndex(i);
        QTest::qWait(20);
        strings += sweep(&window, QStringLiteral("main window (%1)").arg(views->tabText(i)), found);
    }
    {
        RigSetupDialog d(&window);
        d.addDevice(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"));
        strings += sweep(&d, QStringLiteral("Rig setup"), found);
    }
    {
        ModelExportDialog d(&window);
        strings += sweep(&d, QStringLiteral("model export"), found);
    }
    {
        MeasurementRunDialog d([] { return 0.0; }, [](const QVector<InterferometerPoint> &, const QString &) {}, &window);
        strings += sweep(&d, QStringLiteral("measurement run"), found);
    }
    {
        CsvImportDialog d(m_db, &window);
        strings += sweep(&d, QStringLiteral("CSV import"), found);
    }
    qInfo("%d strings read", strings);
    QVERIFY(strings > 300);
    found.removeDuplicates();
    QVERIFY2(found.isEmpty(), qPrintable(found.join(QStringLiteral("\n  "))));
}

void TestVocabulary::cliUsesOneNamePerQuantity()
{
    const QString help = runCli({QStringLiteral("--help")});
    QStringList commands;
    const QRegularExpression command(QStringLiteral("^  ([a-z0-9-]+)\\s{2,}"), QRegularExpression::MultilineOption);
    for (auto it = command.globalMatch(help); it.hasNext();)
        commands << it.next().captured(1);
    QVERIFY2(commands.size() >= 20, qPrintable(help));
    QStringList found;
    check(QStringLiteral("driftlab-cli --help"), help, found);
    for (const QString &c : commands) {
        const QString text = runCli({c, QStringLiteral("--help")});
        QVERIFY2(text.contains(QStringLiteral("Usage")), qPrintable(c + QStringLiteral(": ") + text.left(200)));
        check(c + QStringLiteral(" --help"), text, found);
    }
    const QString id = QString::number(m_session);
    check(QStringLiteral("info"), runCli({QStringLiteral("info"), QStringLiteral("--db"), m_db}), found);
    check(QStringLiteral("list"), runCli({QStringLiteral("list"), QStringLiteral("--db"), m_db}), found);
    const QString iso = runCli({QStringLiteral("iso230"), id, QStringLiteral("--db"), m_db});
    QVERIFY2(iso.contains(QStringLiteral("reference test")), qPrintable(iso.left(300)));
    check(QStringLiteral("iso230"), iso, found);
    QVERIFY2(found.isEmpty(), qPrintable(found.join(QStringLiteral("\n  "))));
}

void TestVocabulary::reportUsesOneNamePerQuantity()
{
    SessionStore store(m_db);
    const ReportTemplate look = ReportTemplate::load();
    const ReportDocument doc = ReportBuilder(store, m_session, look).build();
    QTextDocument d;
    d.setHtml(QString::fromUtf8(ReportWriter(doc, look).html()));
    QString text = d.toPlainText();
    for (const ReportBlock &b : doc.blocks) // the figures' titles and axis titles are SVG text
        if (b.kind == ReportBlock::Kind::Figure)
            text += QLatin1Char('\n') + QString::fromUtf8(b.svg).remove(QRegularExpression(QStringLiteral("<[^>]*>")));
    QVERIFY(text.contains(QStringLiteral("thermal error"), Qt::CaseInsensitive));
    QStringList found;
    check(QStringLiteral("report"), text, found);
    QVERIFY2(found.isEmpty(), qPrintable(found.join(QStringLiteral("\n  "))));
}

void TestVocabulary::docsUseOneNamePerQuantity()
{
    const QDir docs(QStringLiteral(DRIFTLAB_SOURCE_DIR "/docs"));
    if (!docs.exists())
        QSKIP("no source tree");
    QStringList files;
    for (const QString &f : docs.entryList({QStringLiteral("*.md")}, QDir::Files))
        if (f != QLatin1String("glossary.md")) // it names the synonyms it forbids
            files << docs.filePath(f);
    files << QStringLiteral(DRIFTLAB_SOURCE_DIR "/README.md");
    QStringList found;
    for (const QString &path : files) {
        QFile f(path);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QStringList lines = QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'));
        for (int i = 0; i < lines.size(); ++i) // `code` quotes a stored name or a file's text as it is
            check(QStringLiteral("%1:%2").arg(QFileInfo(path).fileName()).arg(i + 1),
                  QString(lines[i]).remove(QRegularExpression(QStringLiteral("`[^`]*`"))), found);
    }
    QVERIFY2(found.isEmpty(), qPrintable(found.join(QStringLiteral("\n  "))));
}

// The sweep itself finds what it should: a label, an axis title and a table header with a
// forbidden name are reported; the names of the glossary are not.
void TestVocabulary::theSweepFindsASynonym()
{
    QWidget w;
    auto *label = new QLabel(QStringLiteral("<b>Deviation (um)</b>"), &w);
    auto *plot = new QwtPlot(&w);
    plot->setAxisTitle(QwtPlot::yLeft, QStringLiteral("displacement (µm)"));
    auto *header = new QLabel(QStringLiteral("CV RMSE (um)"), &w);
    auto *message = new QLabel(QStringLiteral("holding -12.4 um; 0.93 um/m/K"), &w);
    QStringList found;
    sweep(&w, QStringLiteral("test"), found);
    QCOMPARE(found.size(), 5); // the label twice: "Deviation" and "(um)"
    label->setText(QStringLiteral("positional deviation (µm)"));
    plot->setAxisTitle(QwtPlot::yLeft, QStringLiteral("elongation (µm)"));
    plot->setTitle(QStringLiteral("Thermal error against time; mean deviation (µm)"));
    header->setText(QStringLiteral("CV RMSE (\u00b5m)"));
    message->setText(QStringLiteral("holding -12.4 \u00b5m; error_um, \"unit\": \"um\", accepted: um, \u00b5m, nm"));
    found.clear();
    sweep(&w, QStringLiteral("test"), found);
    QVERIFY2(found.isEmpty(), qPrintable(found.join(QLatin1Char('\n'))));
}

QTEST_MAIN(TestVocabulary)
#include "tst_vocabulary.moc"

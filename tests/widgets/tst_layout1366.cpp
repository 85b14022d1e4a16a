// Issue 33 item 1: every dock and every dialog is usable on a 1366 x 768 laptop screen.
// Geometry, not "it opened": each visible widget lies inside the screen (dock contents and
// tables need no sideways scrolling: a table's columns fit its viewport), no label is cut (its text's QFontMetrics width, or its word-wrapped
// height, fits the label), no button is narrower than its text, no plot is a sliver, and a
// mouse wheel over an unfocused combo box leaves its value alone.

#include "AcquisitionPanel.h"
#include "AnalysisPanel.h"
#include "CsvImportDialog.h"
#include "DiagnosisPanel.h"
#include "HelpBrowser.h"
#include "MainWindow.h"
#include "MeasurementRunDialog.h"
#include "ModelExportDialog.h"
#include "RigConfig.h"
#include "RigRecorder.h"
#include "ReviewWorkspace.h"
#include "RigSetupDialog.h"
#include "ScreenFit.h"
#include "SessionStore.h"
#include "SimulatedRig.h"
#include "Workbench.h"
#include "../support/WidgetTestSetup.h"

#include <QAbstractButton>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QHeaderView>
#include <QLabel>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QSplitter>
#include <QTableView>
#include <QStyle>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTextBrowser>
#include <QTextDocument>
#include <QWheelEvent>
#include <QtTest>

#include <qwt_plot.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>

#include <cmath>

using namespace driftlab;

namespace {
const QRect kScreen(0, 0, 1366, 768);

bool insideScrolledContent(const QWidget *w, const QWidget *top)
{
    for (const QWidget *p = w->parentWidget(); p && p != top; p = p->parentWidget())
        if (qobject_cast<const QAbstractScrollArea *>(p))
            return true;
    return false;
}

QString plain(const QLabel *label)
{
    if (!Qt::mightBeRichText(label->text()))
        return label->text();
    QTextDocument doc;
    doc.setHtml(label->text());
    return doc.toPlainText();
}

// What is wrong with the layout of `top` as shown at its current size (empty: nothing).
QStringList problems(QWidget *top)
{
    QStringList out;
    const QRect frame(top->mapToGlobal(QPoint(0, 0)), top->size());
    const QRect onScreen = QRect(QPoint(0, 0), top->size()); // placed at the screen's origin by the caller
    if (top->width() > kScreen.width() || top->height() > kScreen.height())
        out << QStringLiteral("%1 is %2 x %3").arg(top->metaObject()->className()).arg(top->width()).arg(top->height());
    Q_UNUSED(frame)
    for (QWidget *w : top->findChildren<QWidget *>()) {
        if (!w->isVisibleTo(top) || w->isWindow() || w->visibleRegion().isEmpty())
            continue;
        const QString name = QStringLiteral("%1 '%2'").arg(w->metaObject()->className(), w->objectName());
        if (!insideScrolledContent(w, top)) {
            const QRect r(w->mapTo(top, QPoint(0, 0)), w->size());
            if (!onScreen.contains(r))
                out << QStringLiteral("%1 at %2,%3 %4x%5 leaves the window").arg(name).arg(r.x()).arg(r.y()).arg(r.width()).arg(r.height());
        }
        if (auto *scroll = qobject_cast<QScrollArea *>(w)) {
            if (scroll->widget() && scroll->horizontalScrollBar()->maximum() > 0)
                out << QStringLiteral("%1 of %4 scrolls sideways by %2 px (content %3 px wide)")
                           .arg(name)
                           .arg(scroll->horizontalScrollBar()->maximum())
                           .arg(scroll->widget()->minimumSizeHint().width())
                           .arg(QLatin1String(scroll->widget()->metaObject()->className()));
        }
        auto *table = qobject_cast<QTableView *>(w);
        if (table) {
            // A table scrolls sideways when its columns are wider than its viewport (the
            // scroll bar may be switched off: the columns must fit all the same).
            const int columns = table->horizontalHeader()->length();
            if (table->horizontalScrollBar()->isVisible() || columns > table->viewport()->width() + 1)
                out << QStringLiteral("%1 scrolls sideways: columns %2 px, viewport %3 px").arg(name).arg(columns).arg(table->viewport()->width());
            // Every column's heading readable whole ("eld-out RMS (µn" was cut in an empty table).
            const QHeaderView *header = table->horizontalHeader();
            const int margin = 2 * header->style()->pixelMetric(QStyle::PM_HeaderMargin, nullptr, header);
            for (int c = 0; c < header->count() && header->isVisible() && table->model(); ++c) {
                if (header->isSectionHidden(c))
                    continue;
                const QString heading = table->model()->headerData(c, Qt::Horizontal).toString();
                int widest = 0;
                for (const QString &line : heading.split(QLatin1Char('\n')))
                    widest = std::max(widest, header->fontMetrics().horizontalAdvance(line));
                if (!heading.isEmpty() && widest + margin > header->sectionSize(c) + 1)
                    out << QStringLiteral("%1: heading '%2' needs %3 px, its column has %4").arg(name, heading).arg(widest + margin).arg(header->sectionSize(c));
            }
        }
        if (auto *label = qobject_cast<QLabel *>(w)) {
            const QString text = plain(label);
            if (text.trimmed().isEmpty() || !label->pixmap(Qt::ReturnByValue).isNull())
                continue;
            const QRect c = label->contentsRect();
            if (label->wordWrap()) {
                const int need = label->heightForWidth(label->width());
                if (need > label->height() + 1)
                    out << QStringLiteral("label '%1' needs %2 px height, has %3").arg(text.left(40)).arg(need).arg(label->height());
            } else {
                int widest = 0;
                for (const QString &line : text.split(QLatin1Char('\n')))
                    widest = std::max(widest, label->fontMetrics().horizontalAdvance(line));
                if (widest > c.width() + 1)
                    out << QStringLiteral("label '%1' needs %2 px, has %3").arg(text.left(40)).arg(widest).arg(c.width());
            }
        } else if (auto *button = qobject_cast<QAbstractButton *>(w)) {
            if (!button->text().isEmpty() && button->width() + 1 < button->minimumSizeHint().width())
                out << QStringLiteral("button '%1' is %2 px, needs %3").arg(button->text()).arg(button->width()).arg(button->minimumSizeHint().width());
        } else if (auto *plot = qobject_cast<QwtPlot *>(w)) {
            if (plot->width() < 260 || plot->height() < 160)
                out << QStringLiteral("plot '%1' is a sliver: %2 x %3").arg(plot->title().text()).arg(plot->width()).arg(plot->height());
            // Bottom-axis tick labels must not run together ("0100200300400500").
            const QwtScaleDraw *draw = plot->axisScaleDraw(QwtPlot::xBottom);
            const QwtScaleMap map = plot->canvasMap(QwtPlot::xBottom);
            const QList<double> ticks = plot->axisScaleDiv(QwtPlot::xBottom).ticks(QwtScaleDiv::MajorTick);
            const QFont font = plot->axisWidget(QwtPlot::xBottom)->font();
            // The live plot too: its labels touched (52.8 of 56 px) while ticks were counted
            // from the plot's width, not its canvas's (AxisTicks).
            for (int i = 1; i < ticks.size() && plot->axisEnabled(QwtPlot::xBottom); ++i) {
                const double gap = std::fabs(map.transform(ticks[i]) - map.transform(ticks[i - 1]));
                const double need = (draw->labelSize(font, ticks[i]).width() + draw->labelSize(font, ticks[i - 1]).width()) / 2.0;
                if (gap < need + 2.0) {
                    out << QStringLiteral("plot '%1': x tick labels %2 and %3 run together (%4 px apart, need %5)")
                               .arg(plot->title().text()).arg(ticks[i - 1]).arg(ticks[i]).arg(gap).arg(need + 2.0);
                    break;
                }
            }
        }
    }
    return out;
}

// The main window on database `db`, filling the simulated 1366 x 768 screen.
void showOnTheScreen(MainWindow &window, const QString &db)
{
    QVERIFY(window.workbench()->openDatabase(db));
    window.resize(kScreen.size());
    window.move(0, 0);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
}

// Shows dock `name` of `window` in front of the docks it is tabbed with.
void raiseDock(MainWindow &window, const QString &name)
{
    QDockWidget *d = window.dock(name);
    QVERIFY(d);
    d->show();
    d->raise();
}

void checkDialog(QWidget *dialog)
{
    dialog->show();
    dialog->move(0, 0);
    QVERIFY(QTest::qWaitForWindowExposed(dialog));
    QTest::qWait(30);
    // DRIFTLAB_GRAB_DIR=DIR: each dialog as checked, DIR/<class>.png (to look at them).
    if (const QString dir = qEnvironmentVariable("DRIFTLAB_GRAB_DIR"); !dir.isEmpty())
        dialog->grab().save(QDir(dir).filePath(QString::fromLatin1(dialog->metaObject()->className()).section(QLatin1Char(':'), -1) +
                                               QStringLiteral(".png")));
    const QStringList p = problems(dialog);
    QVERIFY2(p.isEmpty(), qPrintable(QStringLiteral("%1:\n  ").arg(dialog->metaObject()->className()) + p.join(QStringLiteral("\n  "))));
    dialog->hide();
}
} // namespace

class TestLayout1366 : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void cleanupTestCase();
    void everyDockFits();
    void everyDialogFits();
    void wheelLeavesUnfocusedCombosAlone();
    void deviceTableFitsWhileRecording();
    void firstStartFits();
    void analysisResultsFit();
    void diagnosisCandidatesInTheCentralView();

private:
    QTemporaryDir m_dir;
    QString m_db;
};

void TestLayout1366::initTestCase()
{
    QVERIFY(m_dir.isValid());
    widgettest::privateSettings(m_dir);
    ScreenFit::simulateScreen(kScreen.size());
    m_db = m_dir.filePath(QStringLiteral("layout.sqlite"));
    SessionStore store(m_db);
    SimulatedRig rig(widgettest::baselineRig());
    RigRecorder recorder(store, rig);
    QVERIFY(recorder.record(QStringLiteral("layout test"), 600.0) > 0);
    QVERIFY(recorder.record(QStringLiteral("second"), 300.0) > 0);
}

void TestLayout1366::cleanupTestCase()
{
    ScreenFit::simulateScreen(QSize());
}

void TestLayout1366::everyDockFits()
{
    MainWindow window;
    showOnTheScreen(window, m_db);
    if (QTest::currentTestFailed())
        return;
    QCOMPARE(window.size(), kScreen.size());
    const QStringList docks{QStringLiteral("SessionsDock"), QStringLiteral("AcquisitionDock"), QStringLiteral("ModelsDock"),
                            QStringLiteral("DiagnosisDock"), QStringLiteral("AnalysisDock"), QStringLiteral("CompensationDock")};
    for (const QString &name : docks) {
        QDockWidget *d = window.dock(name);
        QVERIFY(d);
        d->show();
        d->raise();
        QTest::qWait(30);
        const QStringList p = problems(&window);
        QVERIFY2(p.isEmpty(), qPrintable(name + QStringLiteral(" open:\n  ") + p.join(QStringLiteral("\n  "))));
    }
    // Every central view at full size, all docks open.
    QTabWidget *views = window.centralViews();
    for (int i = 0; i < views->count(); ++i) {
        views->setCurrentIndex(i);
        QTest::qWait(30);
        const QStringList p = problems(&window);
        QVERIFY2(p.isEmpty(), qPrintable(views->tabText(i) + QStringLiteral(" view:\n  ") + p.join(QStringLiteral("\n  "))));
    }
    // The comparison says which session is which.
    window.compareWith(1);
    QVERIFY(window.comparison()->heading().contains(QStringLiteral("#1")));
    QVERIFY(window.workspace()->heading().contains(QStringLiteral("#2")));
    // View > Reset layout: the docks of the first start (only Sessions open).
    window.resetLayout();
    QTest::qWait(30);
    QVERIFY(window.dock(QStringLiteral("SessionsDock"))->isVisible());
    QVERIFY(!window.dock(QStringLiteral("ModelsDock"))->isVisible());
}

void TestLayout1366::everyDialogFits()
{
    MainWindow window;
    {
        RigSetupDialog d(&window);
        d.addDevice(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"));
        checkDialog(&d);
    }
    {
        ModelExportDialog d(&window);
        checkDialog(&d);
    }
    {
        // The CSV import dialog on the German logger file (preamble, ';', decimal comma).
        CsvImportDialog d(m_db, &window);
        QVERIFY(d.openFile(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/csv/german_logger.csv")));
        checkDialog(&d);
    }
    {
        MeasurementRunDialog d([] { return 0.0; }, [](const QVector<InterferometerPoint> &, const QString &) {}, &window);
        checkDialog(&d);
    }
    {
        QTemporaryDir docs;
        QFile f(docs.filePath(QStringLiteral("README.md")));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("# DriftLab\n\nSee [review](review.md).\n");
        f.close();
        QFile g(docs.filePath(QStringLiteral("review.md")));
        QVERIFY(g.open(QIODevice::WriteOnly));
        g.write("# Review\n\nText.\n");
        g.close();
        HelpBrowser d(docs.path(), &window);
        QCOMPARE(d.documents(), QStringList({QStringLiteral("README.md"), QStringLiteral("review.md")}));
        QCOMPARE(d.currentDocument(), QStringLiteral("README.md"));
        QVERIFY(d.browser()->toPlainText().contains(QStringLiteral("See review")));
        QVERIFY(d.showDocument(QStringLiteral("review.md")));
        QVERIFY(d.browser()->toPlainText().startsWith(QStringLiteral("Review")));
        checkDialog(&d);
    }
}

void TestLayout1366::wheelLeavesUnfocusedCombosAlone()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    window.resize(kScreen.size());
    window.show();
    QDockWidget *d = window.dock(QStringLiteral("DiagnosisDock"));
    d->show();
    d->raise();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QComboBox *box = nullptr;
    for (QComboBox *c : window.diagnosis()->findChildren<QComboBox *>())
        if (c->isVisible() && c->count() > 1)
            box = c;
    QVERIFY(box);
    box->setCurrentIndex(0);
    window.setFocus();
    QVERIFY(!box->hasFocus());
    const QPoint at = box->rect().center();
    QWheelEvent wheel(at, box->mapToGlobal(at), QPoint(), QPoint(0, -120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(box, &wheel);
    QCOMPARE(box->currentIndex(), 0);
    QVERIFY(box->focusPolicy() != Qt::WheelFocus);
    // Focused (clicked or tabbed into), it takes the wheel as usual.
    box->setFocus();
    QTRY_VERIFY(box->hasFocus());
    QWheelEvent again(at, box->mapToGlobal(at), QPoint(), QPoint(0, -120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(box, &again);
    QCOMPARE(box->currentIndex(), 1);
}

// The Acquisition dock's device table during a recording (its Gaps column once scrolled
// sideways at 1366 px): every column inside the table, no sideways scroll bar, a long state
// message in the tooltip rather than widening the column. The live view beside it, filled
// with the recording's channels, fits as well (its title once widened the window to 1386 px).
void TestLayout1366::deviceTableFitsWhileRecording()
{
    MainWindow window;
    showOnTheScreen(window, m_db);
    if (QTest::currentTestFailed())
        return;
    raiseDock(window, QStringLiteral("AcquisitionDock"));
    AcquisitionPanel *panel = window.acquisition();
    const QString db = m_dir.filePath(QStringLiteral("recording.sqlite"));
    QVERIFY2(panel->startRecording(QStringLiteral("baseline"), db, 600.0), qPrintable(panel->lastError()));
    QTRY_VERIFY(panel->deviceRowCount() > 0 && !panel->deviceCell(0, 3).isEmpty());
    QTest::qWait(300);
    auto *table = panel->findChild<QTableWidget *>();
    QVERIFY(table && table->isVisible());
    QStringList p = problems(&window);
    // The live view beside the docks, filled, fits too.
    QTabWidget *views = window.centralViews();
    for (int i = 0; i < views->count(); ++i)
        if (views->widget(i)->findChild<QwtPlot *>() && views->tabText(i).contains(QStringLiteral("Recording")))
            views->setCurrentIndex(i);
    QTest::qWait(100);
    for (const QString &q : problems(&window))
        p << QStringLiteral("live view: ") + q;
    panel->stopRecording();
    QVERIFY2(p.isEmpty(), qPrintable(QStringLiteral("recording:\n  ") + p.join(QStringLiteral("\n  "))));
    const int columns = table->horizontalHeader()->length();
    QVERIFY2(columns <= table->viewport()->width(), qPrintable(QStringLiteral("%1 > %2").arg(columns).arg(table->viewport()->width())));
    QVERIFY(!table->horizontalScrollBar()->isVisible());
    // The last column (Gaps) lies wholly inside the viewport.
    const int last = table->columnCount() - 1;
    QVERIFY(table->columnViewportPosition(last) + table->columnWidth(last) <= table->viewport()->width());
}

// The first start (no database): the welcome page's three notes are whole (each was cut to
// two lines, "...choose its", at 1366 x 768 and at 1920 x 1080: the centred box took the
// height of its unwrapped width), and the empty sessions table does not scroll sideways.
void TestLayout1366::firstStartFits()
{
    MainWindow window;
    window.resize(kScreen.size());
    window.move(0, 0);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::qWait(30);
    QVERIFY(!window.workbench()->store());
    QWidget *welcome = window.findChild<QWidget *>(QStringLiteral("WelcomePage"));
    QVERIFY(welcome && welcome->isVisible());
    const QStringList p = problems(&window);
    QVERIFY2(p.isEmpty(), qPrintable(QStringLiteral("first start:\n  ") + p.join(QStringLiteral("\n  "))));
}

// The Analysis dock open under its results, as `driftlab --analysis` shows them: the window
// stays within the screen (the docs' screenshot of 2026-11-27 was 1366 x 794: the filled
// results view and the dock asked for more height than the screen has).
void TestLayout1366::analysisResultsFit()
{
    const QString db = m_dir.filePath(QStringLiteral("analysis.sqlite"));
    {
        SessionStore store(db);
        SimulatedRig rig(widgettest::baselineRig());
        RigRecorder recorder(store, rig);
        QVERIFY(recorder.record(QStringLiteral("two hours"), 2 * 3600.0) > 0);
    }
    MainWindow window;
    showOnTheScreen(window, db);
    if (QTest::currentTestFailed())
        return;
    raiseDock(window, QStringLiteral("AnalysisDock"));
    QSignalSpy done(window.analysis(), &AnalysisPanel::workflowFinished);
    QVERIFY2(window.analysis()->startWorkflow(1, QStringLiteral("S1"), 1.5, false), qPrintable(window.analysis()->lastError()));
    QVERIFY(done.wait(120000));
    QVERIFY2(done.last().at(0).toBool(), qPrintable(window.analysis()->lastError()));
    QTest::qWait(100);
    QCOMPARE(window.centralViews()->currentWidget(), window.analysis()->resultsView());
    const QStringList p = problems(&window);
    QVERIFY2(p.isEmpty(), qPrintable(QStringLiteral("analysis results:\n  ") + p.join(QStringLiteral("\n  "))));
    QVERIFY2(window.minimumSizeHint().height() <= kScreen.height(), qPrintable(QString::number(window.minimumSizeHint().height())));
}

void TestLayout1366::diagnosisCandidatesInTheCentralView()
{
    // The candidates' table is part of the Diagnosis result in the central area, below the
    // residual maps, with at least four of the grammar's ten members in view while the dock is
    // open; in the dock at 1366 x 768 it had room for one row.
    MainWindow window;
    showOnTheScreen(window, m_db);
    if (QTest::currentTestFailed())
        return;
    raiseDock(window, QStringLiteral("DiagnosisDock"));
    QTableWidget *table = window.diagnosis()->candidateTable();
    table->setRowCount(10);
    for (int r = 0; r < 10; ++r)
        for (int c = 0; c < table->columnCount(); ++c)
            table->setItem(r, c, new QTableWidgetItem(QStringLiteral("member %1").arg(r)));
    window.centralViews()->setCurrentWidget(window.diagnosis()->resultsView());
    QTest::qWait(50);
    QVERIFY2(window.diagnosis()->resultsView()->isAncestorOf(table), "the candidates' table is not in the central Diagnosis view");
    QVERIFY(table->isVisible());
    int whole = 0;
    for (int r = 0; r < 10; ++r) {
        const int top = table->rowViewportPosition(r);
        whole += top >= 0 && top + table->rowHeight(r) <= table->viewport()->height();
    }
    QVERIFY2(whole >= 4, qPrintable(QStringLiteral("%1 rows of the candidates' table in view (viewport %2 px)").arg(whole).arg(table->viewport()->height())));
    const QStringList p = problems(&window);
    QVERIFY2(p.isEmpty(), qPrintable(QStringLiteral("diagnosis view:\n  ") + p.join(QStringLiteral("\n  "))));
}

QTEST_MAIN(TestLayout1366)
#include "tst_layout1366.moc"

// Issue 33: "Pressing Diagnose scrolls the dock so that progress and Cancel leave the view".
// The main window maximised on a 1366 x 768 screen, the Diagnosis dock open (its panel in
// a scroll area), Diagnose pressed with the mouse on two short recorded sessions: while the
// diagnosis runs, the progress bar and the Cancel button lie inside the dock's viewport and
// the dock's scroll position has not moved away from them; Cancel (by mouse) stops it.

#include "DiagnosisPanel.h"
#include "MainWindow.h"
#include "ScreenFit.h"
#include "SessionStore.h"
#include "Workbench.h"
#include "../support/WidgetTestSetup.h"

#include <QDockWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

namespace {
const QSize kScreen(1366, 768);

QPushButton *button(QWidget *panel, const QString &text)
{
    for (QPushButton *b : panel->findChildren<QPushButton *>())
        if (b->text() == text)
            return b;
    return nullptr;
}

// Where `w` lies in the viewport of `scroll` and whether it lies there whole.
QString placeIn(const QScrollArea *scroll, const QWidget *w, bool *inside)
{
    const QRect r(w->mapTo(scroll->viewport(), QPoint(0, 0)), w->size());
    *inside = w->isVisible() && scroll->viewport()->rect().contains(r);
    return QStringLiteral("%1 at y %2..%3, viewport 0..%4, scrolled to %5")
        .arg(QLatin1String(w->metaObject()->className()))
        .arg(r.top())
        .arg(r.bottom())
        .arg(scroll->viewport()->height() - 1)
        .arg(scroll->verticalScrollBar()->value());
}
} // namespace

class TestDiagnosisDock : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void cleanupTestCase() { ScreenFit::simulateScreen(QSize()); }
    void diagnoseKeepsProgressAndCancelInView();

private:
    QTemporaryDir m_dir;
    QString m_db;
};

void TestDiagnosisDock::initTestCase()
{
    QVERIFY(m_dir.isValid());
    widgettest::privateSettings(m_dir);
    ScreenFit::simulateScreen(kScreen);
    m_db = m_dir.filePath(QStringLiteral("dock.sqlite"));
    SessionStore store(m_db);
    QVERIFY(widgettest::record(store, widgettest::structureOffsetRig(6000.0), QStringLiteral("train"), 7200.0) > 0);
    QVERIFY(widgettest::record(store, widgettest::structureOffsetRig(8000.0, 1), QStringLiteral("validate"), 5400.0) > 0);
}

void TestDiagnosisDock::diagnoseKeepsProgressAndCancelInView()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    window.resize(kScreen);
    window.move(0, 0);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&window));
    QScrollArea *scroll = widgettest::raiseDock(window.dock(QStringLiteral("DiagnosisDock")));
    QVERIFY(scroll);
    DiagnosisPanel *panel = window.diagnosis();
    QPushButton *run = button(panel, QStringLiteral("Diagnose"));
    QPushButton *cancel = button(panel, QStringLiteral("Cancel"));
    auto *progress = panel->findChild<QProgressBar *>();
    QVERIFY(run && cancel && progress);
    // The dock is shorter than its panel at 768 px (it scrolls), and Diagnose is in view.
    qInfo("dock viewport %d px high, panel %d px, scroll range 0..%d", scroll->viewport()->height(), panel->height(),
          scroll->verticalScrollBar()->maximum());
    bool inside = false;
    QVERIFY2((placeIn(scroll, run, &inside), inside), qPrintable(placeIn(scroll, run, &inside)));
    const int scrolledBefore = scroll->verticalScrollBar()->value();

    QSignalSpy done(panel, &DiagnosisPanel::finished);
    // Pressed as a user does, the button with the focus (a click gives it).
    run->setFocus(Qt::MouseFocusReason);
    QTRY_VERIFY(run->hasFocus());
    QTest::mouseClick(run, Qt::LeftButton);
    QVERIFY2(panel->running(), qPrintable(panel->lastError()));
    // Some progress arrives; the focus has moved on by now and the scroll area followed it, if it does.
    QTRY_VERIFY_WITH_TIMEOUT(progress->value() > 0 || !panel->running(), 20000);
    QTest::qWait(100);
    const QString progressPlace = placeIn(scroll, progress, &inside);
    const bool progressInside = inside;
    const QString cancelPlace = placeIn(scroll, cancel, &inside);
    const bool cancelInside = inside;
    const int scrolledAfter = scroll->verticalScrollBar()->value();
    const bool cancelFocused = cancel->hasFocus();
    const bool wasRunning = panel->running();
    if (panel->running())
        QTest::mouseClick(cancel, Qt::LeftButton);
    QVERIFY(done.count() > 0 || done.wait(120000));
    QVERIFY2(progressInside, qPrintable(progressPlace));
    QVERIFY2(cancelInside, qPrintable(cancelPlace));
    QVERIFY2(wasRunning, "the diagnosis ended before its progress was looked at");
    QVERIFY2(cancelFocused, "the focus left the disabled Diagnose for another widget than Cancel");
    QVERIFY2(scrolledAfter <= scrolledBefore,
             qPrintable(QStringLiteral("the dock scrolled from %1 to %2 px").arg(scrolledBefore).arg(scrolledAfter)));
}

QTEST_MAIN(TestDiagnosisDock)
#include "tst_diagnosisdock.moc"

// Times typed into the GUI read as they are shown (issue 33 item 3: one time format
// everywhere): the Analysis dock's training / held-out bounds, the Acquisition dock's
// duration and the measurement run's stamps take h:mm:ss (or "90 min", "2 h") and show
// h:mm:ss; the values reach the fit request in the hours worked out by hand.
#include "AnalysisPanel.h"
#include "DataDrivenFit.h"
#include "ElapsedTimeBox.h"

#include <QLineEdit>
#include <QtTest>

using namespace driftlab;

class TestElapsedTimeBox : public QObject {
    Q_OBJECT
private slots:
    void typedAndShownAsClock();
    void analysisBoundsInHours();

private:
    static void type(QDoubleSpinBox &box, const QString &text)
    {
        QLineEdit *edit = box.findChild<QLineEdit *>();
        QVERIFY(edit);
        edit->selectAll();
        QTest::keyClicks(edit, text);
        QTest::keyClick(edit, Qt::Key_Return);
    }
};

void TestElapsedTimeBox::typedAndShownAsClock()
{
    ElapsedTimeBox box;
    box.setSpecialValueText(QStringLiteral("until Stop"));
    box.show();
    QCOMPARE(box.text(), QStringLiteral("until Stop")); // 0 at the minimum
    type(box, QStringLiteral("1:30:00"));
    QCOMPARE(box.value(), 5400.0);
    QCOMPARE(box.text(), QStringLiteral("1:30:00"));
    type(box, QStringLiteral("45 min"));
    QCOMPARE(box.value(), 2700.0);
    QCOMPARE(box.text(), QStringLiteral("0:45:00"));
    type(box, QStringLiteral("2 h"));
    QCOMPARE(box.value(), 7200.0);
    box.stepBy(1); // one minute
    QCOMPARE(box.text(), QStringLiteral("2:01:00"));
    // Letters that make no time are not taken: the value stays.
    type(box, QStringLiteral("abc"));
    QCOMPARE(box.value(), 7260.0);
    QCOMPARE(box.text(), QStringLiteral("2:01:00"));
    QVERIFY(box.lastRefusal().isEmpty()); // never typed: no letter of it can start a time
    // An impossible clock (minutes 75) is not accepted either, and the box says why.
    QSignalSpy refused(&box, &ElapsedTimeBox::entryRefused);
    type(box, QStringLiteral("1:75:00"));
    QCOMPARE(box.value(), 7260.0);
    QCOMPARE(refused.count(), 1);
    QCOMPARE(refused.at(0).at(0).toString(), QStringLiteral("'1:75:00': minutes must be below 60 in H:MM:SS; kept 2:01:00"));
    // A time beyond the range is named with the range.
    type(box, QStringLiteral("200 h"));
    QCOMPARE(box.value(), 7260.0);
    QCOMPARE(box.lastRefusal(), QStringLiteral("'200 h' is outside until Stop to 168:00:00; kept 2:01:00"));
    // A good entry after a refused one is taken, and nothing more is refused.
    type(box, QStringLiteral("0:10:00"));
    QCOMPARE(box.value(), 600.0);
    QCOMPARE(refused.count(), 2);
    box.setValue(0.0);
    QCOMPARE(box.text(), QStringLiteral("until Stop"));
}

void TestElapsedTimeBox::analysisBoundsInHours()
{
    AnalysisPanel panel;
    panel.show();
    const QList<QDoubleSpinBox *> boxes = panel.findChildren<QDoubleSpinBox *>();
    QList<ElapsedTimeBox *> times;
    for (QDoubleSpinBox *b : boxes)
        if (auto *t = qobject_cast<ElapsedTimeBox *>(b))
            times << t;
    QCOMPARE(times.size(), 4); // training from / to, held-out from / to
    // All open: "start" / "end" shown, the request leaves both ranges open.
    QCOMPARE(times[0]->text(), QStringLiteral("start"));
    QCOMPARE(times[1]->text(), QStringLiteral("end"));
    QVERIFY(panel.request(QStringLiteral("ridge")).train.all());
    QVERIFY(!panel.request(QStringLiteral("ridge")).holdoutRange.has_value());
    type(*times[0], QStringLiteral("0:15:00"));
    type(*times[1], QStringLiteral("2:30:00"));
    type(*times[2], QStringLiteral("150 min"));
    const DataDrivenFitRequest q = panel.request(QStringLiteral("ridge"));
    QCOMPARE(q.train.from_h, 0.25);
    QCOMPARE(q.train.to_h, 2.5);
    QVERIFY(q.holdoutRange.has_value());
    QCOMPARE(q.holdoutRange->from_h, 2.5);
    QVERIFY(!std::isfinite(q.holdoutRange->to_h));
    QCOMPARE(times[2]->text(), QStringLiteral("2:30:00"));
    // Down one step from 0:00:00 opens the side again.
    times[0]->setValue(0.0);
    times[0]->stepBy(-1);
    QCOMPARE(times[0]->text(), QStringLiteral("start"));
    QVERIFY(!std::isfinite(panel.request(QStringLiteral("ridge")).train.from_h));
}

QTEST_MAIN(TestElapsedTimeBox)
#include "tst_elapsedtimebox.moc"

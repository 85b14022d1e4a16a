// The technician's live interferometer run: targets set, deviations typed and pasted
// (one value per line and "position <tab> deviation" lines), each stamped when entered,
// an incomplete run refused, a committed run handed over with the next run number.
#include "MeasurementRunDialog.h"

#include <QTableWidget>
#include <QtTest>

using namespace driftlab;

class TestMeasurementRunDialog : public QObject {
    Q_OBJECT
private slots:
    void typePasteCommit();
    void timesInClockNotation();
};

void TestMeasurementRunDialog::typePasteCommit()
{
    double now = 100.0;
    QVector<InterferometerPoint> committed;
    QStringList notes;
    MeasurementRunDialog d([&] { return now; },
                           [&](const QVector<InterferometerPoint> &p, const QString &note) {
                               committed += p;
                               notes << note;
                           },
                           nullptr, 3);
    d.setTargets({0.0, 130.0, 260.0, 390.0, 520.0});
    d.setDirection(QStringLiteral("+"));
    QVERIFY(d.enterDeviation(0, QStringLiteral("0.4")));
    now = 104.0;
    QVERIFY(d.enterDeviation(1, QStringLiteral("3,25"))); // a decimal comma as typed on a German keyboard
    QVERIFY(!d.enterDeviation(2, QStringLiteral("abc")));
    QVERIFY(d.lastError().contains(QLatin1String("260.000 mm: \"abc\" is not a number")));
    // Incomplete: refused, nothing handed over.
    QVERIFY(!d.commitRun());
    QVERIFY2(d.lastError().contains(QLatin1String("target 260.000 mm has no deviation")), qPrintable(d.lastError()));
    QVERIFY(committed.isEmpty());
    // Paste the rest from the laser software: one value per line from row 2.
    now = 112.0;
    QCOMPARE(d.paste(QStringLiteral("6.5\n9.75\n"), 2), 2);
    // "position<TAB>deviation" lines find their rows.
    now = 120.0;
    QCOMPARE(d.paste(QStringLiteral("520.000\t13.0\n"), 0), 1);
    if (qEnvironmentVariableIsSet("DRIFTLAB_SCREENSHOTS")) { // docs/screenshots/measurement-run.png
        d.show();
        QTest::qWait(200);
        d.grab().save(QDir(qEnvironmentVariable("DRIFTLAB_SCREENSHOTS")).filePath(QStringLiteral("measurement-run.png")));
    }
    QVERIFY2(d.commitRun(), qPrintable(d.lastError()));
    QCOMPARE(committed.size(), 5);
    QCOMPARE(committed[0].run, 3);
    QCOMPARE(committed[0].t, 100.0);
    QCOMPARE(committed[1].error_um, 3.25);
    QCOMPARE(committed[1].t, 104.0);
    QCOMPARE(committed[2].t, 112.0);
    QCOMPARE(committed[4].position_mm, 520.0);
    QCOMPARE(committed[4].error_um, 13.0);
    QCOMPARE(committed[4].t, 120.0);
    QCOMPARE(committed[4].direction, QStringLiteral("+"));
    QCOMPARE(notes, QStringList{QStringLiteral("interferometer run 3 entered by the technician (5 targets)")});
    // The next run: same targets, empty deviations, number 4.
    QCOMPARE(d.nextRun(), 4);
    QCOMPARE(d.rowCount(), 5);
    QVERIFY(!d.commitRun());
    // More values than targets: the extra ones are not entered, and it says so.
    QCOMPARE(d.paste(QStringLiteral("1\n2\n3\n4\n5\n6\n"), 0), 5);
    QVERIFY(d.lastError().contains(QLatin1String("pasted more values than targets")));
}

void TestMeasurementRunDialog::timesInClockNotation()
{
    // The stamps read h:mm:ss like every time on screen, keep their exact seconds, and a
    // corrected time is typed as h:mm:ss (or "90 min"); a wrong one names its target and
    // stops the commit.
    double now = 3723.5; // 1:02:03.5
    QVector<InterferometerPoint> committed;
    MeasurementRunDialog d([&] { return now; }, [&](const QVector<InterferometerPoint> &p, const QString &) { committed += p; });
    d.setTargets({0.0, 100.0, 200.0});
    auto *table = d.findChild<QTableWidget *>();
    QVERIFY(table);
    QVERIFY(table->horizontalHeaderItem(2)->text().contains(QLatin1String("h:mm:ss")));
    QVERIFY(d.enterDeviation(0, QStringLiteral("1.0")));
    QCOMPARE(table->item(0, 2)->text(), QStringLiteral("1:02:03"));
    now = 3725.0;
    QVERIFY(d.enterDeviation(1, QStringLiteral("2.0")));
    QVERIFY(d.enterDeviation(2, QStringLiteral("3.0")));
    table->item(1, 2)->setText(QStringLiteral("1:00:00"));  // corrected by hand
    QCOMPARE(table->item(1, 2)->text(), QStringLiteral("1:00:00"));
    table->item(2, 2)->setText(QStringLiteral("62 min"));
    QCOMPARE(table->item(2, 2)->text(), QStringLiteral("1:02:00"));
    table->item(0, 2)->setText(QStringLiteral("1:75:00"));
    QVERIFY2(d.lastError().contains(QLatin1String("target 0.000 mm: session time '1:75:00': minutes must be below 60")), qPrintable(d.lastError()));
    QVERIFY(!d.commitRun());
    QVERIFY2(d.lastError().contains(QLatin1String("target 0.000 mm has no valid time")), qPrintable(d.lastError()));
    QVERIFY(committed.isEmpty());
    table->item(0, 2)->setText(QStringLiteral("1:02:03.5"));
    QVERIFY2(d.commitRun(), qPrintable(d.lastError()));
    QCOMPARE(committed.size(), 3);
    // Committed in time order: 1:00:00, 1:02:00, 1:02:03.5.
    QCOMPARE(committed[0].t, 3600.0);
    QCOMPARE(committed[0].position_mm, 100.0);
    QCOMPARE(committed[1].t, 3720.0);
    QCOMPARE(committed[2].t, 3723.5);
}

QTEST_MAIN(TestMeasurementRunDialog)
#include "tst_measurementrundialog.moc"

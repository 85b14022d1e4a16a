// The technician's live interferometer run: targets set, deviations typed and pasted
// (one value per line and "position <tab> deviation" lines), each stamped when entered,
// an incomplete run refused, a committed run handed over with the next run number.
#include "MeasurementRunDialog.h"

#include <QtTest>

using namespace driftlab;

class TestMeasurementRunDialog : public QObject {
    Q_OBJECT
private slots:
    void typePasteCommit();
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

QTEST_MAIN(TestMeasurementRunDialog)
#include "tst_measurementrundialog.moc"

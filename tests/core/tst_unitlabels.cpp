// One notation for elapsed time (issue 33 item 3): what UnitLabels::clock writes, parseClock
// reads back, and every form a person types (H:MM:SS, M:SS, seconds, "2 h", "90 min",
// a decimal comma) gives the seconds worked out by hand; what is not a duration says why.
#include "UnitLabels.h"

#include <QtTest>

using namespace driftlab;

class TestUnitLabels : public QObject {
    Q_OBJECT
private slots:
    void clockFloorsWholeSeconds();
    void parsesWhatPeopleType_data();
    void parsesWhatPeopleType();
    void refusesWithAReason_data();
    void refusesWithAReason();
    void clockReadsBack();
};

void TestUnitLabels::clockFloorsWholeSeconds()
{
    QCOMPARE(UnitLabels::clock(0.0), QStringLiteral("0:00:00"));
    QCOMPARE(UnitLabels::clock(59.99), QStringLiteral("0:00:59"));
    QCOMPARE(UnitLabels::clock(3723.4), QStringLiteral("1:02:03"));
    QCOMPARE(UnitLabels::clock(78.0 * 3600.0 + 5.0), QStringLiteral("78:00:05"));
    QCOMPARE(UnitLabels::clock(-5.0), QStringLiteral("0:00:00"));
}

void TestUnitLabels::parsesWhatPeopleType_data()
{
    QTest::addColumn<QString>("text");
    QTest::addColumn<double>("seconds");
    QTest::newRow("h:mm:ss") << "1:02:03" << 3723.0;
    QTest::newRow("long run") << "78:00:05" << 280805.0;
    QTest::newRow("m:ss") << "12:05" << 725.0;
    QTest::newRow("seconds") << "600" << 600.0;
    QTest::newRow("fraction of the last field") << "0:00:07.25" << 7.25;
    QTest::newRow("decimal comma seconds") << "7,5" << 7.5;
    QTest::newRow("hours") << "2 h" << 7200.0;
    QTest::newRow("hours, comma, no space") << "1,5h" << 5400.0;
    QTest::newRow("minutes") << "90 min" << 5400.0;
    QTest::newRow("seconds unit") << "45 s" << 45.0;
    QTest::newRow("spaces around") << "  0:30:00 " << 1800.0;
    QTest::newRow("zero") << "0:00:00" << 0.0;
}

void TestUnitLabels::parsesWhatPeopleType()
{
    QFETCH(QString, text);
    QFETCH(double, seconds);
    QString why;
    const std::optional<double> v = UnitLabels::parseClock(text, &why);
    QVERIFY2(v.has_value(), qPrintable(why));
    QCOMPARE(*v, seconds);
}

void TestUnitLabels::refusesWithAReason_data()
{
    QTest::addColumn<QString>("text");
    QTest::addColumn<QString>("reason");
    QTest::newRow("word") << "ten" << "'ten' is not a duration (SECONDS or H:MM:SS)";
    QTest::newRow("empty") << "" << "'' is not a duration";
    QTest::newRow("four fields") << "1:2:3:4" << "is not a duration";
    QTest::newRow("negative") << "-5" << "is not a duration";
    QTest::newRow("minutes past 59") << "1:99:00" << "'1:99:00': minutes must be below 60 in H:MM:SS";
    QTest::newRow("seconds past 59") << "5:75" << "seconds must be below 60";
    QTest::newRow("fraction before the last field") << "1.5:00" << "is not a duration";
    QTest::newRow("unknown unit") << "3 days" << "is not a duration";
}

void TestUnitLabels::refusesWithAReason()
{
    QFETCH(QString, text);
    QFETCH(QString, reason);
    QString why;
    QVERIFY(!UnitLabels::parseClock(text, &why).has_value());
    QVERIFY2(why.contains(reason), qPrintable(why));
}

void TestUnitLabels::clockReadsBack()
{
    for (double s : {0.0, 1.0, 59.0, 60.0, 3599.0, 3600.0, 36000.0 + 59.0 * 60 + 59, 280805.0})
        QCOMPARE(UnitLabels::parseClock(UnitLabels::clock(s)).value_or(-1.0), s);
}

QTEST_MAIN(TestUnitLabels)
#include "tst_unitlabels.moc"

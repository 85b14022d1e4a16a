// ParameterPlausibility says when an identified seed-000 parameter sits at an identification
// bound (issue 36 item 1: "a baseline at a bound is reported as such"), with the bounds and
// beside any distance from physics; a value inside its bounds is not called a bound. The
// diagnosis fits lambda in 20-120 W/(m K) and P_f within 40 mm of the drawing
// (DiagnosisOptions); the numbers below are those cases.
#include "ParameterPlausibility.h"

#include <QtTest>

using namespace driftlab;

namespace {

IdentificationResult result(double lambda, double fixedEnd_mm)
{
    IdentificationResult r;
    r.parameters.conductivity_W_mK = lambda;
    r.parameters.fixedEndPosition_mm = fixedEnd_mm;
    return r;
}

IdentificationOptions diagnosisBounds(double drawing_mm)
{
    IdentificationOptions o;
    o.lambdaLower = 20.0;
    o.lambdaUpper = 120.0;
    o.fitFixedEnd = true;
    o.fixedEndLower_mm = drawing_mm - 40.0;
    o.fixedEndUpper_mm = drawing_mm + 40.0;
    return o;
}

const PlausibilityFlag *flag(const std::vector<PlausibilityFlag> &flags, const char *parameter)
{
    for (const PlausibilityFlag &f : flags)
        if (f.parameter == parameter)
            return &f;
    return nullptr;
}

} // namespace

class TestParameterPlausibility : public QObject {
    Q_OBJECT
private slots:
    void boundsAreSaidWithTheirValues();
    void insideTheBoundsIsNoBound();
};

void TestParameterPlausibility::boundsAreSaidWithTheirValues()
{
    // The failure mode: lambda run to its 120 W/(m K) limit, P_f at the tolerance's edge.
    const std::vector<PlausibilityFlag> flags = ParameterPlausibility::implausible(result(120.0, -181.0), diagnosisBounds(-141.0), -141.0);
    const PlausibilityFlag *lambda = flag(flags, "lambda");
    QVERIFY(lambda);
    const QString l = QString::fromStdString(lambda->message);
    QVERIFY2(l.contains(QStringLiteral("far from steel")), qPrintable(l)); // 120 > 90: implausible as before
    QVERIFY2(l.contains(QStringLiteral("at its identification bound (20.0 to 120.0 W/(m K))")), qPrintable(l));
    QCOMPARE(lambda->value, 120.0);
    // P_f 40 mm from the drawing: beyond the 30 mm plausible, and at the bound.
    const PlausibilityFlag *fixedEnd = flag(flags, "P_f");
    QVERIFY(fixedEnd);
    const QString f = QString::fromStdString(fixedEnd->message);
    QVERIFY2(f.contains(QStringLiteral("-181.0 mm, the drawing says -141.0 mm")), qPrintable(f));
    QVERIFY2(f.contains(QStringLiteral("at its identification bound (-181.0 to -101.0 mm)")), qPrintable(f));
    // A bound inside the plausible range is still a bound: lambda at 50 with an upper bound of 50.
    IdentificationOptions narrow = diagnosisBounds(-141.0);
    narrow.lambdaUpper = 50.0;
    const std::vector<PlausibilityFlag> narrowFlags = ParameterPlausibility::implausible(result(50.0, -141.0), narrow, -141.0);
    const PlausibilityFlag *at50 = flag(narrowFlags, "lambda");
    QVERIFY(at50);
    QCOMPARE(QString::fromStdString(at50->message),
             QStringLiteral("lambda 50.0 W/(m K), at its identification bound (20.0 to 50.0 W/(m K)): the fit ran out of room, so "
                            "the model may be absorbing physics it lacks"));
}

void TestParameterPlausibility::insideTheBoundsIsNoBound()
{
    // Far from steel but inside the bounds (the CLI's default 5-5000 W/(m K)): implausible, no bound.
    IdentificationOptions wide;
    const std::vector<PlausibilityFlag> flags = ParameterPlausibility::implausible(result(566.3, -141.0), wide, -141.0);
    const PlausibilityFlag *lambda = flag(flags, "lambda");
    QVERIFY(lambda);
    QVERIFY(!QString::fromStdString(lambda->message).contains(QStringLiteral("bound")));
    // Steel's value and the drawing's P_f inside the diagnosis bounds: nothing said of them.
    const std::vector<PlausibilityFlag> fine = ParameterPlausibility::implausible(result(45.0, -140.0), diagnosisBounds(-141.0), -141.0);
    QVERIFY(!flag(fine, "lambda"));
    QVERIFY(!flag(fine, "P_f"));
}

QTEST_APPLESS_MAIN(TestParameterPlausibility)
#include "tst_parameterplausibility.moc"

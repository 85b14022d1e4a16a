// DiscrepancyTerm (issue 18, item 3) on residuals with known truth: a term driven by a
// neighbouring unit's temperature through a one-hour first-order lag, growing along the travel,
// must be found (driver, time scale, position shape, coefficient), predict another recording
// with a different duty cycle, and be described in words; pure noise must give no term.

#include "DiscrepancyTerm.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

class TestDiscrepancyTerm : public QObject {
    Q_OBJECT
private slots:
    void findsTheLaggedPositionDependentDriver();
    void noTermOnNoise();

private:
    // A recording with ambient, structure and hydraulic_unit channels (1 s apart is not needed:
    // 30 s) and interferometer points every 20 min at 7 targets; residual = truth + noise.
    static DiagnosisRecording make(double period_s, unsigned seed, double coefficient, std::vector<ObservationFit> &points);
    static double truthAt(const DiagnosisRecording &r, double t, double x, double coefficient);
};

namespace {
constexpr double kTau = 3600.0;
constexpr double kLo = 20.0, kHi = 500.0;
} // namespace

double TestDiscrepancyTerm::truthAt(const DiagnosisRecording &r, double t, double x, double coefficient)
{
    // The lag computed independently of the class: explicit Euler on a 1 s grid.
    const TimeSeries &u = r.channelsByRole.at("hydraulic_unit");
    double y = u.v.front(), y0 = y;
    for (double s = 0.0; s < t; s += 1.0) {
        y += (u.at(s) - y) / kTau;
    }
    const double xs = (x - 0.5 * (kLo + kHi)) / (0.5 * (kHi - kLo));
    return coefficient * (y - y0) * xs;
}

DiagnosisRecording TestDiscrepancyTerm::make(double period_s, unsigned seed, double coefficient, std::vector<ObservationFit> &points)
{
    DiagnosisRecording r;
    r.screw.referenceTime_s = 0.0;
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    TimeSeries ambient, structure, unit;
    for (double t = 0.0; t <= 4 * 3600.0; t += 30.0) {
        ambient.t.push_back(t);
        ambient.v.push_back(20.0 + 0.3 * std::sin(t / 5000.0) + 0.02 * noise(rng));
        structure.t.push_back(t);
        structure.v.push_back(20.0 + 0.8 * (1.0 - std::exp(-t / 6000.0)) + 0.02 * noise(rng));
        unit.t.push_back(t);
        unit.v.push_back(20.0 + (std::fmod(t, period_s) < 0.5 * period_s ? 6.0 : 0.0) + 0.02 * noise(rng));
    }
    r.channelsByRole["ambient"] = ambient;
    r.channelsByRole["structure"] = structure;
    r.channelsByRole["hydraulic_unit"] = unit;
    points.clear();
    for (double t = 0.0; t <= 4 * 3600.0; t += 1200.0)
        for (int k = 0; k < 7; ++k) {
            ObservationFit p;
            p.t_s = t;
            p.position_mm = kLo + (kHi - kLo) * k / 6.0;
            p.predicted_um = 1.0; // the model's prediction; the residual is measured - predicted
            p.measured_um = p.predicted_um + truthAt(r, t, p.position_mm, coefficient) + 0.1 * noise(rng);
            points.push_back(p);
        }
    return r;
}

void TestDiscrepancyTerm::findsTheLaggedPositionDependentDriver()
{
    std::vector<ObservationFit> train, other;
    const DiagnosisRecording a = make(5400.0, 1, 0.8, train);
    const DiagnosisRecording b = make(3600.0, 2, 0.8, other);
    const DiscrepancyTerm term;
    const DiscrepancyTerm::Fit fit = term.fit(a, train);
    QVERIFY(!fit.empty());
    const DiscrepancyTerm::Feature &lead = fit.terms.front();
    QCOMPARE(QString::fromStdString(lead.role), QStringLiteral("hydraulic_unit"));
    QCOMPARE(lead.tau_s, kTau);
    QCOMPARE(lead.power, 1);
    QVERIFY2(std::fabs(fit.coefficients.front() - 0.8) < 0.08, qPrintable(QString::number(fit.coefficients.front())));
    QVERIFY(fit.cvRmsAfter_um < 0.5 * fit.cvRmsBefore_um);
    // The other recording (another duty cycle): the term predicts its residual to about the noise.
    const std::vector<double> c = term.predict(fit, b, other);
    QCOMPARE(c.size(), other.size());
    double sq = 0.0, sq0 = 0.0;
    for (size_t i = 0; i < other.size(); ++i) {
        const double e = other[i].measured_um - other[i].predicted_um;
        sq0 += e * e;
        sq += (e - c[i]) * (e - c[i]);
    }
    const double before = std::sqrt(sq0 / other.size()), after = std::sqrt(sq / other.size());
    QVERIFY2(before > 0.5 && after < 0.2, qPrintable(QStringLiteral("%1 -> %2 um").arg(before).arg(after)));
    // In words: the driver, the time scale and the end (fixed end below the travel).
    const QString words = QString::fromStdString(DiscrepancyTerm::hypothesis(fit, -50.0));
    QVERIFY2(words.contains(QStringLiteral("'hydraulic_unit'")) && words.contains(QStringLiteral("60 min")) &&
                 words.contains(QStringLiteral("Empirical")),
             qPrintable(words));
    // Both ends carry the same magnitude for a pure x term; the sign at the fixed-end side is
    // negative, so the free end is where the error grows in the direction of the rise.
    QVERIFY2(words.contains(QStringLiteral("end of the screw")), qPrintable(words));
}

void TestDiscrepancyTerm::noTermOnNoise()
{
    std::vector<ObservationFit> train;
    const DiagnosisRecording a = make(5400.0, 3, 0.0, train);
    const DiscrepancyTerm::Fit fit = DiscrepancyTerm().fit(a, train);
    QVERIFY2(fit.empty(), fit.empty() ? "" : fit.terms.front().describe().c_str());
}

QTEST_GUILESS_MAIN(TestDiscrepancyTerm)
#include "tst_discrepancyterm.moc"

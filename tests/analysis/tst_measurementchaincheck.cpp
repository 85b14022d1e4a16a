// MeasurementChainCheck (issue 36 item 3) on residuals with a known sensor fault: a PT100 that
// jumps, an interferometer whose air compensation is off (1 um/m/K over the beam), a probe
// whose holder follows the bed. Each has a control with the same signal charged to the
// machine (both sensors see it, or another channel drives it), where no sensor may be named.

#include "DiagnosisEngine.h"
#include "DiagnosisTestRecording.h"
#include "MeasurementChainCheck.h"
#include "ScrewModelIdentifier.h"
#include "SyntheticScrewTest.h"

#include <QtTest>

#include <cmath>
#include <functional>
#include <random>

using namespace driftlab;

namespace {

constexpr double kHours = 4.0;

TimeSeries series(double period_s, const std::function<double(double)> &f, double noise, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, noise > 0 ? noise : 1.0);
    TimeSeries s;
    for (double t = 0.0; t <= kHours * 3600.0; t += period_s) {
        s.t.push_back(t);
        s.v.push_back(f(t) + (noise > 0 ? n(rng) : 0.0));
    }
    return s;
}

double airAt(double t, bool validation) { return 20.0 + (validation ? -0.8 : 1.1) * std::sin(t / 5000.0) + 0.1 * t / 3600.0; }
double bedAt(double t, bool validation) { return 21.0 + (validation ? 0.9 : 1.4) * (1.0 - std::exp(-t / 6000.0)); }
double motorAt(double t) { return t < 1000.0 ? 20.0 : 20.0 + 5.0 * (1.0 - std::exp(-(t - 1000.0) / 1800.0)); }

DiagnosisRecording recording(bool validation)
{
    DiagnosisRecording r;
    r.screw.name = validation ? "B" : "A";
    const unsigned seed = validation ? 20 : 10;
    r.channelsByRole["ambient"] = series(3.0, [=](double t) { return airAt(t, validation); }, 0.04, seed);
    r.channelsByRole["structure"] = series(3.0, [=](double t) { return bedAt(t, validation); }, 0.04, seed + 1);
    r.channelsByRole["motor"] = series(3.0, motorAt, 0.04, seed + 2);
    r.screw.drive.position_mm = series(10.0, [](double) { return 0.0; }, 0.0, 1);
    r.screw.drive.feed_mm_min = r.screw.drive.position_mm;
    r.screw.drive.ambient_C = r.channelsByRole["ambient"];
    r.screw.referenceTime_s = 60.0;
    for (double t = 1200.0; t < kHours * 3600.0; t += 1200.0)
        for (int k = 0; k < 9; ++k)
            r.screw.interferometer.push_back({t + 8.0 * k, 25.0 + 100.0 * k, 0.0});
    return r;
}

// Residual points (measured = the given residual, predicted 0): interferometer at every point
// of `r`, probe every 30 s.
std::vector<ObservationFit> residuals(const DiagnosisRecording &r, const std::function<double(const PositioningErrorPoint &)> &inter,
                                      const std::function<double(double)> &probe, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    std::vector<ObservationFit> out;
    for (const PositioningErrorPoint &p : r.screw.interferometer) {
        ObservationFit o;
        o.t_s = p.t_s;
        o.position_mm = p.position_mm;
        o.measured_um = inter(p) + 0.2 * n(rng);
        out.push_back(o);
    }
    for (double t = 0.0; t <= kHours * 3600.0; t += 30.0) {
        ObservationFit o;
        o.elongation = true;
        o.t_s = t;
        o.measured_um = probe(t) + 0.15 * n(rng);
        out.push_back(o);
    }
    return out;
}

} // namespace

class TestMeasurementChainCheck : public QObject {
    Q_OBJECT
private slots:
    void namesAJumpingPt100AndUndoesIt();
    void heatIsNotAStepNorIsACommonJump();
    void aCyclingHeaterIsNotAStep();
    void namesTheInterferometerFollowingTheAir();
    void airLawOnAnotherChannelIsTheMachine();
    void namesTheProbeFollowingTheBed();
    void probeAndInterferometerAgreeingIsTheMachine();
    void airLawThroughTheWholeCheck_data();
    void airLawThroughTheWholeCheck();
    void judgedAgainstTheMachineAsBuilt();
};

void TestMeasurementChainCheck::namesAJumpingPt100AndUndoesIt()
{
    DiagnosisRecording r = recording(false);
    const TimeSeries clean = r.channelsByRole["ambient"];
    for (size_t i = 0; i < r.channelsByRole["ambient"].size(); ++i)
        if (r.channelsByRole["ambient"].t[i] >= 5001.0) {
            r.channelsByRole["ambient"].v[i] += 0.6;
            r.screw.drive.ambient_C.v[i] += 0.6;
        }
    const std::vector<SensorFinding> f = MeasurementChainCheck::correctSteps(r);
    QCOMPARE(f.size(), size_t(1));
    QCOMPARE(f[0].role, std::string("ambient"));
    QCOMPARE(f[0].kind, std::string("step"));
    QVERIFY2(std::fabs(f[0].coefficient - 0.6) < 0.05, std::to_string(f[0].coefficient).c_str());
    QVERIFY2(std::fabs(f[0].time_s - 5001.0) < 4.0, std::to_string(f[0].time_s).c_str());
    QVERIFY(f[0].law.find("ambient PT100") != std::string::npos);
    // Corrected: the channel and the drive's ambient are back to the clean reading (within
    // the step's own error).
    double worst = 0.0;
    for (size_t i = 0; i < clean.size(); ++i) {
        worst = std::max(worst, std::fabs(r.channelsByRole["ambient"].v[i] - clean.v[i]));
        worst = std::max(worst, std::fabs(r.screw.drive.ambient_C.v[i] - clean.v[i]));
    }
    QVERIFY2(worst < 0.05, std::to_string(worst).c_str());
}

void TestMeasurementChainCheck::heatIsNotAStepNorIsACommonJump()
{
    // The motor's warm-up (a kink at t = 1000 s with 10 mK/s afterwards) is heat, not a step.
    DiagnosisRecording r = recording(false);
    QVERIFY(MeasurementChainCheck::steps(r, {}).empty());
    // A jump every channel shares (the logger's offset) is not one sensor's fault.
    for (auto &c : r.channelsByRole)
        for (size_t i = 0; i < c.second.size(); ++i)
            if (c.second.t[i] >= 7001.0)
                c.second.v[i] += 0.5;
    QVERIFY(MeasurementChainCheck::steps(r, {}).empty());
}

// The rig's hydraulic unit ('none' seed 1, issue 36): a heater on for half of an 8573 s period,
// 7.9 K above the air through a 1200 s first-order lag, a 1 Hz PT100 with 0.02 K noise. Where it
// switches, the temperature bends hard (6.6 mK/s of slope reversing over minutes); lines over
// 300 s on either side then disagree at the kink by ~0.3 K, 15-17 x the channel's spread: it
// was named a -0.31 K step in both recordings. Nothing jumps, nothing may be named; a real
// 0.4 K jump on the same channel, half-way through an off phase, still is.
void TestMeasurementChainCheck::aCyclingHeaterIsNotAStep()
{
    DiagnosisRecording r = recording(false);
    TimeSeries &h = r.channelsByRole["hydraulic_unit"];
    std::mt19937 rng(7);
    std::normal_distribution<double> n(0.0, 0.02);
    const double period = 8573.466609863466, phase = 2661.1073996495256, tau = 1200.0, rise = 7.904053980913378;
    double lag = 0.0;
    for (double t = 0.0; t <= kHours * 3600.0; t += 1.0) {
        const bool on = std::fmod(t + phase, period) < 0.5 * period;
        lag += (1.0 - std::exp(-1.0 / tau)) * ((on ? rise : 0.0) - lag);
        h.t.push_back(t);
        h.v.push_back(20.0 + lag + n(rng));
    }
    QVERIFY(MeasurementChainCheck::steps(r, {}).empty());
    // An off phase runs from t = 0.5 period - phase = 1626 s to 5913 s: a jump at 4000 s.
    for (size_t i = 0; i < h.size(); ++i)
        if (h.t[i] >= 4000.0)
            h.v[i] += 0.4;
    const std::vector<SensorFinding> f = MeasurementChainCheck::steps(r, {});
    QCOMPARE(f.size(), size_t(1));
    QCOMPARE(f[0].role, std::string("hydraulic_unit"));
    QVERIFY2(std::fabs(f[0].coefficient - 0.4) < 0.05, std::to_string(f[0].coefficient).c_str());
}

void TestMeasurementChainCheck::namesTheInterferometerFollowingTheAir()
{
    // Beam from a laser head at -40 mm: error 1 um/m/K x (x + 40 mm) x dT_air; the probe
    // sees white noise only.
    const DiagnosisRecording a = recording(false), b = recording(true);
    auto law = [](const DiagnosisRecording &r, bool validation) {
        return [&r, validation](const PositioningErrorPoint &p) {
            return 1.0 * (p.position_mm + 40.0) / 1000.0 * (airAt(p.t_s, validation) - airAt(r.screw.referenceTime_s, validation));
        };
    };
    const auto fa = residuals(a, law(a, false), [](double) { return 0.0; }, 1);
    const auto fb = residuals(b, law(b, true), [](double) { return 0.0; }, 2);
    const std::vector<SensorFinding> f = MeasurementChainCheck::check(a, b, fa, fb, {}, {});
    QCOMPARE(f.size(), size_t(1));
    QCOMPARE(f[0].sensor, std::string("interferometer"));
    QCOMPARE(f[0].driver, std::string("ambient"));
    QVERIFY2(std::fabs(f[0].coefficient - 1.0) < 0.15, std::to_string(f[0].coefficient).c_str());
    // The law at both ends of the travel (the split into slope and offset is less certain).
    for (const double x : {25.0, 825.0}) {
        const double law = f[0].coefficient * x / 1000.0 + f[0].intercept, truth = (x + 40.0) / 1000.0;
        QVERIFY2(std::fabs(law - truth) < 0.25, (std::to_string(x) + ": " + std::to_string(law)).c_str());
    }
    QVERIFY(f[0].law.find("follows the air temperature at ") != std::string::npos);
    // Corrected: the air law leaves the interferometer readings.
    DiagnosisRecording c = a;
    for (size_t i = 0; i < c.screw.interferometer.size(); ++i)
        c.screw.interferometer[i].error_um = law(a, false)(c.screw.interferometer[i]);
    MeasurementChainCheck::correct(c, f[0]);
    double worst = 0.0;
    for (const PositioningErrorPoint &p : c.screw.interferometer)
        worst = std::max(worst, std::fabs(p.error_um));
    QVERIFY2(worst < 0.3, std::to_string(worst).c_str()); // of up to 1.2 um before
    // No fault: nothing named.
    const auto na = residuals(a, [](const PositioningErrorPoint &) { return 0.0; }, [](double) { return 0.0; }, 3);
    const auto nb = residuals(b, [](const PositioningErrorPoint &) { return 0.0; }, [](double) { return 0.0; }, 4);
    QVERIFY(MeasurementChainCheck::check(a, b, na, nb, {}, {}).empty());
}

void TestMeasurementChainCheck::airLawOnAnotherChannelIsTheMachine()
{
    // The same size of law driven by the bed (a structure effect): not the interferometer.
    const DiagnosisRecording a = recording(false), b = recording(true);
    auto law = [](const DiagnosisRecording &r, bool validation) {
        return [&r, validation](const PositioningErrorPoint &p) {
            return 1.5 * (p.position_mm + 40.0) / 1000.0 * (bedAt(p.t_s, validation) - bedAt(r.screw.referenceTime_s, validation));
        };
    };
    const auto fa = residuals(a, law(a, false), [](double) { return 0.0; }, 5);
    const auto fb = residuals(b, law(b, true), [](double) { return 0.0; }, 6);
    QVERIFY(MeasurementChainCheck::check(a, b, fa, fb, {}, {}).empty());
    // The air law, but the probe follows the air as strongly: the screw, not the beam.
    auto airLaw = [](const DiagnosisRecording &r, bool validation) {
        return [&r, validation](const PositioningErrorPoint &p) {
            return 1.0 * (p.position_mm + 40.0) / 1000.0 * (airAt(p.t_s, validation) - airAt(r.screw.referenceTime_s, validation));
        };
    };
    const auto ga = residuals(a, airLaw(a, false), [](double t) { return 1.2 * (airAt(t, false) - airAt(0.0, false)); }, 7);
    const auto gb = residuals(b, airLaw(b, true), [](double t) { return 1.2 * (airAt(t, true) - airAt(0.0, true)); }, 8);
    QVERIFY(MeasurementChainCheck::check(a, b, ga, gb, {}, {}).empty());
}

void TestMeasurementChainCheck::namesTheProbeFollowingTheBed()
{
    // The probe's disagreement with the interferometer-only model: 3 um/K x dT_bed.
    const DiagnosisRecording a = recording(false), b = recording(true);
    const auto none = [](const PositioningErrorPoint &) { return 0.0; };
    const auto fa = residuals(a, none, [](double t) { return 3.0 * (bedAt(t, false) - bedAt(0.0, false)); }, 9);
    const auto fb = residuals(b, none, [](double t) { return 3.0 * (bedAt(t, true) - bedAt(0.0, true)); }, 10);
    const std::vector<SensorFinding> f = MeasurementChainCheck::check(a, b, fa, fb, fa, fb);
    QCOMPARE(f.size(), size_t(1));
    QCOMPARE(f[0].role, std::string("screw_elongation"));
    QCOMPARE(f[0].driver, std::string("structure"));
    QVERIFY2(std::fabs(f[0].coefficient - 3.0) < 0.3, std::to_string(f[0].coefficient).c_str());
    DiagnosisRecording c = a;
    c.screw.elongation_um = series(10.0, [](double) { return 0.0; }, 0.0, 1);
    MeasurementChainCheck::correct(c, f[0]);
    QVERIFY(c.screw.elongation_um.empty()); // left out, not charged to the machine
}

void TestMeasurementChainCheck::probeAndInterferometerAgreeingIsTheMachine()
{
    // The screw really follows the bed: the interferometer sees it too (in proportion to the
    // nut's distance from the fixed end) - not a sensor fault.
    const DiagnosisRecording a = recording(false), b = recording(true);
    auto inter = [](const DiagnosisRecording &r, bool validation) {
        return [&r, validation](const PositioningErrorPoint &p) {
            return 3.0 * (p.position_mm + 100.0) / 1000.0 * (bedAt(p.t_s, validation) - bedAt(r.screw.referenceTime_s, validation));
        };
    };
    const auto fa = residuals(a, inter(a, false), [](double t) { return 3.0 * (bedAt(t, false) - bedAt(0.0, false)); }, 11);
    const auto fb = residuals(b, inter(b, true), [](double t) { return 3.0 * (bedAt(t, true) - bedAt(0.0, true)); }, 12);
    const std::vector<SensorFinding> f = MeasurementChainCheck::check(a, b, fa, fb, fa, fb);
    QVERIFY2(f.empty(), f.empty() ? "" : f[0].law.c_str());
}

namespace {

// A pair recorded by the explicit seed-000 model on a fine grid (SyntheticScrewTest) in a hall
// whose air swings, the interferometer's air compensation off by `k` um/m/K over a beam
// from a head 60 mm below the travel (error k (x + 60 mm) (T_air(t) - T_air(t_ref)));
// the air swings by +-1.5 K over 4 h (3.5 h in B).
DiagnosisRecording airRecording(bool validation, double k_um_mK)
{
    SyntheticTestSpec spec;
    spec.name = validation ? "B" : "A";
    spec.phases = validation ? std::vector<SyntheticPhase>{{2400, 4500}, {1800, 0}, {3600, 7500}}
                             : std::vector<SyntheticPhase>{{3000, 6000}, {1800, 0}, {2400, 9000}, {2400, 0}, {1200, 3000}};
    spec.seed = validation ? 4 : 3;
    spec.ambientAmplitude_K = 1.0;
    spec.ambientAmplitude_K = 1.5;
    spec.ambientPeriod_s = validation ? 3.5 * 3600.0 : 4.0 * 3600.0;
    spec.interferometerInterval_s = 900.0;
    spec.targets_mm = {20, 100, 180, 260, 340, 420, 500};
    spec.probeInterval_s = 5.0;
    spec.driveInterval_s = 1.0;
    FdmParameters truth;
    truth.conductivity_W_mK = 45.0;
    DiagnosisRecording r;
    r.screw = SyntheticScrewTest::generate(spec, ScrewGeometry{}, truth, FdmSettings{0.01, 0.2});
    r.drawingFixedEnd_mm = truth.fixedEndPosition_mm;
    r.channelsByRole["ambient"] = r.screw.drive.ambient_C;
    for (PositioningErrorPoint &p : r.screw.interferometer) {
        const double ref = MeasurementChainCheck::referenceTime(r.screw, p);
        p.error_um += k_um_mK * (p.position_mm + 60.0) / 1000.0 * (spec.ambientAt(p.t_s) - spec.ambientAt(ref));
    }
    return r;
}

} // namespace

// examine() as the diagnosis runs it, on model-exact recordings (the baseline fits them but for
// the fault): the baseline's own fit bends to absorb part of an air law (othersim: its residual
// kept t = -1.3 of 0.93 um/m/K), the joint refit with the probe anchoring the screw does not.
void TestMeasurementChainCheck::airLawThroughTheWholeCheck_data()
{
    QTest::addColumn<double>("k");
    QTest::newRow("compensation off, 1 um/m/K") << 1.0;
    QTest::newRow("clean") << 0.0;
}

void TestMeasurementChainCheck::airLawThroughTheWholeCheck()
{
    QFETCH(double, k);
    DiagnosisRecording a = airRecording(false, k), b = airRecording(true, k);
    IdentificationOptions opts;
    opts.simulator.grid.dt_s = 20.0;
    opts.simulator.driveSample_s = 1.0;
    opts.maxIterations = 60;
    ScrewModelIdentifier id(ScrewGeometry{}, opts);
    const IdentificationResult base = id.fit({a.screw});
    opts.initial = base.parameters; // later fits start here, as in DiagnosisEngine
    opts.initial = base.parameters; // later fits start here, as in DiagnosisEngine
    const FitStatistics heldout = id.predict(base, {b.screw});
    const std::vector<SensorFinding> f =
        MeasurementChainCheck::examine(a, b, ScrewGeometry{}, opts, base.fit.points, heldout.points);
    if (k == 0.0) {
        QVERIFY2(f.empty(), f.empty() ? "" : f.front().law.c_str());
        return;
    }
    QCOMPARE(f.size(), size_t(1));
    QCOMPARE(f.front().kind, std::string("air"));
    QCOMPARE(f.front().driver, std::string("ambient"));
    // Within 0.5 um/m/K: on this model-exact pair the joint refit reads +0.40 um/m/K on the clean
    // training recording (+0.22 on the validation one) and 1.40 with the fault, i.e. the law to the
    // digit on top of a bias the identifier and SyntheticScrewTest share no explanation for yet
    // (docs/diagnosis.md). The residual regression alone read 1.51 here.
    QVERIFY2(std::fabs(f.front().coefficient - k) <= 0.5, std::to_string(f.front().coefficient).c_str());
    // Corrected: B's readings carry less than 0.5 um of the law anywhere on the travel (0.56 um/K x
    // dT_air at the last target before).
    const DiagnosisRecording clean = airRecording(true, 0.0);
    for (size_t i = 0; i < b.screw.interferometer.size(); ++i)
        QVERIFY(std::fabs(b.screw.interferometer[i].error_um - clean.screw.interferometer[i].error_um) < 0.5);
}

// The chain check inside the diagnosis judges the sensors against the diagnosis's own machine
// (issue 36; DiagnosisOptions::housingContactBaseline): seed 000 with housings that follow a
// 1 K air drift through 1000 s and touch the screw at 0.3 / 0.2 W/K (the machine as built),
// and a probe whose holder follows the bed at 3 um/K (the bed: the air through 3000 s plus its
// own 0.8 K warm-up). With the contacts in the check's interferometer-only refit the
// interferometer's own residual is white and the probe alone follows the bed: named, left out,
// and the machine is answered `none`.
void TestMeasurementChainCheck::judgedAgainstTheMachineAsBuilt()
{
    constexpr double kProbe_um_K = 3.0;
    auto faulty = [](bool validation) {
        DiagnosisRecording r = diagnosisTestWithHousings(validation, 0.3, 0.2, 1.0);
        TimeSeries bed = firstOrderLag(r.screw.drive.ambient_C, 3000.0);
        for (size_t k = 0; k < bed.size(); ++k)
            bed.v[k] += 0.8 * (1.0 - std::exp(-(bed.t[k] - bed.t.front()) / 5000.0));
        r.channelsByRole["structure"] = bed;
        for (size_t k = 0; k < r.screw.elongation_um.size(); ++k)
            r.screw.elongation_um.v[k] += kProbe_um_K * (bed.at(r.screw.elongation_um.t[k]) - bed.v.front());
        return r;
    };
    const DiagnosisRecording a = faulty(false), b = faulty(true);
    DiagnosisOptions o = diagnosisTestOptions({"heat_path_lag", "structure_offset", "structure_linear"});
    o.empiricalTerms = false;
    o.checkMeasurementChain = true;
    o.housingContactBaseline = true;
    const DiagnosisReport r = DiagnosisEngine(ScrewGeometry{}, o).run(a, b);
    for (const SensorFinding &f : r.measurementChain)
        qInfo("finding: %s", f.law.c_str());
    qInfo("answer %s, held-out RMS of the baseline %.3f um", r.effect.c_str(), r.baseline.heldoutRms_um);
    QCOMPARE(r.measurementChain.size(), size_t(1));
    QCOMPARE(r.measurementChain.front().role, std::string("screw_elongation"));
    QCOMPARE(r.measurementChain.front().driver, std::string("structure"));
    QVERIFY2(std::fabs(r.measurementChain.front().coefficient - kProbe_um_K) < 0.3,
             std::to_string(r.measurementChain.front().coefficient).c_str());
    QCOMPARE(r.effect, std::string("none"));
}

QTEST_GUILESS_MAIN(TestMeasurementChainCheck)
#include "tst_measurementchaincheck.moc"

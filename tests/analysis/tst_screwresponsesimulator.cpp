// Tests of the unit-response simulator behind the identification:
//  - with one drive sample per step and the whole-cell nut rule it reproduces
//    CrankNicolsonScrewModel (run here independently) for ambient + k3 + k4 exactly;
//  - with 20 s steps and step-averaged nut heat it follows the explicit model on a finer
//    grid (dx/2, dt/2) over the Table-2 programme;
//  - energy conservation of every heat column without convection (k1 = k2 = 0):
//    elongation = alpha * integral(Q dt) / (rho c A), also for the lagged motor source;
//  - error-term columns against their definitions;
//  - a contact conductance (ChannelHeatSource contact mode) to a housing held Delta T above
//    ambient: spread uniformly it is the lumped exponential Delta T (1 - exp(-t g / (rho c A)))
//    exactly; at the bearing or under the nut the screw relaxes to the housing temperature.

#include "BearingHeatSource.h"
#include "ChannelHeatSource.h"
#include "CrankNicolsonScrewModel.h"
#include "EndHeatSource.h"
#include "NutHeatSource.h"
#include "ScaleExpansionTerm.h"
#include "ScrewResponseSimulator.h"
#include "StructureDriftTerm.h"
#include "SyntheticScrewTest.h"

#include <QtTest>

#include <cmath>
#include <limits>

using namespace driftlab;

namespace {
constexpr double kPi = 3.14159265358979323846;

std::vector<std::shared_ptr<HeatSourceComponent>> seedSources()
{
    return {std::make_shared<BearingHeatSource>(), std::make_shared<NutHeatSource>()};
}

SyntheticTestSpec shortProgramme(double feed)
{
    SyntheticTestSpec s = SyntheticTestSpec::seed000Table2(feed);
    s.phases = {{30 * 60.0, feed}, {15 * 60.0, 0.0}, {15 * 60.0, feed * 1.5}};
    s.interferometerNoise_um = 0.0;
    s.probeNoise_um = 0.0;
    s.probeInterval_s = 7.3; // between step boundaries: exercises the interpolation
    return s;
}
} // namespace

class TestScrewResponseSimulator : public QObject {
    Q_OBJECT
private slots:
    void reproducesCrankNicolsonModel();
    void largeStepsFollowFineExplicitModel();
    void heatColumnsConserveEnergy();
    void errorTermColumns();
    void referenceRunIsSubtracted();
    void threadsGiveSameResult();
    void rejectsBadRecordings();
    void contactRelaxesToHousingTemperature();
};

void TestScrewResponseSimulator::reproducesCrankNicolsonModel()
{
    const ScrewGeometry g;
    const FdmParameters p;
    const SyntheticTestSpec spec = shortProgramme(5400.0);
    ScrewRecording rec = SyntheticScrewTest::generate(spec, g, p, FdmSettings{});
    for (double t = 30.0; t < 3600.0; t += 97.3) // screw temperature rows (values unused)
        for (double x : {0.004, 0.2, 0.555, 0.799})
            rec.screwTemperatures.push_back({t, x, 0.0});
    ResponseSimulatorOptions o;
    o.grid = FdmSettings{0.01, 0.1};
    o.driveSample_s = 0.1;
    o.fractionalNut = false;
    o.elongationInterval_s = 0.0;
    ScrewResponseSimulator sim(g, {rec}, o, seedSources());
    Eigen::MatrixXd phi;
    sim.simulate(p.k1, p.k2, p.conductivity_W_mK, p.fixedEndPosition_mm, phi);
    QCOMPARE(phi.cols(), 3);
    const Eigen::VectorXd pred = phi.col(0) + p.k3 * phi.col(1) + p.k4 * phi.col(2);

    // Independent run of the implicit model on the same drive samples; outputs at the step
    // boundaries around each observation, interpolated linearly in time.
    CrankNicolsonScrewModel cn(g, p, o.grid);
    TimeSeries::Cursor pos(rec.drive.position_mm), feed(rec.drive.feed_mm_min), amb(rec.drive.ambient_C);
    cn.reset(amb.at(0.0));
    const auto &obs = sim.observations();
    std::vector<std::pair<double, double>> prevNow(obs.size()); // value at floor / ceil boundary
    double worst = 0.0, peak = 0.0;
    const double ambient0 = amb.at(0.0);
    int temperatureRows = 0;
    auto outputs = [&](const ResponseObservation &ob) {
        if (ob.temperature)
            return cn.temperatures()[static_cast<size_t>(std::floor(ob.distance_m / 0.01))] - ambient0;
        return ob.elongation ? cn.elongation_um() : cn.thermalError_um(ob.position_mm);
    };
    for (const ResponseObservation &ob : sim.observations())
        temperatureRows += ob.temperature ? 1 : 0;
    QVERIFY(temperatureRows > 100);
    size_t next = 0;
    std::vector<size_t> order(obs.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return obs[a].t_s < obs[b].t_s; });
    long k = 0;
    while (next < order.size()) {
        const ResponseObservation &ob = obs[order[next]];
        const double tb = k * 0.1;
        if (tb + 1e-9 >= ob.t_s) {
            // ob lies in (t_{k-1}, t_k]: interpolate with the previous boundary value.
            const double before = prevNow[order[next]].first;
            const double w = (ob.t_s - (k - 1) * 0.1) / 0.1;
            const double value = k == 0 ? outputs(ob) : before + std::clamp(w, 0.0, 1.0) * (outputs(ob) - before);
            worst = std::max(worst, std::fabs(value - pred[static_cast<Eigen::Index>(order[next])]));
            peak = std::max(peak, std::fabs(value));
            ++next;
            continue;
        }
        for (size_t q = next; q < order.size() && obs[order[q]].t_s <= tb + 0.1 + 1e-9; ++q)
            prevNow[order[q]].first = outputs(obs[order[q]]);
        const double t = k * 0.1;
        cn.step(pos.at(t), feed.at(t), amb.at(t + 0.1));
        ++k;
    }
    QVERIFY(peak > 5.0);
    QVERIFY2(worst < 1e-8 * peak, qPrintable(QString("max deviation %1 um of peak %2 um").arg(worst).arg(peak)));
}

void TestScrewResponseSimulator::largeStepsFollowFineExplicitModel()
{
    const ScrewGeometry g;
    const FdmParameters p;
    SyntheticTestSpec spec = SyntheticTestSpec::seed000Table2(5400.0);
    spec.interferometerNoise_um = spec.probeNoise_um = 0.0;
    const ScrewRecording truth = SyntheticScrewTest::generate(spec, g, p, FdmSettings{0.005, 0.05});
    ResponseSimulatorOptions o; // dx 0.01, dt 20 s, fractional nut
    ScrewResponseSimulator sim(g, {truth}, o, seedSources());
    Eigen::MatrixXd phi;
    sim.simulate(p.k1, p.k2, p.conductivity_W_mK, p.fixedEndPosition_mm, phi);
    const Eigen::VectorXd pred = phi.col(0) + p.k3 * phi.col(1) + p.k4 * phi.col(2);
    double worst = 0.0, peak = 0.0;
    for (int r = 0; r < sim.rowCount(); ++r) {
        worst = std::max(worst, std::fabs(pred[r] - sim.observations()[static_cast<size_t>(r)].measured_um));
        peak = std::max(peak, std::fabs(sim.observations()[static_cast<size_t>(r)].measured_um));
    }
    qInfo("20 s implicit steps vs explicit dx/2, dt/2: max deviation %.3f um of peak %.2f um", worst, peak);
    QVERIFY(peak > 20.0);
    // Grid (dx 10 vs 5 mm: nut/bearing cell coverage) and step averaging: 2 % of the peak.
    QVERIFY2(worst < 0.02 * peak, qPrintable(QString("max deviation %1 um of peak %2 um").arg(worst).arg(peak)));
}

void TestScrewResponseSimulator::heatColumnsConserveEnergy()
{
    const ScrewGeometry g;
    SyntheticTestSpec spec = shortProgramme(6000.0);
    spec.phases.push_back({3 * 3600.0, 0.0}); // long standstill so the lagged source settles
    spec.interferometerInterval_s = 1e9;
    spec.probeInterval_s = 60.0;
    FdmParameters truth;
    const ScrewRecording rec = SyntheticScrewTest::generate(spec, g, truth, FdmSettings{});
    auto lagged = std::make_shared<EndHeatSource>(EndHeatSource::End::Free, 1.0, false, 900.0);
    std::vector<std::shared_ptr<HeatSourceComponent>> sources = seedSources();
    sources.push_back(std::make_shared<EndHeatSource>(EndHeatSource::End::Fixed));
    sources.push_back(lagged);
    ResponseSimulatorOptions o;
    ScrewResponseSimulator sim(g, {rec}, o, sources);
    Eigen::MatrixXd phi;
    sim.simulate(0.0, 0.0, 300.0, -141.0, phi); // no convection at all
    // Energy per unit amplitude: integral of v dt (W s per W/(mm/min)).
    double energy = 0.0;
    for (const SyntheticPhase &ph : spec.phases)
        energy += ph.feed_mm_min * ph.duration_s;
    const double area = kPi * g.diameter_m * g.diameter_m / 4.0;
    const double expected = g.expansion_per_K * energy / (g.density_kg_m3 * g.specificHeat_J_kgK * area) * 1e6;
    const int last = sim.rowCount() - 1;
    QVERIFY(sim.observations()[static_cast<size_t>(last)].elongation);
    for (int c = 1; c <= 4; ++c) {
        const double e = phi(last, c);
        // The lagged source has released all but exp(-3 h / 900 s) of its heat.
        const double tol = c == 4 ? 1e-4 : 1e-9;
        QVERIFY2(std::fabs(e - expected) < tol * expected,
                 qPrintable(QString("column %1: %2 um vs %3 um").arg(c).arg(e).arg(expected)));
    }
}

void TestScrewResponseSimulator::errorTermColumns()
{
    const ScrewGeometry g;
    SyntheticTestSpec spec = shortProgramme(3000.0);
    spec.ambientAmplitude_K = 1.0;
    spec.ambientPeriod_s = 3600.0;
    const ScrewRecording rec = SyntheticScrewTest::generate(spec, g, FdmParameters{}, FdmSettings{});
    ScrewResponseSimulator sim(g, {rec}, ResponseSimulatorOptions{}, seedSources(),
                               {std::make_shared<ScaleExpansionTerm>(), std::make_shared<StructureDriftTerm>()});
    Eigen::MatrixXd phi;
    sim.simulate(1e-3, 20.0, 500.0, -141.0, phi);
    QCOMPARE(phi.cols(), 5);
    int checked = 0;
    for (int r = 0; r < sim.rowCount(); ++r) {
        const ResponseObservation &o = sim.observations()[static_cast<size_t>(r)];
        const double dT = spec.ambientAt(o.t_s) - spec.ambientAt(0.0);
        const double scale = o.elongation ? 0.0 : dT * o.position_mm * 1e-3;
        const double drift = o.elongation ? 0.0 : dT;
        QVERIFY(std::fabs(phi(r, 3) - scale) < 1e-6);
        QVERIFY(std::fabs(phi(r, 4) - drift) < 1e-6);
        checked += o.elongation ? 0 : 1;
    }
    QVERIFY(checked > 50);
}

void TestScrewResponseSimulator::referenceRunIsSubtracted()
{
    // Interferometer rows are TE(P, t) - TE(P, t_ref): with a reference run at 900 s every
    // row must drop by the model's error at that time and target (read from an observation
    // placed exactly there), also when the reference time is given per point.
    const ScrewGeometry g;
    ScrewRecording rec = SyntheticScrewTest::generate(shortProgramme(6000.0), g, FdmParameters{}, FdmSettings{});
    rec.elongation_um = TimeSeries{};
    rec.referenceTime_s = std::numeric_limits<double>::quiet_NaN();
    const size_t n = rec.interferometer.size();
    for (size_t i = 0; i < n; ++i)
        rec.interferometer.push_back({900.0, rec.interferometer[i].position_mm, 0.0});
    ScrewRecording withRef = rec;
    withRef.interferometer.resize(n);
    for (size_t i = 0; i < n; ++i)
        withRef.interferometer[i].referenceTime_s = i % 2 ? 900.0 : std::numeric_limits<double>::quiet_NaN();
    withRef.referenceTime_s = 900.0;
    const FdmParameters p;
    std::vector<Eigen::MatrixXd> phi(2);
    ScrewResponseSimulator a(g, {rec}, ResponseSimulatorOptions{}, seedSources());
    ScrewResponseSimulator b(g, {withRef}, ResponseSimulatorOptions{}, seedSources());
    a.simulate(p.k1, p.k2, p.conductivity_W_mK, p.fixedEndPosition_mm, phi[0]);
    b.simulate(p.k1, p.k2, p.conductivity_W_mK, p.fixedEndPosition_mm, phi[1]);
    double worst = 0.0, shift = 0.0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const Eigen::Index r = static_cast<Eigen::Index>(i);
            const double expected = phi[0](r, c) - phi[0](static_cast<Eigen::Index>(n + i), c);
            worst = std::max(worst, std::fabs(phi[1](r, c) - expected));
            shift = std::max(shift, std::fabs(phi[0](static_cast<Eigen::Index>(n + i), c)));
        }
    QVERIFY(shift > 1e-3);
    QVERIFY2(worst < 1e-9 * shift * 1e3, qPrintable(QString("deviation %1").arg(worst)));
}

void TestScrewResponseSimulator::threadsGiveSameResult()
{
    // Three recordings on 1 and on 3 threads, with a stateful (lagged) source: identical.
    const ScrewGeometry g;
    std::vector<ScrewRecording> recs;
    for (double f : {3000.0, 5000.0, 7000.0})
        recs.push_back(SyntheticScrewTest::generate(shortProgramme(f), g, FdmParameters{}, FdmSettings{}));
    std::vector<Eigen::MatrixXd> phi(2);
    for (int k = 0; k < 2; ++k) {
        ResponseSimulatorOptions o;
        o.threads = k == 0 ? 1 : 3;
        std::vector<std::shared_ptr<HeatSourceComponent>> sources = seedSources();
        sources.push_back(std::make_shared<EndHeatSource>(EndHeatSource::End::Free, 1.0, false, 600.0));
        ScrewResponseSimulator sim(g, recs, o, sources);
        sim.simulate(1e-3, 20.0, 400.0, -141.0, phi[static_cast<size_t>(k)]);
    }
    QCOMPARE(phi[0].rows(), phi[1].rows());
    QVERIFY(phi[0].cwiseAbs().maxCoeff() > 0);
    QCOMPARE((phi[0] - phi[1]).cwiseAbs().maxCoeff(), 0.0);
}

void TestScrewResponseSimulator::contactRelaxesToHousingTemperature()
{
    const ScrewGeometry g;
    const double hours = 12.0, dT = 2.0, t0 = 100.0;
    // Standstill with the nut at 300 mm, constant ambient, probe samples every 60 s.
    ScrewRecording rec;
    rec.name = "contact";
    for (double t = t0; t <= t0 + hours * 3600.0 + 1e-9; t += 60.0) {
        rec.drive.position_mm.t.push_back(t);
        rec.drive.position_mm.v.push_back(300.0);
        rec.drive.feed_mm_min.t.push_back(t);
        rec.drive.feed_mm_min.v.push_back(0.0);
        rec.drive.ambient_C.t.push_back(t);
        rec.drive.ambient_C.v.push_back(21.0);
        if (t > t0) {
            rec.elongation_um.t.push_back(t);
            rec.elongation_um.v.push_back(0.0);
        }
    }
    for (double d : {0.005, 0.1, 0.3, 0.5, 0.79}) {
        ScrewTemperaturePoint tp;
        tp.t_s = t0 + hours * 3600.0;
        tp.distance_m = d;
        tp.temperature_C = 21.0;
        rec.screwTemperatures.push_back(tp);
    }
    TimeSeries housing = rec.drive.ambient_C;
    for (double &v : housing.v)
        v += dT;
    const double area = kPi * g.diameter_m * g.diameter_m / 4.0;
    const double rhoC = g.density_kg_m3 * g.specificHeat_J_kgK;
    const double full = g.expansion_per_K * g.length_m * dT * 1e6; // um, whole screw at T_a + dT

    using Location = ChannelHeatSource::Location;
    for (Location where : {Location::Distributed, Location::FixedBearing, Location::Nut}) {
        // Distributed: g in W/(m K); elsewhere G in W/K.
        const double G = where == Location::Distributed ? 4.0 : 3.0;
        auto contact = std::make_shared<ChannelHeatSource>(ParameterSpec{"a", "1", 1.0, 0.0, 3.0, 1.0}, where, false,
                                                           ParameterSpec{"G", "W/K", G, 0.0, 20.0, 1.0});
        QCOMPARE(contact->nonlinearParameters().size(), size_t(1));
        contact->setNonlinearParameters(&G);
        contact->bind(&housing, &rec.drive.ambient_C, t0);
        std::vector<std::shared_ptr<HeatSourceComponent>> sources = seedSources();
        sources.push_back(contact);
        ScrewResponseSimulator sim(g, {rec}, ResponseSimulatorOptions{}, sources);
        Eigen::MatrixXd phi;
        sim.simulate(0.0, 0.0, 200.0, 0.0, phi); // no convection: the contact is the only path
        QVERIFY(phi.col(0).cwiseAbs().maxCoeff() < 1e-12); // constant ambient
        const double tau = rhoC * area / G;            // lumped, per metre (Distributed)
        double worst = 0.0;
        for (int r = 0; r < sim.rowCount(); ++r) {
            if (sim.observations()[static_cast<size_t>(r)].temperature)
                continue;
            const double t = sim.observations()[static_cast<size_t>(r)].t_s - t0;
            const double e = phi(r, 3);
            QVERIFY2(e >= -1e-9 && e <= full * (1.0 + 1e-9), qPrintable(QString("t = %1 s: %2 um").arg(t).arg(e)));
            if (where == Location::Distributed)
                worst = std::max(worst, std::fabs(e - full * (1.0 - std::exp(-t / tau))));
        }
        if (where == Location::Distributed)
            QVERIFY2(worst < 1e-3 * full, qPrintable(QString("lumped exponential off by %1 um").arg(worst)));
        // After 12 h (contact time constant rho c A L / G ~ 850 s, slowest axial mode
        // 4 L^2 rho c / (pi^2 lambda) ~ 1.3 h) the whole screw sits at the housing temperature.
        int last = -1;
        for (int r = 0; r < sim.rowCount(); ++r) {
            const ResponseObservation &o = sim.observations()[static_cast<size_t>(r)];
            if (o.temperature)
                QVERIFY2(std::fabs(phi(r, 3) - dT) < 2e-3 * dT,
                         qPrintable(QString("location %1: %2 K at %3 m after 12 h, housing %4 K")
                                        .arg(int(where)).arg(phi(r, 3)).arg(o.distance_m).arg(dT)));
            else
                last = r;
        }
        QVERIFY(last > 0);
        const double end = phi(last, 3);
        QVERIFY2(std::fabs(end - full) < 2e-3 * full,
                 qPrintable(QString("location %1: %2 um at 12 h vs %3 um").arg(int(where)).arg(end).arg(full)));
        // Half-way time: the bearing contact (one end) is slower than the spread contact.
        if (where == Location::FixedBearing) {
            int half = 0;
            while (half < sim.rowCount() && phi(half, 3) < 0.5 * full)
                ++half;
            QVERIFY(half < sim.rowCount());
            const double tHalf = sim.observations()[static_cast<size_t>(half)].t_s - t0;
            const double lumped = std::log(2.0) * rhoC * area * g.length_m / G;
            QVERIFY2(tHalf >= lumped - 60.0 && tHalf < 10.0 * lumped,
                     qPrintable(QString("half-way after %1 s, lumped bound %2 s").arg(tHalf).arg(lumped)));
        }
    }
}

void TestScrewResponseSimulator::rejectsBadRecordings()
{
    const ScrewGeometry g;
    ScrewRecording empty;
    empty.name = "empty";
    QVERIFY_EXCEPTION_THROWN(ScrewResponseSimulator(g, {empty}, ResponseSimulatorOptions{}, seedSources()),
                             std::invalid_argument);
    ScrewRecording rec = SyntheticScrewTest::generate(shortProgramme(3000.0), g, FdmParameters{}, FdmSettings{});
    rec.interferometer.push_back({1e7, 100.0, 1.0});
    QVERIFY_EXCEPTION_THROWN(ScrewResponseSimulator(g, {rec}, ResponseSimulatorOptions{}, seedSources()),
                             std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestScrewResponseSimulator)
#include "tst_screwresponsesimulator.moc"

// bench_fdm: throughput of FdmScrewModel::step (seed-000 eq. 10, explicit) against a
// straightforward transcription of eq. (10) written here, run in the same process.
//
// Workload: a 10-hour test at N = 80 (dx = 0.01 m), dt = 0.1 s (360 000 steps), X-axis
// parameters of Table 3, nut reciprocating between two axis coordinates at the feed,
// feed phases of Table 2 repeated (warm-up 84 min at 6000 mm/min, cooling 42 min,
// warm-up 42 min at 9000 mm/min), slow ambient drift. Best of 3 repetitions each.
// Both implementations must give the same elongation (sampled once a simulated minute).

#include "FdmScrewModel.h"

#include "../tests/support/Table2Duty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace driftlab;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Scenario {
    testduty::Table2Duty duty{-100.0, 550.0}; // nut 41 mm .. 691 mm from the fixed end
    double ambient(double t) const { return 20.0 + 1.5 * std::sin(2.0 * kPi * t / 86400.0); }
};

// Straightforward eq. (10): 1-based n as in the paper, per-cell branching, coefficients
// recomputed every step, a fresh T^{t+dt} vector every step. Same modelling decisions as
// FdmScrewModel (sources add up where nut and bearing overlap, no convection under them,
// free-end face convection; the 1e-9 guard on the eq. (10) index bounds).
class ReferenceFdm {
public:
    ReferenceFdm(const ScrewGeometry &g, const FdmParameters &p, const FdmSettings &s)
        : g(g), p(p), s(s), T(static_cast<size_t>(std::lround(g.length_m / s.dx_m)), 20.0)
    {
    }

    void reset(double ambient)
    {
        std::fill(T.begin(), T.end(), ambient);
        Ta = ambient;
        Ta0 = ambient;
    }

    void step(double axis_mm, double feed, double ambientNext)
    {
        const int N = static_cast<int>(T.size());
        const double v = std::fabs(feed);
        const double h = p.k1 * v + p.k2;          // eq. (17)
        const double QB = p.k3 * v;                // eq. (18)
        const double QN = p.k4 * v;                // eq. (19)
        const double rho = g.density_kg_m3, c = g.specificHeat_J_kgK, D = g.diameter_m;
        const double dx = s.dx_m, dt = s.dt_s, lambda = p.conductivity_W_mK;
        const double XN = std::fabs(axis_mm - p.fixedEndPosition_mm) / 1000.0;
        std::vector<double> Tn(T.size());
        for (int n = 1; n <= N; ++n) {
            const double Tc = T[static_cast<size_t>(n - 1)];
            const double Tl = n > 1 ? T[static_cast<size_t>(n - 2)] : Tc;
            const double Tr = n < N ? T[static_cast<size_t>(n)] : Tc;
            const double cond = lambda * dt / (rho * c * dx * dx);
            const double src = 4.0 * dt / (kPi * D * D * rho * c);
            const bool bearing = g.fixedBearingLength_m > 0 && n <= g.fixedBearingLength_m / dx + 1e-9;
            const bool nut = g.nutLength_m > 0 && n > (XN - g.nutLength_m / 2.0) / dx + 1e-9 &&
                             n <= (XN + g.nutLength_m / 2.0) / dx + 1e-9;
            double value = Tc + cond * (Tr + Tl - 2.0 * Tc);
            if (bearing)
                value += src * QB / g.fixedBearingLength_m;
            if (nut)
                value += src * QN / g.nutLength_m;
            if (n == N) {
                if (bearing || nut)
                    value -= h * dt / (rho * c * dx) * (Tc - Ta);
                else
                    value -= 4.0 * h * dt / (rho * c * D) * (1.0 + D / (4.0 * dx)) * (Tc - Ta);
            } else if (!bearing && !nut) {
                value -= 4.0 * h * dt / (rho * c * D) * (Tc - Ta);
            }
            Tn[static_cast<size_t>(n - 1)] = value;
        }
        T = Tn;
        Ta = ambientNext;
    }

    double elongation_um() const
    {
        double sum = 0.0;
        for (double t : T)
            sum += g.expansion_per_K * (t - Ta0) * s.dx_m; // eq. (11)-(13) plus eq. (1)
        return sum * 1e6;
    }

private:
    ScrewGeometry g;
    FdmParameters p;
    FdmSettings s;
    std::vector<double> T;
    double Ta = 20.0, Ta0 = 20.0;
};

// Inputs of every step, precomputed so that only the model is timed.
struct Inputs {
    std::vector<double> position, feed, ambient;
    double ambient0 = 20.0;
};

Inputs makeInputs(const Scenario &sc, long steps, double dt)
{
    Inputs in;
    in.ambient0 = sc.ambient(0.0);
    for (long k = 0; k < steps; ++k) {
        const double t = k * dt;
        in.position.push_back(sc.duty.position(t));
        in.feed.push_back(sc.duty.feed(t));
        in.ambient.push_back(sc.ambient(t + dt));
    }
    return in;
}

template <class Model>
double run(Model &model, const Inputs &in, double dt, std::vector<double> &elong)
{
    elong.clear();
    elong.reserve(in.feed.size() / 100 + 1);
    model.reset(in.ambient0);
    const size_t steps = in.feed.size();
    const size_t sampleEvery = static_cast<size_t>(std::lround(60.0 / dt));
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t k = 0; k < steps; ++k) {
        model.step(in.position[k], in.feed[k], in.ambient[k]);
        if ((k + 1) % sampleEvery == 0)
            elong.push_back(model.elongation_um());
    }
    const auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double>(t1 - t0).count();
}

} // namespace

int main()
{
    const ScrewGeometry g;   // Table 1
    const FdmParameters p;   // Table 3, X axis
    const FdmSettings s;     // dx = 0.01 m, dt = 0.1 s
    const Scenario sc;
    const double hours = 10.0;
    const long steps = std::lround(hours * 3600.0 / s.dt_s);

    FdmScrewModel model(g, p, s);
    ReferenceFdm reference(g, p, s);
    const int N = model.cellCount();
    const double cellUpdates = static_cast<double>(steps) * N;

    const Inputs in = makeInputs(sc, steps, s.dt_s);
    std::vector<double> eModel, eRef;
    double bestModel = 1e300, bestRef = 1e300;
    for (int rep = 0; rep < 3; ++rep) {
        bestModel = std::min(bestModel, run(model, in, s.dt_s, eModel));
        bestRef = std::min(bestRef, run(reference, in, s.dt_s, eRef));
    }

    double maxDiff = 0.0, peak = 0.0;
    for (size_t i = 0; i < eModel.size() && i < eRef.size(); ++i) {
        maxDiff = std::max(maxDiff, std::fabs(eModel[i] - eRef[i]));
        peak = std::max(peak, std::fabs(eRef[i]));
    }
    const double rateModel = cellUpdates / bestModel;
    const double rateRef = cellUpdates / bestRef;
    const bool same = eModel.size() == eRef.size() && maxDiff <= 1e-9 * std::max(1.0, peak);

    std::printf("bench_fdm: %.0f h simulated, N = %d, dt = %.2f s, %ld steps, %.3g cell updates; best of 3\n",
                hours, N, s.dt_s, steps, cellUpdates);
    std::printf("  FdmScrewModel::step : %8.3f ms  %8.1f Mcell/s  (%.3f us per step)\n", bestModel * 1e3,
                rateModel / 1e6, bestModel / steps * 1e6);
    std::printf("  reference eq. (10)  : %8.3f ms  %8.1f Mcell/s  (%.3f us per step)\n", bestRef * 1e3,
                rateRef / 1e6, bestRef / steps * 1e6);
    std::printf("  ratio model/reference: %.2fx; elongation peak %.3f um, max |difference| %.3g um over %zu samples (%s)\n",
                rateModel / rateRef, peak, maxDiff, eModel.size(), same ? "same" : "DIFFERENT");
    std::printf("\n| benchmark | workload | FdmScrewModel (Mcell/s) | reference (Mcell/s) | ratio | max elongation difference (um) |\n");
    std::printf("|---|---|---|---|---|---|\n");
    std::printf("| bench_fdm | 10 h, N = %d, dt = %.1f s | %.1f | %.1f | %.2fx | %.2g |\n", N, s.dt_s,
                rateModel / 1e6, rateRef / 1e6, rateModel / rateRef, maxDiff);
    return same ? 0 : 1;
}

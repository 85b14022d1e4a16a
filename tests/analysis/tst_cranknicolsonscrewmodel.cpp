// Tests of the implicit (Crank-Nicolson) seed-000 screw model against
//  - the exact discrete decay of the Neumann cosine mode (CN amplification factor) and the
//    continuous analytic decay exp(-lambda pi^2 t / (rho c L^2)) of cos(pi x / L);
//  - a closed-form steady fin (bearing heat over [0, L_B] without convection, convection
//    beyond, convective free-end face) reached with dt far beyond the explicit limit;
//  - the explicit model FdmScrewModel at small dt on a Table-2-like duty cycle.

#include "CrankNicolsonScrewModel.h"
#include "FdmScrewModel.h"
#include "ScrewCellLayout.h"
#include "TridiagonalSolver.h"

#include "../support/Table2Duty.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace driftlab;

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

class TestCrankNicolsonScrewModel : public QObject {
    Q_OBJECT
private slots:
    void tridiagonalSolvesKnownSystem();
    void tridiagonalFactorsSeveralAsOne();
    void layoutMatchesExplicitModel();
    void cosineModeDecaysExactly();
    void steadyFinMatchesClosedForm();
    void agreesWithExplicitAtSmallStep();
    void rejectsBadInput();
};

void TestCrankNicolsonScrewModel::tridiagonalSolvesKnownSystem()
{
    // x = (1, -2, 3, 0.5, 4); build rhs from a diagonally dominant tridiagonal matrix.
    const std::vector<double> x{1, -2, 3, 0.5, 4};
    const std::vector<double> lo{0, -1, 0.5, -2, 1}, di{4, 5, 6, 7, 8}, up{1, -1.5, 2, 0.3, 0};
    std::vector<double> b(5);
    for (int i = 0; i < 5; ++i)
        b[i] = di[i] * x[i] + (i > 0 ? lo[i] * x[i - 1] : 0) + (i < 4 ? up[i] * x[i + 1] : 0);
    TridiagonalSolver s;
    s.factor(lo.data(), di.data(), up.data(), 5);
    s.solve(b.data());
    for (int i = 0; i < 5; ++i)
        QVERIFY2(std::fabs(b[i] - x[i]) < 1e-12, qPrintable(QString("x[%1] = %2").arg(i).arg(b[i])));
    const std::vector<double> zero{0, 0};
    QVERIFY_EXCEPTION_THROWN(s.factor(zero.data(), zero.data(), zero.data(), 2), std::invalid_argument);
}

void TestCrankNicolsonScrewModel::tridiagonalFactorsSeveralAsOne()
{
    // The simulator factors four steps' matrices side by side (factorSeveral) and solves
    // several interleaved right-hand sides (column counts unrolled at compile time): each
    // system must come out bit for bit as factor() + solve() give it alone, one column at a
    // time, and solve its system.
    const int n = 37;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> lo(n), up(n), di(4 * n);
    for (int i = 0; i < n; ++i) {
        lo[i] = u(rng);
        up[i] = u(rng);
    }
    for (double &d : di)
        d = 3.0 + u(rng);
    for (int count = 1; count <= TridiagonalSolver::kMaxSystems; ++count) {
        TridiagonalSolver several;
        several.factorSeveral(lo.data(), di.data(), up.data(), n, count);
        for (int sys = 0; sys < count; ++sys) {
            TridiagonalSolver one;
            one.factor(lo.data(), di.data() + sys * n, up.data(), n);
            several.select(sys);
            for (int cols : {1, 2, 3, 4, 5, 6, 7, 9}) {
                std::vector<double> rhs(static_cast<size_t>(n) * cols);
                for (double &r : rhs)
                    r = u(rng);
                std::vector<double> x = rhs;
                several.solveInterleaved(x.data(), cols);
                for (int c = 0; c < cols; ++c) {
                    std::vector<double> col(n);
                    for (int i = 0; i < n; ++i)
                        col[i] = rhs[static_cast<size_t>(i) * cols + c];
                    one.solve(col.data());
                    for (int i = 0; i < n; ++i) {
                        const double got = x[static_cast<size_t>(i) * cols + c];
                        QVERIFY2(std::memcmp(&got, &col[i], sizeof got) == 0,
                                 qPrintable(QString("count %1 system %2 columns %3 x[%4][%5]: %6 vs %7")
                                                .arg(count).arg(sys).arg(cols).arg(i).arg(c)
                                                .arg(got, 0, 'g', 17).arg(col[i], 0, 'g', 17)));
                        // and it solves the system
                        const double *d = di.data() + sys * n;
                        const double lhs = d[i] * got + (i > 0 ? lo[i] * x[static_cast<size_t>(i - 1) * cols + c] : 0.0) +
                                           (i < n - 1 ? up[i] * x[static_cast<size_t>(i + 1) * cols + c] : 0.0);
                        QVERIFY(std::fabs(lhs - rhs[static_cast<size_t>(i) * cols + c]) < 1e-12);
                    }
                }
            }
        }
        QVERIFY_EXCEPTION_THROWN(several.select(count), std::invalid_argument);
    }
    std::vector<double> bad = di;
    bad[2 * n] = 0.0; // the third system's first pivot
    QVERIFY_EXCEPTION_THROWN(TridiagonalSolver().factorSeveral(lo.data(), bad.data(), up.data(), n, 3), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(TridiagonalSolver().factorSeveral(lo.data(), di.data(), up.data(), n, 5), std::invalid_argument);
}

void TestCrankNicolsonScrewModel::layoutMatchesExplicitModel()
{
    const ScrewGeometry g;
    for (double dx : {0.01, 0.005, 0.013}) {
        FdmSettings s;
        s.dx_m = dx;
        s.dt_s = 0.01;
        const FdmScrewModel ref(g, FdmParameters{}, s);
        const ScrewCellLayout layout(g, s);
        QCOMPARE(layout.cellCount(), ref.cellCount());
        for (double x = -0.3; x < 1.2; x += 0.0037) {
            int f1, l1, f2, l2, b;
            ref.heatedCells(x, f1, l1, b);
            layout.nutCells(x, f2, l2);
            QCOMPARE(layout.bearingCells(), b);
            if (l1 >= f1 || l2 >= f2) {
                QCOMPARE(f2, f1);
                QCOMPARE(l2, l1);
            }
        }
    }
}

void TestCrankNicolsonScrewModel::cosineModeDecaysExactly()
{
    // No convection (k1 = k2 = 0), no heat: both ends adiabatic. cos(pi (i + 1/2) / N) is an
    // exact eigenvector of the cell-centred Neumann Laplacian, eigenvalue
    // mu = -4 r sin^2(pi / 2N); CN multiplies it by (1 + dt mu / 2) / (1 - dt mu / 2) per step.
    const ScrewGeometry g;
    FdmParameters p;
    p.k1 = p.k2 = p.k3 = p.k4 = 0.0;
    FdmSettings s;
    s.dt_s = 20.0; // explicit limit is 0.31 s here
    CrankNicolsonScrewModel m(g, p, s);
    const int N = m.cellCount();
    const double Ta = 20.0, A = 3.0;
    m.reset(Ta);
    std::vector<double> T0(static_cast<size_t>(N));
    for (int i = 0; i < N; ++i)
        T0[i] = Ta + A * std::cos(kPi * (i + 0.5) / N);
    m.setTemperatures(T0);
    const double rhoC = g.density_kg_m3 * g.specificHeat_J_kgK;
    const double r = p.conductivity_W_mK / (rhoC * s.dx_m * s.dx_m);
    const double mu = -4.0 * r * std::pow(std::sin(kPi / (2.0 * N)), 2);
    const double gain = (1.0 + s.dt_s * mu / 2.0) / (1.0 - s.dt_s * mu / 2.0);
    const double tau = rhoC * g.length_m * g.length_m / (p.conductivity_W_mK * kPi * kPi); // ~400 s
    const int steps = static_cast<int>(std::lround(tau / s.dt_s));
    for (int k = 0; k < steps; ++k)
        m.step(0.0, 0.0, Ta);
    const double discrete = A * std::pow(gain, steps);
    const double continuous = A * std::exp(-m.time_s() / tau);
    double maxDiscrete = 0.0, maxContinuous = 0.0;
    for (int i = 0; i < N; ++i) {
        const double c = std::cos(kPi * (i + 0.5) / N);
        maxDiscrete = std::max(maxDiscrete, std::fabs(m.temperatures()[i] - Ta - discrete * c));
        maxContinuous = std::max(maxContinuous, std::fabs(m.temperatures()[i] - Ta - continuous * c));
    }
    QVERIFY2(maxDiscrete < 1e-10 * A, qPrintable(QString("discrete mode error %1 K").arg(maxDiscrete)));
    // Spatial (1 - 1.3e-4 in mu) and temporal (O((dt/tau)^2) = 2.5e-3 / 12) errors: < 0.2 %.
    QVERIFY2(maxContinuous < 2e-3 * A, qPrintable(QString("continuous mode error %1 K").arg(maxContinuous)));
    // Expansion to mid-length: alpha * A(t) * L / pi exactly for the cell-wise integral of
    // the sampled cosine up to O(dx^2).
    const double e = m.expansionAt_um(g.length_m / 2.0);
    const double eAnalytic = g.expansion_per_K * continuous * g.length_m / kPi * 1e6;
    QVERIFY2(std::fabs(e - eAnalytic) < 2e-3 * std::fabs(eAnalytic),
             qPrintable(QString("expansion %1 vs %2 um").arg(e).arg(eAnalytic)));
}

void TestCrankNicolsonScrewModel::steadyFinMatchesClosedForm()
{
    // Bearing heat Q_B = k3 v over [0, a], no convection there (eq. 10); lateral convection
    // h on [a, L]; free-end face -lambda T'(L) = h (T(L) - Ta). Nut parked far beyond the screw.
    const ScrewGeometry g;
    FdmParameters p; // Table 3 X
    FdmSettings s;
    s.dx_m = 0.005;
    s.dt_s = 20.0; // 250x the explicit limit at this dx (CN damps the stiffest mode by only
                   // (1 - a/2)/(1 + a/2) ~ -0.992 per step here, so not much larger)
    CrankNicolsonScrewModel m(g, p, s);
    const double v = 6000.0, Ta = 20.0;
    const double axisFar = p.fixedEndPosition_mm + 5000.0;
    m.reset(Ta);
    std::vector<double> prev;
    for (int k = 0; k < 5000; ++k) {
        prev = m.temperatures();
        m.step(axisFar, v, Ta);
    }
    double change = 0.0;
    for (size_t i = 0; i < prev.size(); ++i)
        change = std::max(change, std::fabs(prev[i] - m.temperatures()[i]));
    QVERIFY2(change < 1e-9, qPrintable(QString("not steady: %1 K per step").arg(change)));

    const double lambda = p.conductivity_W_mK, h = p.k1 * v + p.k2, D = g.diameter_m, L = g.length_m;
    const double a = g.fixedBearingLength_m, A = kPi * D * D / 4.0;
    const double qp = p.k3 * v / (a * A * lambda); // K/m^2
    const double mm = std::sqrt(4.0 * h / (lambda * D));
    const double ell = L - a, beta = h / (lambda * mm);
    const double B1 = qp * a / (mm * std::sinh(mm * ell) + mm * beta * std::cosh(mm * ell));
    const double B2 = beta * B1;
    const double thetaA = B1 * (std::cosh(mm * ell) + beta * std::sinh(mm * ell));
    auto theta = [&](double x) {
        if (x <= a)
            return thetaA + qp * (a * a - x * x) / 2.0;
        return B1 * std::cosh(mm * (L - x)) + B2 * std::sinh(mm * (L - x));
    };
    const double peak = theta(0.0);
    double worst = 0.0;
    for (int i = 0; i < m.cellCount(); ++i)
        worst = std::max(worst, std::fabs(m.temperatures()[i] - Ta - theta((i + 0.5) * s.dx_m)));
    // Cell-centred sampling of a kinked profile and the cell-wise end face: O(dx) = 1 % of the peak.
    QVERIFY2(worst < 0.01 * peak, qPrintable(QString("max deviation %1 K, peak %2 K").arg(worst).arg(peak)));
    const double integral = thetaA * a + qp * a * a * a / 3.0 + B1 * std::sinh(mm * ell) / mm +
                            B2 * (std::cosh(mm * ell) - 1.0) / mm;
    const double elongation = g.expansion_per_K * integral * 1e6;
    QVERIFY2(std::fabs(m.elongation_um() - elongation) < 0.01 * elongation,
             qPrintable(QString("elongation %1 vs analytic %2 um").arg(m.elongation_um()).arg(elongation)));
}

void TestCrankNicolsonScrewModel::agreesWithExplicitAtSmallStep()
{
    const ScrewGeometry g;
    const FdmParameters p;
    const FdmSettings s; // dx 0.01, dt 0.1
    FdmScrewModel ex(g, p, s);
    CrankNicolsonScrewModel cn(g, p, s);
    const testduty::Table2Duty duty; // one cycle, nut 0 .. 550 mm
    auto ambient = [](double t) { return 20.0 + 0.5 * std::sin(2 * kPi * t / 7200.0); };
    ex.reset(ambient(0));
    cn.reset(ambient(0));
    double peak = 0.0, worst = 0.0;
    const long steps = std::lround(168 * 60.0 / s.dt_s);
    for (long k = 0; k < steps; ++k) {
        const double t = k * s.dt_s;
        ex.step(duty.position(t), duty.feed(t), ambient(t + s.dt_s));
        cn.step(duty.position(t), duty.feed(t), ambient(t + s.dt_s));
        if (k % 600 == 0) {
            peak = std::max(peak, std::fabs(ex.elongation_um()));
            worst = std::max(worst, std::fabs(ex.elongation_um() - cn.elongation_um()));
            for (double x : {0.0, 150.0, 300.0, 550.0})
                worst = std::max(worst, std::fabs(ex.thermalError_um(x) - cn.thermalError_um(x)));
        }
    }
    QVERIFY(peak > 10.0);
    // Both are first/second order in dt = 0.1 s against time scales of minutes; the only
    // difference in the schemes is the time integration (and ambient at t vs mid-step).
    QVERIFY2(worst < 2e-3 * peak, qPrintable(QString("max difference %1 um, peak %2 um").arg(worst).arg(peak)));
}

void TestCrankNicolsonScrewModel::rejectsBadInput()
{
    FdmParameters p;
    p.conductivity_W_mK = 0.0;
    QVERIFY_EXCEPTION_THROWN(CrankNicolsonScrewModel(ScrewGeometry{}, p), std::invalid_argument);
    FdmSettings s;
    s.dt_s = -1;
    QVERIFY_EXCEPTION_THROWN(CrankNicolsonScrewModel(ScrewGeometry{}, FdmParameters{}, s), std::invalid_argument);
    CrankNicolsonScrewModel m(ScrewGeometry{}, FdmParameters{});
    QVERIFY_EXCEPTION_THROWN(m.setTemperatures(std::vector<double>(3, 20.0)), std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestCrankNicolsonScrewModel)
#include "tst_cranknicolsonscrewmodel.moc"

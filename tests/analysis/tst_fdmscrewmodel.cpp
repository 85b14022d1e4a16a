// Tests of the seed-000 explicit finite-difference ball-screw model (FdmScrewModel)
// against expectations built independently here:
//  - steady state: analytic solution of the piecewise 1-D fin equation (Eigen solve);
//  - transient: an implicit-Euler solution on a 10x finer cell-centred grid with its own
//    source/convection coverage (physical nut and bearing extents) and its own end face;
//  - stability: the coefficient of T_n^t in eq. (10) computed here for every cell kind;
//  - sign convention of eq. (15)/(16), ambient term eq. (1), energy conservation.

#include "FdmScrewModel.h"

#include <QtTest>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace driftlab;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Axis coordinate (mm) that puts the nut centre at distance x (m) from the fixed end,
// for a fixed end at P_f < 0 (travel towards positive coordinates).
double axisForNut(const FdmParameters &p, double x_m)
{
    return p.fixedEndPosition_mm + x_m * 1000.0;
}

double maxAbsDiff(const std::vector<double> &a, const std::vector<double> &b)
{
    double m = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
        m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

// Runs the model at constant input until the largest temperature change over 1000 s of
// simulated time is below tol. Returns false if it does not converge within maxTime.
bool runToSteadyState(FdmScrewModel &model, double axis_mm, double feed, double ambient,
                      double tol = 1e-6, double maxTime_s = 4.0e5)
{
    const long stepsPerChunk = std::lround(1000.0 / model.settings().dt_s);
    std::vector<double> prev = model.temperatures();
    for (double t = 0.0; t < maxTime_s; t += 1000.0) {
        for (long k = 0; k < stepsPerChunk; ++k)
            model.step(axis_mm, feed, ambient);
        const double change = maxAbsDiff(prev, model.temperatures());
        if (change < tol)
            return true;
        prev = model.temperatures();
    }
    return false;
}

// ---------------------------------------------------------------------------------------
// Analytic steady state of  theta'' - m^2 theta = -s  (piecewise constant m^2, s),
// theta'(0) = 0, continuity of theta and theta' at interfaces, -lambda theta'(L) = h theta(L).
// Region basis (local, well conditioned):
//   m > 0 : theta = c1 exp(-m (x-a)) + c2 exp(-m (b-x)) + s/m^2
//   m = 0 : theta = c1 + c2 (x-a) - s (x-a)^2 / 2
class AnalyticFin {
public:
    struct Region {
        double a, b, m, s;
    };

    AnalyticFin(std::vector<Region> regions, double lambda, double h)
        : m_r(std::move(regions))
    {
        const int R = static_cast<int>(m_r.size());
        Eigen::MatrixXd M = Eigen::MatrixXd::Zero(2 * R, 2 * R);
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * R);
        int row = 0;
        // theta'(0) = 0
        {
            const Basis b = basis(0, m_r[0].a);
            M(row, 0) = b.d1;
            M(row, 1) = b.d2;
            rhs(row) = -b.dp;
            ++row;
        }
        for (int j = 0; j + 1 < R; ++j) {
            const double x = m_r[static_cast<size_t>(j)].b;
            const Basis l = basis(j, x);
            const Basis r = basis(j + 1, x);
            M(row, 2 * j) = l.v1;
            M(row, 2 * j + 1) = l.v2;
            M(row, 2 * j + 2) = -r.v1;
            M(row, 2 * j + 3) = -r.v2;
            rhs(row) = r.p - l.p;
            ++row;
            M(row, 2 * j) = l.d1;
            M(row, 2 * j + 1) = l.d2;
            M(row, 2 * j + 2) = -r.d1;
            M(row, 2 * j + 3) = -r.d2;
            rhs(row) = r.dp - l.dp;
            ++row;
        }
        // lambda theta'(L) + h theta(L) = 0
        {
            const Basis b = basis(R - 1, m_r.back().b);
            M(row, 2 * R - 2) = lambda * b.d1 + h * b.v1;
            M(row, 2 * R - 1) = lambda * b.d2 + h * b.v2;
            rhs(row) = -(lambda * b.dp + h * b.p);
        }
        const Eigen::VectorXd c = M.fullPivLu().solve(rhs);
        m_residual = (M * c - rhs).norm() / std::max(1.0, rhs.norm());
        m_c.assign(c.data(), c.data() + c.size());
    }

    double value(double x) const
    {
        int j = 0;
        while (j + 1 < static_cast<int>(m_r.size()) && x > m_r[static_cast<size_t>(j)].b)
            ++j;
        const Basis b = basis(j, x);
        return m_c[static_cast<size_t>(2 * j)] * b.v1 + m_c[static_cast<size_t>(2 * j + 1)] * b.v2 + b.p;
    }

    // integral of theta over the whole rod
    double integral() const
    {
        double sum = 0.0;
        for (size_t j = 0; j < m_r.size(); ++j) {
            const Region &g = m_r[j];
            const double len = g.b - g.a;
            const double c1 = m_c[2 * j], c2 = m_c[2 * j + 1];
            if (g.m > 0.0)
                sum += (c1 + c2) * (1.0 - std::exp(-g.m * len)) / g.m + g.s * len / (g.m * g.m);
            else
                sum += c1 * len + c2 * len * len / 2.0 - g.s * len * len * len / 6.0;
        }
        return sum;
    }

    double residual() const { return m_residual; }

private:
    struct Basis {
        double v1, v2, p, d1, d2, dp;
    };

    Basis basis(int j, double x) const
    {
        const Region &g = m_r[static_cast<size_t>(j)];
        Basis b{};
        if (g.m > 0.0) {
            const double e1 = std::exp(-g.m * (x - g.a));
            const double e2 = std::exp(-g.m * (g.b - x));
            b.v1 = e1;
            b.v2 = e2;
            b.p = g.s / (g.m * g.m);
            b.d1 = -g.m * e1;
            b.d2 = g.m * e2;
            b.dp = 0.0;
        } else {
            const double u = x - g.a;
            b.v1 = 1.0;
            b.v2 = u;
            b.p = -g.s * u * u / 2.0;
            b.d1 = 0.0;
            b.d2 = 1.0;
            b.dp = -g.s * u;
        }
        return b;
    }

    std::vector<Region> m_r;
    std::vector<double> m_c;
    double m_residual = 0.0;
};

// ---------------------------------------------------------------------------------------
// Independent transient reference: cell-centred finite volumes on a fine grid, implicit
// Euler, Thomas solve. Heat sources and the convective fraction use the exact overlap of
// each fine cell with the physical bearing [0, L_B] and nut [c - L_N/2, c + L_N/2]; the free
// end face convects through the half-cell conduction resistance (second order).
class FineGridScrew {
public:
    FineGridScrew(const ScrewGeometry &g, const FdmParameters &p, int cells, double dt)
        : m_g(g), m_p(p), m_M(cells), m_dx(g.length_m / cells), m_dt(dt),
          m_T(static_cast<size_t>(cells)), m_a(m_T), m_b(m_T), m_c(m_T), m_d(m_T)
    {
    }

    void reset(double ambient)
    {
        std::fill(m_T.begin(), m_T.end(), ambient);
        m_ambient0 = ambient;
    }

    // One implicit step with nut centre at x (m), feed (mm/min), ambient at the step end.
    void advance(double nutCentre_m, double feed_mm_min, double ambient)
    {
        const double v = std::fabs(feed_mm_min);
        const double h = m_p.k1 * v + m_p.k2;
        const double qB = m_p.k3 * v;
        const double qN = m_p.k4 * v;
        const double lam = m_p.conductivity_W_mK;
        const double D = m_g.diameter_m;
        const double area = kPi * D * D / 4.0;
        const double cap = m_g.density_kg_m3 * m_g.specificHeat_J_kgK / m_dt;
        const double kap = lam / (m_dx * m_dx);
        const double hp = 4.0 * h / D;                                 // per unit volume
        const double hEnd = h / (1.0 + h * m_dx / (2.0 * lam)) / m_dx; // end face per volume
        const double LB = m_g.fixedBearingLength_m, LN = m_g.nutLength_m;
        const double nLo = nutCentre_m - LN / 2.0, nHi = nutCentre_m + LN / 2.0;
        const double bLo = std::max(0.0, nLo), bHi = std::min(LB, nHi); // bearing & nut

        auto overlap = [](double a0, double a1, double b0, double b1) {
            return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
        };

        for (int i = 0; i < m_M; ++i) {
            const size_t k = static_cast<size_t>(i);
            const double xa = i * m_dx, xb = xa + m_dx;
            const double ob = LB > 0 ? overlap(xa, xb, 0.0, LB) : 0.0;
            const double on = LN > 0 ? overlap(xa, xb, nLo, nHi) : 0.0;
            const double obn = (LB > 0 && LN > 0) ? overlap(xa, xb, bLo, bHi) : 0.0;
            const double fConv = std::max(0.0, 1.0 - (ob + on - obn) / m_dx);
            double src = 0.0;
            if (LB > 0)
                src += qB / LB * ob;
            if (LN > 0)
                src += qN / LN * on;
            src /= area * m_dx; // W/m^3
            const double loss = fConv * hp + (i == m_M - 1 ? hEnd : 0.0);
            m_a[k] = i > 0 ? -kap : 0.0;
            m_c[k] = i < m_M - 1 ? -kap : 0.0;
            m_b[k] = cap + loss - m_a[k] - m_c[k];
            m_d[k] = cap * m_T[k] + src + loss * ambient;
        }
        // Thomas algorithm
        for (int i = 1; i < m_M; ++i) {
            const size_t k = static_cast<size_t>(i);
            const double w = m_a[k] / m_b[k - 1];
            m_b[k] -= w * m_c[k - 1];
            m_d[k] -= w * m_d[k - 1];
        }
        const size_t last = static_cast<size_t>(m_M - 1);
        m_T[last] = m_d[last] / m_b[last];
        for (int i = m_M - 2; i >= 0; --i) {
            const size_t k = static_cast<size_t>(i);
            m_T[k] = (m_d[k] - m_c[k] * m_T[k + 1]) / m_b[k];
        }
    }

    // alpha * integral_0^x (T - T_a0) dx, um
    double expansion_um(double x) const
    {
        x = std::clamp(x, 0.0, m_g.length_m);
        double sum = 0.0;
        for (int i = 0; i < m_M; ++i) {
            const double xa = i * m_dx;
            if (xa >= x)
                break;
            sum += (std::min(x, xa + m_dx) - xa) * (m_T[static_cast<size_t>(i)] - m_ambient0);
        }
        return m_g.expansion_per_K * sum * 1e6;
    }

private:
    ScrewGeometry m_g;
    FdmParameters m_p;
    int m_M;
    double m_dx, m_dt;
    std::vector<double> m_T, m_a, m_b, m_c, m_d;
    double m_ambient0 = 20.0;
};

// Duty cycle of Table 2 (warm-up 84 min, cooling 42 min, warm-up 42 min), nut reciprocating
// at the feed between two axis coordinates, slow ambient drift.
struct DutyCycle {
    struct Phase {
        double duration_s, feed;
    };
    std::vector<Phase> phases{{5040.0, 6000.0}, {2520.0, 0.0}, {2520.0, 9000.0}};
    double posA_mm = 9.0;   // nut 0.15 m from the fixed end (P_f = -141 mm)
    double posB_mm = 509.0; // nut 0.65 m from the fixed end
    double ambientDrift_K = 0.8;

    double duration() const
    {
        double t = 0.0;
        for (const Phase &p : phases)
            t += p.duration_s;
        return t;
    }
    double feed(double t) const
    {
        for (const Phase &p : phases) {
            if (t < p.duration_s)
                return p.feed;
            t -= p.duration_s;
        }
        return 0.0;
    }
    double position(double t) const
    {
        double path = 0.0; // mm travelled
        for (const Phase &p : phases) {
            const double dur = std::min(t, p.duration_s);
            path += p.feed / 60.0 * dur;
            t -= dur;
            if (t <= 0.0)
                break;
        }
        const double stroke = posB_mm - posA_mm;
        const double u = std::fmod(path, 2.0 * stroke);
        return posA_mm + (u <= stroke ? u : 2.0 * stroke - u);
    }
    double ambient(double t) const { return 20.0 + ambientDrift_K * t / duration(); }
};

} // namespace

class TestFdmScrewModel : public QObject {
    Q_OBJECT

private slots:
    void steadyStateMatchesAnalyticFin_data();
    void steadyStateMatchesAnalyticFin();
    void transientMatchesFineGrid_data();
    void transientMatchesFineGrid();
    void stabilityLimitThrows();
    void stabilityLimitMatchesEq10Coefficient_data();
    void stabilityLimitMatchesEq10Coefficient();
    void signConventionEq15Eq16();
    void ambientOnlyChangeGivesLinearExpansion();
    void energyIsConservedWithoutConvection();
    void invalidGeometryThrows();
};

// ---------------------------------------------------------------------------------------
void TestFdmScrewModel::steadyStateMatchesAnalyticFin_data()
{
    QTest::addColumn<double>("lambda");
    QTest::addColumn<double>("feed");
    QTest::addColumn<double>("nutCentre");
    // Paper grid dx = 0.01 m, dt = 0.1 s for all rows (passes the 1 % bound).
    QTest::newRow("X axis Table 3, 6000 mm/min, nut mid") << 566.3 << 6000.0 << 0.40;
    QTest::newRow("X axis Table 3, 9000 mm/min, nut on bearing") << 566.3 << 9000.0 << 0.05;
    QTest::newRow("steel lambda 45, 6000 mm/min, nut mid") << 45.0 << 6000.0 << 0.40;
    QTest::newRow("steel lambda 45, 3000 mm/min, nut over free end") << 45.0 << 3000.0 << 0.75;
}

void TestFdmScrewModel::steadyStateMatchesAnalyticFin()
{
    QFETCH(double, lambda);
    QFETCH(double, feed);
    QFETCH(double, nutCentre);

    const ScrewGeometry g;
    FdmParameters p;
    p.conductivity_W_mK = lambda;
    const FdmSettings s; // dx = 0.01, dt = 0.1 (Table 1)
    FdmScrewModel model(g, p, s);
    const double Ta = 20.0;
    model.reset(Ta);

    const int N = model.cellCount();
    QCOMPARE(N, 80);
    const double dx = s.dx_m;

    // Covered cells computed here from eq. (10) (1-based n: (X_N - L_N/2)/dx < n <= (X_N + L_N/2)/dx,
    // and 1 <= n <= L_B/dx for the bearing), then cross-checked with the model's own choice.
    int firstNut = N, lastNut = -1;
    for (int n = 1; n <= N; ++n) {
        if (n > (nutCentre - g.nutLength_m / 2) / dx && n <= (nutCentre + g.nutLength_m / 2) / dx) {
            firstNut = std::min(firstNut, n - 1);
            lastNut = std::max(lastNut, n - 1);
        }
    }
    const int nB = static_cast<int>(std::floor(g.fixedBearingLength_m / dx + 1e-9));
    int mFirst = 0, mLast = 0, mB = 0;
    model.heatedCells(nutCentre, mFirst, mLast, mB);
    QCOMPARE(mFirst, firstNut);
    QCOMPARE(mLast, lastNut);
    QCOMPARE(mB, nB);

    // Piecewise regions on cell boundaries.
    const double v = feed;
    const double h = p.k1 * v + p.k2;
    const double area = kPi * g.diameter_m * g.diameter_m / 4.0;
    const double mConv = std::sqrt(4.0 * h / (lambda * g.diameter_m));
    const double sB = p.k3 * v / g.fixedBearingLength_m / (area * lambda);
    const double sN = p.k4 * v / g.nutLength_m / (area * lambda);
    std::vector<AnalyticFin::Region> regions;
    for (int i = 0; i < N; ++i) {
        const bool bearing = i < nB;
        const bool nut = i >= firstNut && i <= lastNut;
        const double m = (bearing || nut) ? 0.0 : mConv;
        const double src = (bearing ? sB : 0.0) + (nut ? sN : 0.0);
        if (!regions.empty() && regions.back().m == m && regions.back().s == src)
            regions.back().b = (i + 1) * dx;
        else
            regions.push_back({i * dx, (i + 1) * dx, m, src});
    }
    const AnalyticFin fin(regions, lambda, h);
    QVERIFY2(fin.residual() < 1e-10, qPrintable(QString::number(fin.residual())));

    QVERIFY2(runToSteadyState(model, axisForNut(p, nutCentre), feed, Ta), "no steady state reached");

    double peak = 0.0, maxErr = 0.0;
    for (int i = 0; i < N; ++i) {
        const double exact = fin.value((i + 0.5) * dx);
        peak = std::max(peak, std::fabs(exact));
        maxErr = std::max(maxErr, std::fabs(model.cellTemperature(i) - Ta - exact));
    }
    const double relT = maxErr / peak;
    const double elongExact = g.expansion_per_K * fin.integral() * 1e6;
    const double relE = std::fabs(model.elongation_um() - elongExact) / elongExact;
    qInfo("steady state: peak rise %.4f K, max |dT| %.3e K (%.4f %% of peak); elongation %.4f um vs analytic %.4f um (%.4f %%)",
          peak, maxErr, 100 * relT, model.elongation_um(), elongExact, 100 * relE);
    QVERIFY(peak > 1.0); // a meaningful heating
    QVERIFY2(relT < 0.01, qPrintable(QString("temperature error %1 of peak").arg(relT)));
    QVERIFY2(relE < 0.01, qPrintable(QString("elongation error %1").arg(relE)));
}

// ---------------------------------------------------------------------------------------
void TestFdmScrewModel::transientMatchesFineGrid_data()
{
    QTest::addColumn<double>("warmFeed1");
    QTest::addColumn<double>("warmFeed2");
    QTest::addColumn<double>("tolerance"); // fraction of the peak elongation
    // With dt = 0.1 s and dx = 0.01 m, the Table 2 feeds move the nut by a whole number of
    // half cells per step (6000 mm/min = exactly one cell), so the number of cells eq. (10)
    // puts under the 212 mm nut (21 or 22, 21.2 on average) does not average out: up to
    // 22/21.2 = +3.8 % nut heat. Measured 2.6 % of the peak; tolerance 4 %.
    QTest::newRow("Table 2 feeds 6000/9000 (cell-aliased nut)") << 6000.0 << 9000.0 << 0.04;
    // Feeds that are not commensurate with dx/dt: the nut coverage averages out. Measured
    // 0.3 % of the peak; tolerance 1 %.
    QTest::newRow("feeds 5400/8700") << 5400.0 << 8700.0 << 0.01;
}

void TestFdmScrewModel::transientMatchesFineGrid()
{
    QFETCH(double, warmFeed1);
    QFETCH(double, warmFeed2);
    QFETCH(double, tolerance);
    const ScrewGeometry g;
    const FdmParameters p; // Table 3, X axis
    const FdmSettings s;   // Table 1 grid
    FdmScrewModel model(g, p, s);
    const int N = model.cellCount();
    // Reference: 10x finer grid (800 cells, dx = 1 mm), implicit Euler, same dt = 0.1 s.
    FineGridScrew fine(g, p, 10 * N, s.dt_s);
    DutyCycle cycle;
    cycle.phases[0].feed = warmFeed1;
    cycle.phases[2].feed = warmFeed2;
    const double Ta0 = cycle.ambient(0.0);
    model.reset(Ta0);
    fine.reset(Ta0);

    const std::vector<double> axes{-91.0, 109.0, 309.0, 509.0, 659.0}; // P_x, mm
    const double dt = s.dt_s;
    const long steps = std::lround(cycle.duration() / dt);
    const long compareEvery = std::lround(600.0 / dt);
    double peak = 0.0, maxErrElong = 0.0, maxErrTe = 0.0;
    int comparisons = 0;
    for (long k = 0; k < steps; ++k) {
        const double tMid = (k + 0.5) * dt;
        const double tEnd = (k + 1) * dt;
        const double pos = cycle.position(tMid);
        const double feed = cycle.feed(tMid);
        model.step(pos, feed, cycle.ambient(tEnd));
        fine.advance((pos - p.fixedEndPosition_mm) / 1000.0, feed, cycle.ambient(tEnd));
        if ((k + 1) % compareEvery == 0) {
            const double ref = fine.expansion_um(g.length_m);
            peak = std::max(peak, std::fabs(ref));
            maxErrElong = std::max(maxErrElong, std::fabs(model.elongation_um() - ref));
            for (double px : axes) {
                const double teRef = fine.expansion_um((px - p.fixedEndPosition_mm) / 1000.0); // P_f < 0: eq. (16)
                maxErrTe = std::max(maxErrTe, std::fabs(model.thermalError_um(px) - teRef));
            }
            ++comparisons;
        }
    }
    qInfo("transient vs fine grid (%d comparisons): peak elongation %.3f um, max |error| elongation %.3f um (%.2f %% of peak), "
          "thermal error at axis positions %.3f um (%.2f %% of peak)",
          comparisons, peak, maxErrElong, 100 * maxErrElong / peak, maxErrTe, 100 * maxErrTe / peak);
    QVERIFY(comparisons >= 10);
    QVERIFY(peak > 10.0);
    // The coarse model quantises the nut to whole cells by eq. (10) (cells whose right edge is
    // inside the nut) and treats the free-end face to first order; the fine grid uses the
    // physical extents (see the _data rows for the tolerances).
    QVERIFY2(maxErrElong < tolerance * peak, qPrintable(QString::number(maxErrElong)));
    QVERIFY2(maxErrTe < tolerance * peak, qPrintable(QString::number(maxErrTe)));
}

// ---------------------------------------------------------------------------------------
void TestFdmScrewModel::stabilityLimitThrows()
{
    const ScrewGeometry g;
    const FdmParameters p;
    const double feed = 6000.0;
    const double limit = FdmScrewModel(g, p).maxStableTimeStep(feed);
    QVERIFY(limit > 0.1 && limit < 1.0); // 0.1 s of Table 1 is stable for the X axis

    {
        FdmSettings s;
        s.dt_s = 1.01 * limit;
        FdmScrewModel model(g, p, s);
        model.reset(20.0);
        bool thrown = false;
        try {
            model.step(0.0, feed, 20.0);
        } catch (const FdmStabilityError &e) {
            thrown = true;
            const std::string msg = e.what();
            const size_t iDt = msg.find("dt = ");
            const size_t iLim = msg.find("limit ");
            QVERIFY2(iDt != std::string::npos, e.what());
            QVERIFY2(iLim != std::string::npos, e.what());
            const double dtInMsg = std::stod(msg.substr(iDt + 5));
            const double limInMsg = std::stod(msg.substr(iLim + 6));
            QVERIFY2(std::fabs(dtInMsg - s.dt_s) < 1e-5 * s.dt_s, e.what());
            QVERIFY2(std::fabs(limInMsg - limit) < 1e-5 * limit, e.what());
        }
        QVERIFY(thrown);
        QCOMPARE(model.time_s(), 0.0); // nothing advanced
        QCOMPARE(model.cellTemperature(0), 20.0);
    }
    {
        // The limit depends on the feed (h = k1 v + k2): a dt between the limits at 6000 mm/min
        // and at rest is refused at 6000 (either direction) but accepted at rest.
        const double limit0 = FdmScrewModel(g, p).maxStableTimeStep(0.0);
        QVERIFY(limit0 > limit);
        FdmSettings s;
        s.dt_s = 0.5 * (limit + limit0);
        FdmScrewModel model(g, p, s);
        model.reset(20.0);
        QVERIFY_EXCEPTION_THROWN(model.step(0.0, feed, 20.0), FdmStabilityError);
        model.step(0.0, 0.0, 20.0);
        QCOMPARE(model.time_s(), s.dt_s);
        QVERIFY_EXCEPTION_THROWN(model.step(0.0, -feed, 20.0), FdmStabilityError);
        QCOMPARE(model.time_s(), s.dt_s);
    }
    {
        FdmSettings s;
        s.dt_s = 0.99 * limit;
        FdmScrewModel model(g, p, s);
        model.reset(20.0);
        double minT = 20.0, maxT = 20.0;
        bool finite = true;
        for (int k = 0; k < 20000; ++k) {
            model.step(axisForNut(p, 0.4 + 0.2 * std::sin(k * 0.01)), k % 2 ? feed : -feed, 20.0);
            for (double T : model.temperatures()) {
                finite = finite && std::isfinite(T);
                minT = std::min(minT, T);
                maxT = std::max(maxT, T);
            }
        }
        QVERIFY(finite);
        // Non-negative coefficients: no undershoot below ambient, bounded heating.
        QVERIFY2(minT >= 20.0 - 1e-9, qPrintable(QString::number(minT, 'g', 17)));
        QVERIFY(maxT > 20.5 && maxT < 60.0);
    }
}

void TestFdmScrewModel::stabilityLimitMatchesEq10Coefficient_data()
{
    QTest::addColumn<double>("lambda");
    QTest::addColumn<double>("dx");
    QTest::addColumn<double>("fixedBearing");
    QTest::newRow("X axis, dx 0.01") << 566.3 << 0.01 << 0.03;
    QTest::newRow("steel, dx 0.01") << 45.0 << 0.01 << 0.03;
    QTest::newRow("X axis, dx 0.002") << 566.3 << 0.002 << 0.03;
    QTest::newRow("low lambda, dx 0.05 (free end dominates)") << 1.0 << 0.05 << 0.03;
    QTest::newRow("no fixed bearing") << 45.0 << 0.01 << 0.0;
}

void TestFdmScrewModel::stabilityLimitMatchesEq10Coefficient()
{
    QFETCH(double, lambda);
    QFETCH(double, dx);
    QFETCH(double, fixedBearing);
    ScrewGeometry g;
    g.fixedBearingLength_m = fixedBearing;
    FdmParameters p;
    p.conductivity_W_mK = lambda;
    FdmSettings s;
    s.dx_m = dx;
    const FdmScrewModel model(g, p, s);
    const double rc = g.density_kg_m3 * g.specificHeat_J_kgK;
    const double D = g.diameter_m;
    for (double feed : {0.0, 3000.0, 6000.0, 9000.0, 20000.0}) {
        const double h = p.k1 * feed + p.k2;
        // Coefficient of T_n^t in eq. (10) is 1 - dt * K for each cell kind:
        std::vector<double> K{
            lambda / (rc * dx * dx),                                   // n = 1 (fixed end, bearing)
            2.0 * lambda / (rc * dx * dx),                             // bearing / nut interior
            2.0 * lambda / (rc * dx * dx) + 4.0 * h / (rc * D),        // convective interior ("else")
            lambda / (rc * dx * dx) + 4.0 * h / (rc * D) * (1.0 + D / (4.0 * dx)), // n = N free end
            lambda / (rc * dx * dx) + h / (rc * dx),                   // free end under the nut
        };
        if (fixedBearing == 0.0)
            K.push_back(lambda / (rc * dx * dx) + 4.0 * h / (rc * D)); // n = 1 convective
        const double Kmax = *std::max_element(K.begin(), K.end());
        const double expected = 1.0 / Kmax;
        const double got = model.maxStableTimeStep(feed);
        QVERIFY2(std::fabs(got - expected) <= 1e-12 * expected,
                 qPrintable(QString("feed %1: %2 vs %3").arg(feed).arg(got, 0, 'g', 17).arg(expected, 0, 'g', 17)));
        // at the limit the smallest coefficient is exactly zero
        QVERIFY(std::fabs(1.0 - got * Kmax) < 1e-12);
        // feed sign is the direction of travel, not a different speed
        QCOMPARE(model.maxStableTimeStep(-feed), got);
    }
}

// ---------------------------------------------------------------------------------------
void TestFdmScrewModel::signConventionEq15Eq16()
{
    const ScrewGeometry g;
    FdmParameters pNeg; // X axis: P_f = -141 mm
    FdmParameters pPos;
    pPos.fixedEndPosition_mm = 151.0; // Z axis of Table 3: P_f > 0
    FdmScrewModel a(g, pNeg), b(g, pPos);
    a.reset(20.0);
    b.reset(20.0);
    // Same nut distance from the fixed end on both: 0.3 m, reciprocating +-0.1 m.
    for (int k = 0; k < 6000; ++k) {
        const double d_mm = 300.0 + 100.0 * std::sin(k * 0.02);
        a.step(pNeg.fixedEndPosition_mm + d_mm, 6000.0, 20.0);
        b.step(pPos.fixedEndPosition_mm - d_mm, 6000.0, 20.0);
    }
    QCOMPARE(a.temperatures(), b.temperatures());
    QVERIFY(a.elongation_um() > 1.0);

    // Independent eq. (11)-(14): cumulative alpha (T - T_a) dx plus linear part of the next cell.
    auto teM = [&](const FdmScrewModel &m, double x) {
        const double dx = m.settings().dx_m;
        double sum = 0.0;
        for (int i = 0; i < m.cellCount(); ++i) {
            const double xa = i * dx;
            if (xa >= x)
                break;
            sum += (std::min(x, xa + dx) - xa) * (m.cellTemperature(i) - 20.0);
        }
        return g.expansion_per_K * sum * 1e6;
    };

    QCOMPARE(a.thermalError_um(pNeg.fixedEndPosition_mm), 0.0); // eq. (12)
    QCOMPARE(b.thermalError_um(pPos.fixedEndPosition_mm), 0.0);
    QCOMPARE(a.expansionAt_um(0.0), 0.0);
    for (double d_mm : {5.0, 95.0, 250.0, 333.3, 500.0, 799.0}) {
        // eq. (16), P_f < 0: TE(P_x) = +TE_m(P_x - P_f)
        const double px = pNeg.fixedEndPosition_mm + d_mm;
        const double expA = teM(a, (px - pNeg.fixedEndPosition_mm) / 1000.0);
        QVERIFY(expA > 0.0);
        QVERIFY2(std::fabs(a.thermalError_um(px) - expA) < 1e-9 * expA,
                 qPrintable(QString("%1 vs %2").arg(a.thermalError_um(px)).arg(expA)));
        // eq. (15), P_f > 0: TE(P_x) = -TE_m(P_f - P_x)
        const double qx = pPos.fixedEndPosition_mm - d_mm;
        const double expB = -teM(b, (pPos.fixedEndPosition_mm - qx) / 1000.0);
        QVERIFY(expB < 0.0);
        QVERIFY2(std::fabs(b.thermalError_um(qx) - expB) < 1e-9 * std::fabs(expB),
                 qPrintable(QString("%1 vs %2").arg(b.thermalError_um(qx)).arg(expB)));
    }
    // error grows monotonically away from the fixed end (all cells above ambient)
    QVERIFY(a.thermalError_um(pNeg.fixedEndPosition_mm + 600.0) > a.thermalError_um(pNeg.fixedEndPosition_mm + 300.0));
    QVERIFY(b.thermalError_um(pPos.fixedEndPosition_mm - 600.0) < b.thermalError_um(pPos.fixedEndPosition_mm - 300.0));
    QVERIFY(std::fabs(a.elongation_um() - teM(a, g.length_m)) < 1e-9 * a.elongation_um());
}

void TestFdmScrewModel::ambientOnlyChangeGivesLinearExpansion()
{
    const ScrewGeometry g;
    const FdmParameters p;
    FdmScrewModel model(g, p);
    model.reset(20.0);
    const double dTa = 3.0;
    // No feed: no heat; the screw relaxes to the new ambient (tau = rho c D / 4 h ~ 1100 s).
    for (int k = 0; k < 400000; ++k) // 40000 s
        model.step(axisForNut(p, 0.4), 0.0, 20.0 + dTa);
    QCOMPARE(model.ambient_C(), 23.0);
    const double expected = g.expansion_per_K * dTa * g.length_m * 1e6; // eq. (1), um
    QVERIFY2(std::fabs(model.elongation_um() - expected) < 1e-6 * expected,
             qPrintable(QString("%1 vs %2").arg(model.elongation_um()).arg(expected)));
    for (double d_mm : {0.0, 100.0, 437.5, 800.0}) {
        const double px = p.fixedEndPosition_mm + d_mm;
        const double te = g.expansion_per_K * dTa * d_mm * 1e3; // alpha dTa X_N in um
        QVERIFY2(std::fabs(model.thermalError_um(px) - te) < 1e-6 * expected,
                 qPrintable(QString("%1: %2 vs %3").arg(d_mm).arg(model.thermalError_um(px)).arg(te)));
    }
}

void TestFdmScrewModel::energyIsConservedWithoutConvection()
{
    ScrewGeometry g;
    g.nutLength_m = 0.20; // whole number of cells: eq. (10) then covers exactly 20 cells
    FdmParameters p;
    p.k1 = 0.0;
    p.k2 = 0.0; // h = 0: adiabatic everywhere
    const FdmSettings s;
    FdmScrewModel model(g, p, s);
    const double T0 = 20.0;
    model.reset(T0);
    const double dt = s.dt_s;
    const DutyCycle cycle; // nut between 0.15 m and 0.65 m: never clipped, never on the bearing
    const long steps = std::lround(3600.0 / dt);
    double injected = 0.0;
    bool coverageOk = true;
    for (long k = 0; k < steps; ++k) {
        const double t = (k + 0.5) * dt * 2.8; // compress the cycle: warm, cool and warm in 1 h
        const double feed = cycle.feed(t);
        const double pos = cycle.position(t);
        int f = 0, l = 0, nb = 0;
        model.heatedCells((pos - p.fixedEndPosition_mm) / 1000.0, f, l, nb);
        coverageOk = coverageOk && (l - f + 1 == 20) && nb == 3;
        model.step(pos, feed, T0 + 5.0 * std::sin(k * 1e-3)); // ambient irrelevant at h = 0
        injected += (p.k3 + p.k4) * std::fabs(feed) * dt;       // (Q_B + Q_N) dt
    }
    QVERIFY(coverageOk);
    const double area = kPi * g.diameter_m * g.diameter_m / 4.0;
    double sum = 0.0;
    for (double T : model.temperatures())
        sum += T - T0;
    const double stored = g.density_kg_m3 * g.specificHeat_J_kgK * area * s.dx_m * sum;
    qInfo("energy: injected %.6f J, stored %.6f J, relative difference %.3e", injected, stored,
          std::fabs(stored - injected) / injected);
    QVERIFY(injected > 1e4);
    QVERIFY2(std::fabs(stored - injected) <= 1e-9 * injected,
             qPrintable(QString("stored %1 J vs injected %2 J").arg(stored, 0, 'g', 15).arg(injected, 0, 'g', 15)));
}

void TestFdmScrewModel::invalidGeometryThrows()
{
    auto throws = [](const ScrewGeometry &g, const FdmParameters &p, const FdmSettings &s) {
        try {
            FdmScrewModel m(g, p, s);
        } catch (const std::invalid_argument &) {
            return true;
        }
        return false;
    };
    const FdmParameters p0;
    const FdmSettings s0;
    QVERIFY(!throws(ScrewGeometry{}, p0, s0));
    {
        ScrewGeometry g;
        g.length_m = -0.8;
        QVERIFY(throws(g, p0, s0));
        g.length_m = 0.0;
        QVERIFY(throws(g, p0, s0));
        g.length_m = std::numeric_limits<double>::quiet_NaN();
        QVERIFY(throws(g, p0, s0));
    }
    {
        ScrewGeometry g;
        g.diameter_m = 0.0;
        QVERIFY(throws(g, p0, s0));
    }
    {
        ScrewGeometry g;
        g.nutLength_m = -0.1;
        QVERIFY(throws(g, p0, s0));
    }
    {
        ScrewGeometry g;
        g.fixedBearingLength_m = -0.01;
        QVERIFY(throws(g, p0, s0));
    }
    {
        ScrewGeometry g;
        g.density_kg_m3 = 0.0;
        QVERIFY(throws(g, p0, s0));
        g = ScrewGeometry{};
        g.specificHeat_J_kgK = -1.0;
        QVERIFY(throws(g, p0, s0));
    }
    {
        FdmParameters p;
        p.conductivity_W_mK = 0.0;
        QVERIFY(throws(ScrewGeometry{}, p, s0));
    }
    {
        FdmSettings s;
        s.dx_m = 0.0;
        QVERIFY(throws(ScrewGeometry{}, p0, s));
        s.dx_m = 1.0; // longer than the screw
        QVERIFY(throws(ScrewGeometry{}, p0, s));
        s = FdmSettings{};
        s.dt_s = -0.1;
        QVERIFY(throws(ScrewGeometry{}, p0, s));
    }
}

QTEST_APPLESS_MAIN(TestFdmScrewModel)

#include "tst_fdmscrewmodel.moc"

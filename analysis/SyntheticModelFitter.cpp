#include "SyntheticModelFitter.h"

#include "DataDrivenPredictor.h"
#include "NonlinearUncertainty.h"
#include "SolverOptions.h"

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace driftlab {

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Linear interpolation of a column with NaN gaps at time s (NaN if no finite neighbours).
double valueAt(const SignalTable &table, const std::vector<double> &v, double s)
{
    const auto it = std::lower_bound(table.t.begin(), table.t.end(), s);
    const std::size_t k = static_cast<std::size_t>(it - table.t.begin());
    if (k < table.t.size() && table.t[k] == s)
        return v[k];
    if (k == 0 || k >= table.t.size())
        return kNaN;
    const double a = v[k - 1], b = v[k];
    if (!std::isfinite(a) || !std::isfinite(b))
        return kNaN;
    const double w = (s - table.t[k - 1]) / (table.t[k] - table.t[k - 1]);
    return a + w * (b - a);
}

double meanAt(const SignalTable &table, const std::vector<const SignalColumn *> &cols, double s)
{
    double sum = 0;
    for (const SignalColumn *c : cols)
        sum += valueAt(table, c->v, s);
    return sum / static_cast<double>(cols.size());
}

struct Sample {
    double t, p, temp, e;
};

// g(T) (P - P0) / (Pref - P0); theta = a, b, c[, P0]
double synthetic(const double *q, bool position, double pRef, double t0, const Sample &s)
{
    const double g = q[2] + q[0] * (std::exp(q[1] * (s.temp - t0)) - 1.0);
    if (!position)
        return g;
    return g * (s.p - q[3]) / (pRef - q[3]);
}

struct Cost {
    const std::vector<Sample> *samples;
    bool position;
    double pRef, t0;
    bool operator()(double const *const *x, double *r) const
    {
        for (std::size_t i = 0; i < samples->size(); ++i)
            r[i] = (*samples)[i].e - synthetic(x[0], position, pRef, t0, (*samples)[i]);
        return true;
    }
};

// y0 + A1 (1 - exp(-t/tau1)) + A2 (1 - exp(-t/tau2)) by a grid over tau1 < tau2 with the
// amplitudes by least squares. Returns {y0, A1, tau1, A2, tau2} and R^2.
std::vector<double> timeLaw(const std::vector<double> &t, const std::vector<double> &y, double &r2)
{
    r2 = 0;
    if (t.size() < 6)
        return {};
    const Eigen::Index n = static_cast<Eigen::Index>(t.size());
    Eigen::VectorXd Y = Eigen::Map<const Eigen::VectorXd>(y.data(), n);
    const double ss = (Y.array() - Y.mean()).square().sum();
    double best = std::numeric_limits<double>::infinity();
    std::vector<double> out;
    const int g = 24;
    for (int i = 0; i < g; ++i)
        for (int j = i + 1; j < g; ++j) {
            const double t1 = 60.0 * std::pow(2e5 / 60.0, i / (g - 1.0)), t2 = 60.0 * std::pow(2e5 / 60.0, j / (g - 1.0));
            Eigen::MatrixXd X(n, 3);
            for (Eigen::Index k = 0; k < n; ++k) {
                const double s = t[static_cast<std::size_t>(k)];
                X(k, 0) = 1.0;
                X(k, 1) = 1.0 - std::exp(-s / t1);
                X(k, 2) = 1.0 - std::exp(-s / t2);
            }
            const Eigen::VectorXd c = X.colPivHouseholderQr().solve(Y);
            const double sse = (Y - X * c).squaredNorm();
            if (sse < best) {
                best = sse;
                out = {c(0), c(1), t1, c(2), t2};
            }
        }
    r2 = ss > 0 ? 1.0 - best / ss : 0.0;
    return out;
}

} // namespace

std::vector<double> SyntheticModelFitter::predictPoints(const DataDrivenModel &model, const SignalTable &table,
                                                        const std::vector<PositioningErrorPoint> &points)
{
    DataDrivenPredictor predictor(model);
    std::vector<double> inputs(model.inputs.size()), out;
    for (const PositioningErrorPoint &p : points) {
        for (std::size_t i = 0; i < inputs.size(); ++i)
            inputs[i] = valueAt(table, table.column(model.inputs[i].id).v, p.t_s);
        out.push_back(predictor.predictAt(p.position_mm, inputs.data()));
    }
    return out;
}

SyntheticFit SyntheticModelFitter::fit(const SignalTable &table, const SyntheticOptions &o)
{
    if (o.temperatures.empty())
        throw std::invalid_argument("synthetic: needs at least one temperature channel (the characteristic temperature)");
    std::vector<const SignalColumn *> temps;
    for (const std::string &id : o.temperatures)
        temps.push_back(&table.column(id));
    const bool position = o.target.empty();
    std::vector<Sample> samples;
    if (position) {
        for (const PositioningErrorPoint &p : o.points) {
            if (p.t_s < o.trainFrom_s || p.t_s >= o.trainTo_s)
                continue;
            const double temp = meanAt(table, temps, p.t_s);
            if (std::isfinite(temp) && std::isfinite(p.error_um))
                samples.push_back({p.t_s, p.position_mm, temp, p.error_um});
        }
    } else {
        const SignalColumn &target = table.column(o.target);
        for (std::size_t k = 0; k < table.t.size(); ++k) {
            if ((!o.trainRows.empty() && !o.trainRows[k]) || !std::isfinite(target.v[k]))
                continue;
            double temp = 0;
            for (const SignalColumn *c : temps)
                temp += c->v[k];
            temp /= static_cast<double>(temps.size());
            if (std::isfinite(temp))
                samples.push_back({table.t[k], 0.0, temp, target.v[k]});
        }
    }
    if (samples.size() < 8)
        throw std::invalid_argument("synthetic: " + std::to_string(samples.size()) +
                                    (position ? " interferometer points" : " samples") +
                                    " have a characteristic temperature in the training range; at least 8 are needed");
    SyntheticFit fit;
    fit.samples = samples.size();
    const double t0 = samples.front().temp;
    double pRef = 0.0, p0 = 0.0;
    if (position) {
        // Eq. (22): linear in position at the last training run (runs split where the time
        // between consecutive points exceeds 5x the median) -> P0 and R^2; P_ref = the target
        // with the largest mean |E| over all runs.
        std::vector<std::size_t> order(samples.size());
        for (std::size_t i = 0; i < order.size(); ++i)
            order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return samples[a].t < samples[b].t; });
        std::vector<double> gaps;
        for (std::size_t i = 1; i < order.size(); ++i)
            gaps.push_back(samples[order[i]].t - samples[order[i - 1]].t);
        std::vector<double> sorted = gaps;
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
        const double split = 5.0 * std::max(sorted[sorted.size() / 2], 1e-9);
        std::size_t runStart = 0;
        for (std::size_t i = 1; i < order.size(); ++i)
            if (gaps[i - 1] > split)
                runStart = i;
        std::map<double, std::pair<double, int>> byTarget;
        for (const Sample &s : samples) {
            auto &acc = byTarget[s.p];
            acc.first += std::fabs(s.e);
            ++acc.second;
        }
        if (byTarget.size() < 2 || order.size() - runStart < 2)
            throw std::invalid_argument("synthetic: the interferometer points need at least two target positions per run");
        const Eigen::Index nRun = static_cast<Eigen::Index>(order.size() - runStart);
        Eigen::MatrixXd X(nRun, 2);
        Eigen::VectorXd Y(nRun);
        for (Eigen::Index i = 0; i < nRun; ++i) {
            const Sample &s = samples[order[runStart + static_cast<std::size_t>(i)]];
            X(i, 0) = 1.0;
            X(i, 1) = s.p;
            Y(i) = s.e;
        }
        const Eigen::VectorXd c = X.colPivHouseholderQr().solve(Y);
        const double ss = (Y.array() - Y.mean()).square().sum();
        fit.positionLawR2 = ss > 0 ? 1.0 - (Y - X * c).squaredNorm() / ss : 0.0;
        double bestMean = -1;
        for (const auto &kv : byTarget)
            if (kv.second.first / kv.second.second > bestMean) {
                bestMean = kv.second.first / kv.second.second;
                pRef = kv.first;
            }
        p0 = std::fabs(c(1)) > 1e-12 ? -c(0) / c(1) : 0.0;
        if (!std::isfinite(p0) || std::fabs(p0 - pRef) < 1e-6)
            p0 = pRef - 1000.0;
    } else {
        pRef = 0.0;
        p0 = -1.0;
    }
    // Initial a, b, c: g linear in T with b = 0.05 /K.
    std::vector<double> q{0.0, 0.05, 0.0, p0};
    {
        Eigen::MatrixXd X(static_cast<Eigen::Index>(samples.size()), 2);
        Eigen::VectorXd Y(X.rows());
        for (std::size_t i = 0; i < samples.size(); ++i) {
            const double ratio = position ? (samples[i].p - p0) / (pRef - p0) : 1.0;
            X(static_cast<Eigen::Index>(i), 0) = ratio;
            X(static_cast<Eigen::Index>(i), 1) = ratio * (samples[i].temp - t0);
            Y(static_cast<Eigen::Index>(i)) = samples[i].e;
        }
        const Eigen::VectorXd c = X.colPivHouseholderQr().solve(Y);
        q[2] = c(0);
        q[0] = c(1) / q[1];
    }
    const int np = position ? 4 : 3;
    auto *fn = new ceres::DynamicNumericDiffCostFunction<Cost, ceres::CENTRAL>(new Cost{&samples, position, pRef, t0});
    fn->AddParameterBlock(np);
    fn->SetNumResiduals(static_cast<int>(samples.size()));
    ceres::Problem problem;
    problem.AddResidualBlock(fn, nullptr, q.data());
    problem.SetParameterLowerBound(q.data(), 1, -2.0);
    problem.SetParameterUpperBound(q.data(), 1, 2.0);
    ceres::Solver::Summary summary;
    ceres::Solve(SolverOptions::denseQr(200), &problem, &summary);

    DataDrivenModel &m = fit.model;
    m.kind = "synthetic";
    if (position)
        m.target = {"interferometer", "um", "positioning_error"};
    else
        m.target = {o.target, table.column(o.target).unit, table.column(o.target).kind};
    for (std::size_t i = 0; i < temps.size(); ++i) {
        m.inputs.push_back({temps[i]->id, temps[i]->unit, temps[i]->kind});
        m.synthetic.temperatures.push_back(static_cast<int>(i));
    }
    m.synthetic.a = q[0];
    m.synthetic.b_perK = q[1];
    m.synthetic.c = q[2];
    m.synthetic.t0_C = t0;
    m.synthetic.p0_mm = position ? q[3] : p0;
    m.synthetic.pRef_mm = pRef;
    if (!position)
        m.samplePeriod_s = table.medianStep();

    fit.names = {"a_um", "b_perK", "c_um"};
    if (position)
        fit.names.push_back("p0_mm");
    fit.values.assign(q.begin(), q.begin() + np);
    std::vector<double> measured;
    for (const Sample &s : samples)
        measured.push_back(s.e);
    const NonlinearUncertainty::Model model = [&](const std::vector<double> &th, std::vector<double> &out) {
        out.resize(samples.size());
        for (std::size_t i = 0; i < samples.size(); ++i)
            out[i] = synthetic(th.data(), position, pRef, t0, samples[i]);
    };
    const Uncertainty u = NonlinearUncertainty::estimate(model, fit.values, measured);
    fit.standardErrors = u.standardErrors;
    fit.seInflation = u.inflation;
    std::vector<double> predicted;
    model(fit.values, predicted);
    fit.training = ErrorMetrics::compute(measured, predicted);

    // Time law at the reference position (or of the displacement channel).
    std::vector<double> tt, yy;
    const double start = samples.front().t;
    for (const Sample &s : samples)
        if (!position || s.p == pRef) {
            tt.push_back(s.t - start);
            yy.push_back(s.e);
        }
    fit.timeLaw = timeLaw(tt, yy, fit.timeLawR2);
    return fit;
}

} // namespace driftlab

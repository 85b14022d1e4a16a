#include "ExponentialWarmupFitter.h"

#include "DataDrivenPredictor.h"
#include "NonlinearUncertainty.h"
#include "SolverOptions.h"
#include "TimeBlockedFolds.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace driftlab {

namespace {

struct Data {
    const std::vector<double> *t = nullptr;
    std::vector<double> v;        // |drive|, gaps held
    double threshold = 0.0;
    double reference = 1.0;
    std::vector<std::size_t> rows;
    std::vector<double> y;
};

// Unit response (k = 1, baseline 0) at the rows, simulated from the session start.
void response(const Data &d, const std::vector<std::size_t> &rows, double tauWarm, double tauCool, double p,
              std::vector<double> &out)
{
    out.assign(rows.size(), 0.0);
    if (rows.empty())
        return;
    const std::vector<double> &t = *d.t;
    double x = 0.0;
    std::size_t r = 0;
    // exp(-dt/tau) for the last (dt, tau): most steps repeat the same sample period.
    double lastDt = -1.0, lastTau = -1.0, keep = 0.0;
    for (std::size_t k = 0; k <= rows.back(); ++k) {
        if (k > 0) {
            const bool on = d.v[k] > d.threshold;
            const double ratio = d.v[k] / d.reference;
            const double goal = on ? (p == 1.0 ? ratio : std::pow(ratio, p)) : 0.0;
            const double dt = t[k] - t[k - 1], tau = on ? tauWarm : tauCool;
            if (dt != lastDt || tau != lastTau) {
                keep = std::exp(-dt / tau);
                lastDt = dt;
                lastTau = tau;
            }
            x = goal + keep * (x - goal); // DataDrivenPredictor::lagStep
        }
        if (k == rows[r])
            out[r++] = x;
    }
}

struct Params {
    double baseline = 0, k = 0, tauWarm = 1000, tauCool = 1000, p = 1;
};

// baseline, k by least squares for a given unit response.
double linearPart(const std::vector<double> &y, const std::vector<double> &s, double &b, double &k)
{
    const double n = static_cast<double>(y.size());
    double sy = 0, ss = 0, sss = 0, ssy = 0;
    for (std::size_t i = 0; i < y.size(); ++i) {
        sy += y[i];
        ss += s[i];
        sss += s[i] * s[i];
        ssy += s[i] * y[i];
    }
    const double det = n * sss - ss * ss;
    if (std::fabs(det) < 1e-12 * std::max(1.0, n * sss)) {
        b = sy / n;
        k = 0;
    } else {
        k = (n * ssy - ss * sy) / det;
        b = (sy - k * ss) / n;
    }
    double sse = 0;
    for (std::size_t i = 0; i < y.size(); ++i)
        sse += (y[i] - b - k * s[i]) * (y[i] - b - k * s[i]);
    return sse;
}

struct Cost {
    const Data *d;
    const std::vector<std::size_t> *rows;
    const std::vector<double> *y;
    bool fitExponent;
    bool operator()(double const *const *x, double *residuals) const
    {
        const double *q = x[0];
        std::vector<double> s;
        response(*d, *rows, std::exp(q[2]), std::exp(q[3]), fitExponent ? q[4] : 1.0, s);
        for (std::size_t i = 0; i < s.size(); ++i)
            residuals[i] = (*y)[i] - q[0] - q[1] * s[i];
        return true;
    }
};

Params fitRows(const Data &d, const std::vector<std::size_t> &rows, const std::vector<double> &y, bool fitExponent,
               bool *converged)
{
    Params best;
    double bestSse = std::numeric_limits<double>::infinity();
    std::vector<double> s;
    for (int i = 0; i < 14; ++i)
        for (int j = 0; j < 14; ++j) {
            const double tw = 60.0 * std::pow(2e5 / 60.0, i / 13.0), tc = 60.0 * std::pow(2e5 / 60.0, j / 13.0);
            response(d, rows, tw, tc, 1.0, s);
            double b = 0, k = 0;
            const double sse = linearPart(y, s, b, k);
            if (sse < bestSse) {
                bestSse = sse;
                best = {b, k, tw, tc, 1.0};
            }
        }
    std::vector<double> q{best.baseline, best.k, std::log(best.tauWarm), std::log(best.tauCool), 1.0};
    const int np = fitExponent ? 5 : 4;
    auto *fn = new ceres::DynamicNumericDiffCostFunction<Cost, ceres::CENTRAL>(new Cost{&d, &rows, &y, fitExponent});
    fn->AddParameterBlock(np);
    fn->SetNumResiduals(static_cast<int>(rows.size()));
    ceres::Problem problem;
    problem.AddResidualBlock(fn, nullptr, q.data());
    const double lo = std::log(1.0), hi = std::log(1e7);
    problem.SetParameterLowerBound(q.data(), 2, lo);
    problem.SetParameterUpperBound(q.data(), 2, hi);
    problem.SetParameterLowerBound(q.data(), 3, lo);
    problem.SetParameterUpperBound(q.data(), 3, hi);
    if (fitExponent) {
        problem.SetParameterLowerBound(q.data(), 4, 0.2);
        problem.SetParameterUpperBound(q.data(), 4, 4.0);
    }
    ceres::Solver::Summary summary;
    ceres::Solve(SolverOptions::denseQr(100), &problem, &summary);
    if (converged)
        *converged = summary.termination_type == ceres::CONVERGENCE;
    return {q[0], q[1], std::exp(q[2]), std::exp(q[3]), fitExponent ? q[4] : 1.0};
}

} // namespace

ExponentialFit ExponentialWarmupFitter::fit(const SignalTable &table, const ExponentialOptions &o,
                                            const std::function<bool(double)> &progress)
{
    const SignalColumn &target = table.column(o.target);
    if (o.drive.empty())
        throw std::invalid_argument("exp: needs a drive channel (spindle speed or feed)");
    const SignalColumn &drive = table.column(o.drive);
    const std::size_t N = table.t.size();
    Data d;
    d.t = &table.t;
    d.v.resize(N);
    double last = std::numeric_limits<double>::quiet_NaN();
    for (double x : drive.v)
        if (std::isfinite(x)) {
            last = x;
            break;
        }
    for (std::size_t k = 0; k < N; ++k) {
        if (std::isfinite(drive.v[k]))
            last = drive.v[k];
        d.v[k] = std::fabs(last);
    }
    for (std::size_t k = 0; k < N; ++k)
        if ((o.trainRows.empty() || o.trainRows[k]) && std::isfinite(target.v[k]) && std::isfinite(drive.v[k])) {
            d.rows.push_back(k);
            d.y.push_back(target.v[k]);
        }
    if (d.rows.size() < 20)
        throw std::invalid_argument("exp: " + std::to_string(d.rows.size()) +
                                    " training samples have the target and the drive; at least 20 are needed");
    d.reference = 0.0;
    for (std::size_t r : d.rows)
        d.reference = std::max(d.reference, d.v[r]);
    if (!(d.reference > 0))
        throw std::invalid_argument("exp: drive '" + o.drive + "' is zero over the training samples");
    d.threshold = 0.02 * d.reference;
    std::set<long> levels;
    for (std::size_t r : d.rows)
        if (d.v[r] > d.threshold)
            levels.insert(std::lround(100.0 * d.v[r] / d.reference));
    ExponentialFit fit;
    fit.exponentFitted = levels.size() >= 2;
    fit.trainingRows = d.rows.size();
    if (progress && !progress(0.05))
        throw std::runtime_error("cancelled");
    const Params p = fitRows(d, d.rows, d.y, fit.exponentFitted, &fit.converged);

    DataDrivenModel &m = fit.model;
    m.kind = "exp";
    m.target = {target.id, target.unit, target.kind};
    m.inputs = {{drive.id, drive.unit, drive.kind}};
    m.exponential.drive = 0;
    m.exponential.onThreshold = d.threshold;
    m.exponential.referenceDrive = d.reference;
    m.exponential.steadyState = p.k;
    m.exponential.exponent = p.p;
    m.exponential.tauWarm_s = p.tauWarm;
    m.exponential.tauCool_s = p.tauCool;
    m.exponential.baseline = p.baseline;
    m.exponential.expansion_per_K = o.expansion_per_K;
    m.exponential.length_m = o.length_m;
    std::vector<double> times;
    for (std::size_t r : d.rows)
        times.push_back(table.t[r]);
    m.samplePeriod_s = SignalTable::medianInterval(times);

    // Standard errors from the numerical Jacobian in natural units.
    fit.names = {"baseline", "steady_state", "tau_warm_s", "tau_cool_s"};
    std::vector<double> theta{p.baseline, p.k, p.tauWarm, p.tauCool};
    if (fit.exponentFitted) {
        fit.names.push_back("exponent");
        theta.push_back(p.p);
    }
    auto model = [&](const std::vector<double> &th, std::vector<double> &out) {
        std::vector<double> s;
        response(d, d.rows, th[2], th[3], th.size() > 4 ? th[4] : 1.0, s);
        out.resize(s.size());
        for (std::size_t i = 0; i < s.size(); ++i)
            out[i] = th[0] + th[1] * s[i];
    };
    const Uncertainty u = NonlinearUncertainty::estimate(model, theta, d.y);
    fit.values = theta;
    fit.standardErrors = u.standardErrors;
    fit.seInflation = u.inflation;

    std::vector<char> mask(N, 0);
    for (std::size_t r : d.rows)
        mask[r] = 1;
    fit.training = ErrorMetrics::compute(target.v, DataDrivenPredictor::run(m, table.t, {drive.v}), &mask);

    if (o.crossValidate) {
        const double gap = o.gap_s >= 0 ? o.gap_s : TimeBlockedFolds::defaultGap(times, o.folds);
        const std::vector<TimeBlockedFold> folds = TimeBlockedFolds::make(times, o.folds, gap);
        double sseCv = 0, count = 0;
        for (std::size_t f = 0; f < folds.size(); ++f) {
            std::vector<std::size_t> rows;
            std::vector<double> y;
            for (std::size_t i = 0; i < d.rows.size(); ++i)
                if (i < folds[f].excludeBegin || i >= folds[f].excludeEnd) {
                    rows.push_back(d.rows[i]);
                    y.push_back(d.y[i]);
                }
            const Params q = fitRows(d, rows, y, fit.exponentFitted, nullptr);
            const std::vector<std::size_t> block(d.rows.begin() + static_cast<std::ptrdiff_t>(folds[f].begin),
                                                 d.rows.begin() + static_cast<std::ptrdiff_t>(folds[f].end));
            std::vector<double> s;
            response(d, block, q.tauWarm, q.tauCool, q.p, s);
            double foldSse = 0;
            for (std::size_t i = 0; i < block.size(); ++i) {
                const double r = d.y[folds[f].begin + i] - q.baseline - q.k * s[i];
                foldSse += r * r;
            }
            fit.foldRmse.push_back(std::sqrt(foldSse / static_cast<double>(block.size())));
            sseCv += foldSse;
            count += static_cast<double>(block.size());
            if (progress && !progress(0.1 + 0.9 * static_cast<double>(f + 1) / static_cast<double>(folds.size())))
                throw std::runtime_error("cancelled");
        }
        fit.cvRmse = std::sqrt(sseCv / count);
    }
    return fit;
}

} // namespace driftlab

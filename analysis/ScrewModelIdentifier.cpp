#include "ScrewModelIdentifier.h"

#include "BearingHeatSource.h"
#include "NutHeatSource.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace driftlab {

namespace {

// Forwards Ceres iterations to IdentificationOptions::progress; a false answer aborts.
class ProgressCallback : public ceres::IterationCallback {
public:
    explicit ProgressCallback(const std::function<bool(int, double)> &progress) : m_progress(progress) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary &summary) override
    {
        if (m_progress && !m_progress(summary.iteration, summary.cost)) {
            m_cancelled = true;
            return ceres::SOLVER_ABORT;
        }
        return ceres::SOLVER_CONTINUE;
    }
    bool cancelled() const { return m_cancelled; }

private:
    const std::function<bool(int, double)> &m_progress;
    bool m_cancelled = false;
};


constexpr int kBase = 4; // k1, k2, lambda, P_f

// Gaussian priors on some of the optimiser's (scaled) variables: r = (u_k scale - mean) / sigma.
class PriorCost : public ceres::CostFunction {
public:
    struct Term {
        int k;
        double mean, sigma, scale;
    };
    PriorCost(std::vector<Term> terms, int n) : m_terms(std::move(terms)), m_n(n)
    {
        set_num_residuals(static_cast<int>(m_terms.size()));
        mutable_parameter_block_sizes()->push_back(n);
    }
    bool Evaluate(double const *const *u, double *r, double **jacobians) const override
    {
        for (size_t i = 0; i < m_terms.size(); ++i) {
            const Term &t = m_terms[i];
            r[i] = (u[0][t.k] * t.scale - t.mean) / t.sigma;
            if (jacobians && jacobians[0]) {
                std::fill(jacobians[0] + i * static_cast<size_t>(m_n), jacobians[0] + (i + 1) * static_cast<size_t>(m_n), 0.0);
                jacobians[0][i * static_cast<size_t>(m_n) + static_cast<size_t>(t.k)] = t.scale / t.sigma;
            }
        }
        return true;
    }

private:
    std::vector<Term> m_terms;
    int m_n;
};

// min |A a - z|^2 subject to lo <= a <= hi (simple active-set method for a handful of
// columns). Columns are normalised first: unit amplitudes differ by orders of magnitude.
Eigen::VectorXd boundedLeastSquares(const Eigen::MatrixXd &A, const Eigen::VectorXd &z, const Eigen::VectorXd &lo,
                                    const Eigen::VectorXd &hi)
{
    const int m = static_cast<int>(A.cols());
    Eigen::VectorXd norm(m);
    for (int c = 0; c < m; ++c)
        norm[c] = std::max(A.col(c).norm(), 1e-300);
    const Eigen::MatrixXd As = A * norm.cwiseInverse().asDiagonal();
    const Eigen::VectorXd los = lo.cwiseProduct(norm), his = hi.cwiseProduct(norm);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
    std::vector<int> state(static_cast<size_t>(m), 0); // 0 free, -1 at lower, +1 at upper
    for (int iter = 0; iter < 4 * m + 4; ++iter) {
        std::vector<int> freeIdx;
        Eigen::VectorXd zr = z;
        for (int c = 0; c < m; ++c) {
            if (state[static_cast<size_t>(c)] == 0) {
                freeIdx.push_back(c);
            } else {
                b[c] = state[static_cast<size_t>(c)] < 0 ? los[c] : his[c];
                zr -= As.col(c) * b[c];
            }
        }
        if (!freeIdx.empty()) {
            Eigen::MatrixXd Af(As.rows(), static_cast<Eigen::Index>(freeIdx.size()));
            for (size_t k = 0; k < freeIdx.size(); ++k)
                Af.col(static_cast<Eigen::Index>(k)) = As.col(freeIdx[k]);
            const Eigen::VectorXd bf = Af.colPivHouseholderQr().solve(zr);
            // Most violated free variable goes to its bound.
            int worst = -1;
            double worstViolation = 0.0;
            for (size_t k = 0; k < freeIdx.size(); ++k) {
                const int c = freeIdx[k];
                const double v = bf[static_cast<Eigen::Index>(k)];
                const double viol = std::max(los[c] - v, v - his[c]);
                if (viol > worstViolation) {
                    worstViolation = viol;
                    worst = c;
                }
                b[c] = v;
            }
            if (worst >= 0) {
                state[static_cast<size_t>(worst)] = b[worst] < los[worst] ? -1 : 1;
                continue;
            }
        }
        // KKT: release a bound variable whose gradient points into the feasible box.
        const Eigen::VectorXd g = As.transpose() * (As * b - z);
        int release = -1;
        double best = 0.0;
        for (int c = 0; c < m; ++c) {
            const int s = state[static_cast<size_t>(c)];
            const double push = s < 0 ? -g[c] : (s > 0 ? g[c] : 0.0);
            if (push > best * 1.0 + 1e-12 * (1.0 + z.norm())) {
                best = push;
                release = c;
            }
        }
        if (release < 0)
            break;
        state[static_cast<size_t>(release)] = 0;
    }
    return b.cwiseQuotient(norm);
}

// Residuals of the projected problem for a full nonlinear vector x (unscaled).
class VarPro {
public:
    VarPro(ScrewResponseSimulator &sim, std::vector<int> componentOffsets)
        : m_sim(sim), m_offsets(std::move(componentOffsets))
    {
        const auto &obs = sim.observations();
        const int n = sim.rowCount();
        m_y.resize(n);
        m_w.resize(n);
        for (int r = 0; r < n; ++r) {
            m_y[r] = obs[static_cast<size_t>(r)].measured_um;
            m_w[r] = 1.0 / obs[static_cast<size_t>(r)].sigma_um;
        }
        const int m = sim.columnCount() - 1;
        m_lo.resize(m);
        m_hi.resize(m);
        int c = 0;
        for (const auto &s : sim.sources()) {
            const ParameterSpec a = s->amplitude();
            m_lo[c] = a.lower;
            m_hi[c++] = a.upper;
        }
        for (const auto &t : sim.errorTerms()) {
            const ParameterSpec a = t->amplitude();
            m_lo[c] = a.lower;
            m_hi[c++] = a.upper;
        }
    }

    void simulate(const double *x)
    {
        for (size_t i = 0; i < m_sim.sources().size(); ++i)
            if (m_offsets[i + 1] > m_offsets[i])
                m_sim.sources()[i]->setNonlinearParameters(x + kBase + m_offsets[i]);
        m_sim.simulate(x[0], x[1], x[2], x[3], m_phi);
        ++evaluations;
    }

    // Solves the amplitudes and writes weighted residuals.
    void residuals(const double *x, double *r, Eigen::VectorXd *amplitudesOut)
    {
        simulate(x);
        const Eigen::VectorXd z = (m_y - m_phi.col(0)).cwiseProduct(m_w);
        const Eigen::MatrixXd A = m_w.asDiagonal() * m_phi.rightCols(m_phi.cols() - 1);
        const Eigen::VectorXd a = boundedLeastSquares(A, z, m_lo, m_hi);
        Eigen::Map<Eigen::VectorXd>(r, m_y.size()) = A * a - z;
        if (amplitudesOut)
            *amplitudesOut = a;
    }

    // Weighted residuals at given amplitudes (no projection), for the covariance.
    void fixedResiduals(const double *x, const Eigen::VectorXd &a, Eigen::VectorXd &r)
    {
        simulate(x);
        r = (m_phi.col(0) + m_phi.rightCols(m_phi.cols() - 1) * a - m_y).cwiseProduct(m_w);
    }

    const Eigen::MatrixXd &phi() const { return m_phi; }
    const Eigen::VectorXd &weights() const { return m_w; }
    int rows() const { return static_cast<int>(m_y.size()); }
    int evaluations = 0;

private:
    ScrewResponseSimulator &m_sim;
    std::vector<int> m_offsets; // start of each source's nonlinear parameters (after kBase), + end
    Eigen::VectorXd m_y, m_w, m_lo, m_hi;
    Eigen::MatrixXd m_phi;
};

// The last residual vectors the solver asked for, by parameter vector (exact match). Ceres
// evaluates the same points more than once per iteration under bounds: the projected line
// search evaluates the step (with its forward-difference gradient: one point per parameter),
// then the candidate's cost at the same point, then the Jacobian there again after a
// successful step. A repeated point is answered from here instead of a new simulation, so
// the fit is bit-identical and about half the simulations go.
class EvaluationMemo {
public:
    explicit EvaluationMemo(size_t capacity) : m_capacity(capacity) {}
    bool find(const double *parameters, size_t n, double *residuals, size_t rows) const
    {
        for (const Entry &e : m_entries)
            if (std::equal(e.parameters.begin(), e.parameters.end(), parameters, parameters + n)) {
                std::copy(e.residuals.begin(), e.residuals.begin() + static_cast<std::ptrdiff_t>(rows), residuals);
                return true;
            }
        return false;
    }
    void store(const double *parameters, size_t n, const double *residuals, size_t rows)
    {
        if (m_entries.size() < m_capacity)
            m_entries.emplace_back();
        Entry &e = m_entries[m_next];
        m_next = (m_next + 1) % m_capacity;
        e.parameters.assign(parameters, parameters + n);
        e.residuals.assign(residuals, residuals + rows);
    }

private:
    struct Entry {
        std::vector<double> parameters, residuals;
    };
    size_t m_capacity;
    size_t m_next = 0;
    std::vector<Entry> m_entries;
};

struct ProjectedCost {
    VarPro *problem;
    std::vector<double> base;   // full x, unscaled
    std::vector<int> freeIndex; // which entries of x the optimiser moves
    std::vector<double> scale;
    // Two points' forward differences (the step's and the one before it): 2 (1 + free).
    std::shared_ptr<EvaluationMemo> memo;

    bool operator()(double const *const *parameters, double *residuals) const
    {
        const size_t n = freeIndex.size();
        const size_t rows = static_cast<size_t>(problem->rows());
        if (memo && memo->find(parameters[0], n, residuals, rows))
            return true;
        std::vector<double> x = base;
        for (size_t k = 0; k < n; ++k)
            x[static_cast<size_t>(freeIndex[k])] = parameters[0][k] * scale[k];
        if (!(x[2] > 0))
            return false;
        try {
            problem->residuals(x.data(), residuals, nullptr);
        } catch (const std::invalid_argument &) {
            return false;
        }
        if (memo)
            memo->store(parameters[0], n, residuals, rows);
        return true;
    }
};

FitStatistics statistics(const ScrewResponseSimulator &sim, const Eigen::VectorXd &predicted)
{
    FitStatistics s;
    double si = 0.0, se = 0.0, st = 0.0, lo = 0.0, hi = 0.0;
    bool any = false;
    for (int r = 0; r < sim.rowCount(); ++r) {
        const ResponseObservation &o = sim.observations()[static_cast<size_t>(r)];
        ObservationFit p{o.recording, o.elongation, o.t_s, o.position_mm, o.measured_um, predicted[r], o.temperature,
                         o.distance_m};
        s.points.push_back(p);
        const double e = p.predicted_um - p.measured_um;
        if (o.temperature) {
            ++s.temperaturePoints;
            st += e * e;
        } else if (o.elongation) {
            ++s.elongationPoints;
            se += e * e;
            s.elongationPeak_um = std::max(s.elongationPeak_um, std::fabs(o.measured_um));
        } else {
            ++s.interferometerPoints;
            si += e * e;
            lo = any ? std::min(lo, o.measured_um) : o.measured_um;
            hi = any ? std::max(hi, o.measured_um) : o.measured_um;
            any = true;
        }
    }
    s.interferometerRms_um = s.interferometerPoints ? std::sqrt(si / s.interferometerPoints) : 0.0;
    s.elongationRms_um = s.elongationPoints ? std::sqrt(se / s.elongationPoints) : 0.0;
    s.temperatureRms_K = s.temperaturePoints ? std::sqrt(st / s.temperaturePoints) : 0.0;
    s.interferometerPeakToValley_um = hi - lo;
    return s;
}

} // namespace

ScrewModelIdentifier::ScrewModelIdentifier(const ScrewGeometry &geometry, const IdentificationOptions &options)
    : m_geometry(geometry), m_options(options)
{
    m_sources.push_back(std::make_shared<BearingHeatSource>());
    m_sources.push_back(std::make_shared<NutHeatSource>());
}

void ScrewModelIdentifier::addHeatSource(std::shared_ptr<HeatSourceComponent> source)
{
    if (!source)
        throw std::invalid_argument("ScrewModelIdentifier::addHeatSource: null source");
    m_sources.push_back(std::move(source));
}

void ScrewModelIdentifier::addErrorTerm(std::shared_ptr<ErrorTermComponent> term)
{
    if (!term)
        throw std::invalid_argument("ScrewModelIdentifier::addErrorTerm: null term");
    m_terms.push_back(std::move(term));
}

IdentificationResult ScrewModelIdentifier::fit(const std::vector<ScrewRecording> &recordings)
{
    const auto start = std::chrono::steady_clock::now();
    const IdentificationOptions &o = m_options;
    ScrewResponseSimulator sim(m_geometry, recordings, o.simulator, m_sources, m_terms);

    // Nonlinear parameter specs: base four, then each source's own.
    std::vector<ParameterSpec> specs = {
        {"k1", "W/(m^2 K)/(mm/min)", o.initial.k1, o.k1Lower, o.k1Upper, 1e-3},
        {"k2", "W/(m^2 K)", o.initial.k2, o.k2Lower, o.k2Upper, 10.0},
        {"lambda", "W/(m K)", o.initial.conductivity_W_mK, o.lambdaLower, o.lambdaUpper, 100.0},
        {"P_f", "mm", o.initial.fixedEndPosition_mm, o.fixedEndLower_mm, o.fixedEndUpper_mm, 100.0},
    };
    std::vector<int> offsets{0};
    for (const auto &s : m_sources) {
        const auto extra = s->nonlinearParameters();
        specs.insert(specs.end(), extra.begin(), extra.end());
        offsets.push_back(offsets.back() + static_cast<int>(extra.size()));
    }
    VarPro problem(sim, offsets);

    std::vector<double> x;
    for (const ParameterSpec &s : specs)
        x.push_back(std::clamp(s.initial, s.lower, s.upper));
    auto cost = std::make_unique<ProjectedCost>();
    cost->problem = &problem;
    cost->base = x;
    for (int i = 0; i < static_cast<int>(specs.size()); ++i) {
        if (i == 3 && !o.fitFixedEnd)
            continue;
        cost->freeIndex.push_back(i);
        cost->scale.push_back(specs[static_cast<size_t>(i)].scale);
    }
    const int nFree = static_cast<int>(cost->freeIndex.size());
    cost->memo = std::make_shared<EvaluationMemo>(2 * static_cast<size_t>(nFree + 1));
    std::vector<double> u(static_cast<size_t>(nFree));
    for (int k = 0; k < nFree; ++k)
        u[static_cast<size_t>(k)] = x[static_cast<size_t>(cost->freeIndex[static_cast<size_t>(k)])] / cost->scale[static_cast<size_t>(k)];
    const std::vector<int> freeIndex = cost->freeIndex;
    const std::vector<double> freeScale = cost->scale;

    ceres::Problem ceresProblem;
    auto *fn = new ceres::DynamicNumericDiffCostFunction<ProjectedCost, ceres::FORWARD>(cost.release());
    fn->AddParameterBlock(nFree);
    fn->SetNumResiduals(sim.rowCount());
    ceresProblem.AddResidualBlock(fn, nullptr, u.data());
    std::vector<PriorCost::Term> priors;
    for (int k = 0; k < nFree; ++k) {
        const int i = freeIndex[static_cast<size_t>(k)];
        if (i == 2 && o.lambdaPriorSigma > 0)
            priors.push_back({k, o.lambdaPriorMean, o.lambdaPriorSigma, freeScale[static_cast<size_t>(k)]});
        if (i == 3 && o.fixedEndPriorSigma_mm > 0)
            priors.push_back({k, o.fixedEndPriorMean_mm, o.fixedEndPriorSigma_mm, freeScale[static_cast<size_t>(k)]});
    }
    if (!priors.empty())
        ceresProblem.AddResidualBlock(new PriorCost(std::move(priors), nFree), nullptr, u.data());
    for (int k = 0; k < nFree; ++k) {
        const ParameterSpec &s = specs[static_cast<size_t>(freeIndex[static_cast<size_t>(k)])];
        if (std::isfinite(s.lower))
            ceresProblem.SetParameterLowerBound(u.data(), k, s.lower / s.scale);
        if (std::isfinite(s.upper))
            ceresProblem.SetParameterUpperBound(u.data(), k, s.upper / s.scale);
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.line_search_interpolation_type = ceres::QUADRATIC;
    so.max_num_iterations = o.maxIterations;
    so.function_tolerance = 1e-10;
    so.gradient_tolerance = 1e-12;
    so.parameter_tolerance = 1e-9;
    so.num_threads = 1;
    so.logging_type = ceres::SILENT;
    ProgressCallback callback(o.progress);
    if (o.progress)
        so.callbacks.push_back(&callback);
    ceres::Solver::Summary summary;
    ceres::Solve(so, &ceresProblem, &summary);
    if (callback.cancelled())
        throw IdentificationCancelled();
    if (summary.termination_type == ceres::FAILURE)
        throw std::runtime_error("screw model identification failed: " + summary.message);
    for (int k = 0; k < nFree; ++k)
        x[static_cast<size_t>(freeIndex[static_cast<size_t>(k)])] = u[static_cast<size_t>(k)] * freeScale[static_cast<size_t>(k)];

    IdentificationResult res;
    Eigen::VectorXd residual(sim.rowCount()), amps;
    problem.residuals(x.data(), residual.data(), &amps);
    res.iterations = static_cast<int>(summary.iterations.size());
    res.converged = summary.termination_type == ceres::CONVERGENCE;
    res.solverReport = summary.BriefReport();
    res.amplitudes.assign(amps.data(), amps.data() + amps.size());
    res.nonlinearComponentValues.assign(x.begin() + kBase, x.end());
    res.parameters.k1 = x[0];
    res.parameters.k2 = x[1];
    res.parameters.conductivity_W_mK = x[2];
    res.parameters.fixedEndPosition_mm = x[3];
    res.parameters.k3 = amps[0];
    res.parameters.k4 = amps[1];
    const int rows = sim.rowCount();
    res.weightedRms = std::sqrt(residual.squaredNorm() / rows);
    const Eigen::VectorXd predicted = problem.phi().col(0) + problem.phi().rightCols(amps.size()) * amps;
    res.fit = statistics(sim, predicted);

    // Full parameter list in reporting order and the Jacobian of the fitted ones.
    struct Entry {
        IdentifiedParameter p;
        int nonlinearIndex; // into x, or -1
        int amplitudeIndex; // into amps, or -1
    };
    std::vector<Entry> entries;
    auto nonlinearEntry = [&](int i) {
        const ParameterSpec &s = specs[static_cast<size_t>(i)];
        const bool fitted = std::find(freeIndex.begin(), freeIndex.end(), i) != freeIndex.end();
        entries.push_back({{s.name, s.unit, x[static_cast<size_t>(i)], 0.0, false, fitted}, i, -1});
    };
    auto amplitudeEntry = [&](int a, const ParameterSpec &s) {
        entries.push_back({{s.name, s.unit, amps[a], 0.0, true, true}, -1, a});
    };
    nonlinearEntry(0);
    nonlinearEntry(1);
    amplitudeEntry(0, m_sources[0]->amplitude());
    amplitudeEntry(1, m_sources[1]->amplitude());
    nonlinearEntry(2);
    nonlinearEntry(3);
    for (size_t s = 2; s < m_sources.size(); ++s) {
        amplitudeEntry(static_cast<int>(s), m_sources[s]->amplitude());
        for (int k = offsets[s]; k < offsets[s + 1]; ++k)
            nonlinearEntry(kBase + k);
    }
    for (size_t t = 0; t < m_terms.size(); ++t)
        amplitudeEntry(static_cast<int>(m_sources.size() + t), m_terms[t]->amplitude());

    std::vector<int> fittedEntries;
    for (size_t e = 0; e < entries.size(); ++e)
        if (entries[e].p.fitted)
            fittedEntries.push_back(static_cast<int>(e));
    const int p = static_cast<int>(fittedEntries.size());
    if (!o.standardErrors) {
        for (const Entry &e : entries)
            res.all.push_back(e.p);
        res.evaluations = problem.evaluations;
        res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return res;
    }
    Eigen::MatrixXd J(rows, p);
    const Eigen::MatrixXd phiOpt = problem.phi();
    Eigen::VectorXd rPlus, rMinus;
    for (int c = 0; c < p; ++c) {
        const Entry &e = entries[static_cast<size_t>(fittedEntries[static_cast<size_t>(c)])];
        if (e.amplitudeIndex >= 0) {
            J.col(c) = phiOpt.col(1 + e.amplitudeIndex).cwiseProduct(problem.weights());
        } else {
            const size_t i = static_cast<size_t>(e.nonlinearIndex);
            const ParameterSpec &s = specs[i];
            const double h = 1e-4 * std::max(std::fabs(x[i]), s.scale);
            std::vector<double> xp = x, xm = x;
            xp[i] += h;
            xm[i] -= h;
            if (i == 2)
                xm[i] = std::max(xm[i], 0.5 * x[i]);
            problem.fixedResiduals(xp.data(), amps, rPlus);
            problem.fixedResiduals(xm.data(), amps, rMinus);
            J.col(c) = (rPlus - rMinus) / (xp[i] - xm[i]);
        }
    }
    const double dof = std::max(1, rows - p);
    const double s2 = residual.squaredNorm() / dof;
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    // Scale to unit diagonal before inverting (columns differ by many orders of magnitude).
    Eigen::VectorXd d = JtJ.diagonal().cwiseMax(1e-300).cwiseSqrt();
    const Eigen::MatrixXd Cs = (d.cwiseInverse().asDiagonal() * JtJ * d.cwiseInverse().asDiagonal())
                                   .completeOrthogonalDecomposition()
                                   .pseudoInverse();
    const Eigen::MatrixXd cov = s2 * (d.cwiseInverse().asDiagonal() * Cs * d.cwiseInverse().asDiagonal());
    res.correlation.resize(p, p);
    for (int a = 0; a < p; ++a)
        for (int b = 0; b < p; ++b)
            res.correlation(a, b) = cov(a, b) / std::sqrt(std::max(cov(a, a) * cov(b, b), 1e-300));
    for (int c = 0; c < p; ++c) {
        Entry &e = entries[static_cast<size_t>(fittedEntries[static_cast<size_t>(c)])];
        e.p.standardError = std::sqrt(std::max(0.0, cov(c, c)));
        res.correlationNames.push_back(e.p.name);
    }
    for (const Entry &e : entries)
        res.all.push_back(e.p);
    res.evaluations = problem.evaluations;
    res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return res;
}

FitStatistics ScrewModelIdentifier::predict(const IdentificationResult &result,
                                            const std::vector<ScrewRecording> &recordings)
{
    ScrewResponseSimulator sim(m_geometry, recordings, m_options.simulator, m_sources, m_terms);
    if (static_cast<int>(result.amplitudes.size()) != sim.columnCount() - 1)
        throw std::invalid_argument("ScrewModelIdentifier::predict: result has " +
                                    std::to_string(result.amplitudes.size()) + " amplitudes, the model " +
                                    std::to_string(sim.columnCount() - 1));
    size_t k = 0;
    for (const auto &s : m_sources) {
        const size_t n = s->nonlinearParameters().size();
        if (n > 0) {
            if (k + n > result.nonlinearComponentValues.size())
                throw std::invalid_argument("ScrewModelIdentifier::predict: component parameters missing");
            s->setNonlinearParameters(result.nonlinearComponentValues.data() + k);
        }
        k += n;
    }
    Eigen::MatrixXd phi;
    const FdmParameters &p = result.parameters;
    sim.simulate(p.k1, p.k2, p.conductivity_W_mK, p.fixedEndPosition_mm, phi);
    const Eigen::VectorXd a = Eigen::Map<const Eigen::VectorXd>(result.amplitudes.data(),
                                                               static_cast<Eigen::Index>(result.amplitudes.size()));
    const Eigen::VectorXd predicted = phi.col(0) + phi.rightCols(a.size()) * a;
    return statistics(sim, predicted);
}

} // namespace driftlab

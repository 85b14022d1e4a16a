#include "LinearLagFitter.h"

#include "DataDrivenPredictor.h"
#include "NonlinearUncertainty.h"
#include "TimeBlockedFolds.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace driftlab {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// NaN -> the last finite value (the first finite value before it), as DataDrivenPredictor::run.
std::vector<double> held(const std::vector<double> &v)
{
    std::vector<double> out(v);
    double last = std::numeric_limits<double>::quiet_NaN();
    for (double x : v)
        if (std::isfinite(x)) {
            last = x;
            break;
        }
    for (double &x : out) {
        if (std::isfinite(x))
            last = x;
        else
            x = last;
    }
    return out;
}

struct Sums {
    double n = 0.0;
    VectorXd s;
    MatrixXd S;
    double sy = 0.0;
    VectorXd sxy;
};

Sums sums(const MatrixXd &X, const VectorXd &y, Index begin, Index end)
{
    Sums r;
    const Index p = X.cols();
    r.n = static_cast<double>(end - begin);
    const auto Xb = X.middleRows(begin, end - begin);
    const auto yb = y.segment(begin, end - begin);
    r.s = Xb.colwise().sum().transpose();
    r.S = MatrixXd::Zero(p, p);
    r.S.selfadjointView<Eigen::Lower>().rankUpdate(Xb.transpose());
    r.S = r.S.selfadjointView<Eigen::Lower>();
    r.sy = yb.sum();
    r.sxy = Xb.transpose() * yb;
    return r;
}

Sums minus(const Sums &a, const Sums &b)
{
    Sums r;
    r.n = a.n - b.n;
    r.s = a.s - b.s;
    r.S = a.S - b.S;
    r.sy = a.sy - b.sy;
    r.sxy = a.sxy - b.sxy;
    return r;
}

struct Solution {
    VectorXd c;          // coefficients on the raw features
    double intercept = 0.0;
    VectorXd mu;
    VectorXd d;          // 1 / feature standard deviation
    MatrixXd A;          // D C D + lambda n I
    MatrixXd DCD;
};

// prior(j) > 0: the feature's fixed scale; otherwise its standard deviation over these samples.
Solution solve(const Sums &t, double lambda, const VectorXd &prior)
{
    Solution r;
    const Index p = t.s.size();
    r.mu = t.s / t.n;
    const double ybar = t.sy / t.n;
    const MatrixXd C = t.S - t.n * r.mu * r.mu.transpose();
    r.d.resize(p);
    for (Index j = 0; j < p; ++j) {
        const double sd = prior(j) > 0 ? prior(j) : std::sqrt(std::max(0.0, C(j, j) / t.n));
        r.d(j) = sd > 1e-12 ? 1.0 / sd : 0.0; // a feature constant over these samples gets no weight
    }
    r.DCD = r.d.asDiagonal() * C * r.d.asDiagonal();
    r.A = r.DCD + lambda * t.n * MatrixXd::Identity(p, p);
    const VectorXd b = r.d.asDiagonal() * (t.sxy - t.n * r.mu * ybar);
    const VectorXd beta = lambda > 0 ? VectorXd(r.A.ldlt().solve(b)) : VectorXd(r.A.completeOrthogonalDecomposition().solve(b));
    r.c = r.d.asDiagonal() * beta;
    r.intercept = ybar - r.mu.dot(r.c);
    return r;
}

struct Structure {
    int components = 0;
    std::vector<double> temperatureLags{0.0};
    std::vector<double> driveLags;
};

} // namespace

LinearLagFit LinearLagFitter::fit(const SignalTable &table, const LinearLagOptions &o,
                                  const std::function<bool(double)> &progress)
{
    if (o.kind != "mlr" && o.kind != "ridge" && o.kind != "dynamic")
        throw std::invalid_argument("model '" + o.kind + "' is not a linear-lag model (mlr, ridge, dynamic)");
    if (o.inputs.empty())
        throw std::invalid_argument(o.kind + ": no input channels");
    if (o.kind != "dynamic" && !o.drive.empty())
        throw std::invalid_argument(o.kind + ": a drive channel is used by the dynamic model only");
    const SignalColumn &target = table.column(o.target);
    std::set<std::string> unique;
    std::vector<const SignalColumn *> inputs;
    for (const std::string &id : o.inputs) {
        if (id == o.target)
            throw std::invalid_argument("input '" + id + "' is the target");
        if (!unique.insert(id).second)
            throw std::invalid_argument("input '" + id + "' given twice");
        inputs.push_back(&table.column(id));
    }
    const SignalColumn *drive = o.drive.empty() ? nullptr : &table.column(o.drive);
    const std::size_t N = table.t.size();
    if (!o.trainRows.empty() && o.trainRows.size() != N)
        throw std::invalid_argument("training rows do not match the grid");

    std::vector<std::size_t> rows;
    for (std::size_t k = 0; k < N; ++k) {
        if ((!o.trainRows.empty() && !o.trainRows[k]) || !std::isfinite(target.v[k]))
            continue;
        bool ok = !drive || std::isfinite(drive->v[k]);
        for (const SignalColumn *c : inputs)
            ok = ok && std::isfinite(c->v[k]);
        if (ok)
            rows.push_back(k);
    }
    const std::size_t minRows = std::max<std::size_t>(20, static_cast<std::size_t>(5 * std::max(o.folds, 2)));
    if (rows.size() < minRows)
        throw std::invalid_argument(o.kind + ": " + std::to_string(rows.size()) +
                                    " training samples have the target and every input; at least " +
                                    std::to_string(minRows) + " are needed");
    const Index n = static_cast<Index>(rows.size());
    const Index nT = static_cast<Index>(inputs.size());

    // Normalised inputs on the whole grid (lag states run from the session start).
    std::vector<double> offset(inputs.size()), scale(inputs.size());
    std::vector<std::vector<double>> z(inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const std::vector<double> h = held(inputs[i]->v);
        double mean = 0.0, var = 0.0;
        for (std::size_t r : rows)
            mean += h[r];
        mean /= static_cast<double>(n);
        for (std::size_t r : rows)
            var += (h[r] - mean) * (h[r] - mean);
        const double sd = std::sqrt(var / static_cast<double>(n));
        if (!(sd > 1e-9 * (1.0 + std::fabs(mean))))
            throw std::invalid_argument("input '" + inputs[i]->id + "' is constant over the training samples");
        offset[i] = mean;
        scale[i] = std::max(sd, o.scaleFloor);
        z[i].resize(N);
        for (std::size_t k = 0; k < N; ++k)
            z[i][k] = (h[k] - mean) / scale[i];
    }
    double driveScale = 1.0;
    std::vector<double> driveHeld;
    if (drive) {
        driveHeld = held(drive->v);
        driveScale = 0.0;
        for (std::size_t r : rows)
            driveScale = std::max(driveScale, std::fabs(driveHeld[r]));
        if (!(driveScale > 0))
            throw std::invalid_argument("drive '" + drive->id + "' is zero over the training samples");
    }
    VectorXd y(n);
    for (Index r = 0; r < n; ++r)
        y(r) = target.v[rows[static_cast<std::size_t>(r)]];

    // Lagged normalised temperatures at the training rows, per time constant.
    std::map<double, MatrixXd> lagged;
    auto laggedZ = [&](double tau) -> const MatrixXd & {
        auto it = lagged.find(tau);
        if (it != lagged.end())
            return it->second;
        MatrixXd m(n, nT);
        for (Index i = 0; i < nT; ++i) {
            const std::vector<double> x = DataDrivenPredictor::lagSeries(table.t, z[static_cast<std::size_t>(i)], tau);
            for (Index r = 0; r < n; ++r)
                m(r, i) = x[rows[static_cast<std::size_t>(r)]];
        }
        return lagged.emplace(tau, std::move(m)).first->second;
    };
    std::map<std::pair<int, double>, VectorXd> laggedDrive;
    auto driveFeature = [&](int power, double tau) -> const VectorXd & {
        const auto key = std::make_pair(power, tau);
        auto it = laggedDrive.find(key);
        if (it != laggedDrive.end())
            return it->second;
        std::vector<double> g(N);
        for (std::size_t k = 0; k < N; ++k) {
            const double v = driveHeld[k] / driveScale;
            g[k] = power == 2 ? v * v : v;
        }
        const std::vector<double> x = DataDrivenPredictor::lagSeries(table.t, g, tau);
        VectorXd out(n);
        for (Index r = 0; r < n; ++r)
            out(r) = x[rows[static_cast<std::size_t>(r)]];
        return laggedDrive.emplace(key, std::move(out)).first->second;
    };

    LinearLagFit fit;
    fit.trainingRows = rows.size();
    // Principal components of the z-scored temperatures over the training rows.
    MatrixXd W; // components x inputs
    std::vector<Structure> structures;
    if (o.kind == "dynamic") {
        const MatrixXd &Z0 = laggedZ(0.0);
        Eigen::JacobiSVD<MatrixXd> svd(Z0, Eigen::ComputeThinV);
        W = svd.matrixV().transpose();
        const VectorXd s2 = svd.singularValues().array().square();
        double cum = 0.0;
        for (Index k = 0; k < s2.size(); ++k) {
            cum += s2(k);
            fit.componentVariance.push_back(cum / s2.sum());
        }
        std::set<int> comps;
        for (int m : o.components)
            if (m >= 1)
                comps.insert(std::min<int>(m, static_cast<int>(nT)));
        if (comps.empty())
            throw std::invalid_argument("dynamic: no principal-component count >= 1 given");
        std::vector<std::vector<double>> driveSets = drive ? o.driveLags : std::vector<std::vector<double>>{{}};
        if (o.temperatureLags.empty() || driveSets.empty())
            throw std::invalid_argument("dynamic: empty lag-bank candidate list");
        for (int m : comps)
            for (const std::vector<double> &tl : o.temperatureLags)
                for (const std::vector<double> &dl : driveSets) {
                    if (tl.empty())
                        throw std::invalid_argument("dynamic: a temperature lag bank is empty");
                    for (double tau : tl)
                        if (!(tau >= 0))
                            throw std::invalid_argument("dynamic: lag time constants must be >= 0");
                    structures.push_back({m, tl, dl});
                }
        // The drive alone (no temperatures): seed 001's virtual sensor as a lag bank.
        if (drive)
            for (const std::vector<double> &dl : o.driveLags)
                if (!dl.empty())
                    structures.push_back({0, {}, dl});
    } else {
        structures.push_back({});
    }
    const std::vector<double> lambdas = o.kind == "mlr" ? std::vector<double>{0.0} : o.lambdas;
    if (lambdas.empty())
        throw std::invalid_argument(o.kind + ": empty penalty grid");
    for (double l : lambdas)
        if (!(l >= 0))
            throw std::invalid_argument(o.kind + ": penalties must be >= 0");

    auto design = [&](const Structure &s) {
        std::vector<VectorXd> cols;
        for (double tau : s.temperatureLags) {
            const MatrixXd &L = laggedZ(tau);
            if (s.components == 0) {
                for (Index i = 0; i < nT; ++i)
                    cols.push_back(L.col(i));
            } else {
                const MatrixXd P = L * W.topRows(s.components).transpose();
                for (Index k = 0; k < P.cols(); ++k)
                    cols.push_back(P.col(k));
            }
        }
        for (int power : {1, 2})
            for (double tau : s.driveLags)
                cols.push_back(driveFeature(power, tau));
        MatrixXd X(n, static_cast<Index>(cols.size()));
        for (std::size_t j = 0; j < cols.size(); ++j)
            X.col(static_cast<Index>(j)) = cols[j];
        return X;
    };

    // Scales of the features in the ridge penalty: 0 = the feature's own standard deviation.
    auto priorScale = [&](const Structure &s, Index columns) {
        VectorXd prior = VectorXd::Zero(columns);
        if (s.components > 0 && !o.standardizeComponents)
            prior.head(static_cast<Index>(s.temperatureLags.size()) * s.components).setOnes();
        return prior;
    };

    std::vector<double> times(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r)
        times[r] = table.t[rows[r]];
    fit.folds = o.folds;
    fit.gap_s = o.gap_s >= 0 ? o.gap_s : TimeBlockedFolds::defaultGap(times, o.folds);
    const std::vector<TimeBlockedFold> folds = TimeBlockedFolds::make(times, o.folds, fit.gap_s);

    CvCandidate best;
    best.cvRmse = std::numeric_limits<double>::infinity();
    Structure bestStructure;
    for (std::size_t si = 0; si < structures.size(); ++si) {
        const Structure &s = structures[si];
        const MatrixXd X = design(s);
        const VectorXd prior = priorScale(s, X.cols());
        const Sums total = sums(X, y, 0, n);
        std::vector<Sums> train;
        for (const TimeBlockedFold &f : folds)
            train.push_back(minus(total, sums(X, y, static_cast<Index>(f.excludeBegin), static_cast<Index>(f.excludeEnd))));
        CvCandidate structureBest;
        structureBest.cvRmse = std::numeric_limits<double>::infinity();
        for (double lambda : lambdas) {
            CvCandidate c;
            c.components = s.components;
            c.temperatureLags_s = s.temperatureLags;
            c.driveLags_s = s.driveLags;
            c.lambda = lambda;
            c.features = static_cast<std::size_t>(X.cols());
            double sse = 0.0, count = 0.0;
            for (std::size_t fi = 0; fi < folds.size(); ++fi) {
                const TimeBlockedFold &f = folds[fi];
                const Solution sol = solve(train[fi], lambda, prior);
                const Index b = static_cast<Index>(f.begin), len = static_cast<Index>(f.end - f.begin);
                const VectorXd e = y.segment(b, len) - (X.middleRows(b, len) * sol.c).array().matrix() -
                                   VectorXd::Constant(len, sol.intercept);
                const double foldSse = e.squaredNorm();
                c.foldRmse.push_back(std::sqrt(foldSse / static_cast<double>(len)));
                sse += foldSse;
                count += static_cast<double>(len);
            }
            c.cvRmse = std::sqrt(sse / count);
            if (!std::isfinite(c.cvRmse))
                continue;
            if (c.cvRmse < structureBest.cvRmse)
                structureBest = c;
        }
        if (std::isfinite(structureBest.cvRmse)) {
            fit.structures.push_back(structureBest);
            if (structureBest.cvRmse < best.cvRmse) {
                best = structureBest;
                bestStructure = s;
            }
        }
        if (progress && !progress(0.9 * static_cast<double>(si + 1) / static_cast<double>(structures.size())))
            throw std::runtime_error("cancelled");
    }
    if (!std::isfinite(best.cvRmse))
        throw std::invalid_argument(o.kind + ": no candidate gave a finite cross-validation error");
    fit.chosen = best;

    // Final fit on every training sample.
    const MatrixXd X = design(bestStructure);
    const Sums total = sums(X, y, 0, n);
    const Solution sol = solve(total, best.lambda, priorScale(bestStructure, X.cols()));
    const VectorXd residual = y - X * sol.c - VectorXd::Constant(n, sol.intercept);
    // Degrees of freedom and the sandwich covariance of the standardised coefficients.
    const Eigen::CompleteOrthogonalDecomposition<MatrixXd> Ainv(sol.A);
    const MatrixXd AinvM = Ainv.pseudoInverse();
    fit.effectiveDof = (AinvM * sol.DCD).trace() + 1.0;
    const double sigma2 = residual.squaredNorm() / std::max(1.0, static_cast<double>(n) - fit.effectiveDof);
    const double r1 = NonlinearUncertainty::lag1(std::vector<double>(residual.data(), residual.data() + n));
    fit.residualLag1 = r1;
    const double rc = std::clamp(r1, 0.0, 0.98);
    fit.seInflation = std::sqrt((1.0 + rc) / (1.0 - rc));
    const MatrixXd covBeta = sigma2 * AinvM * sol.DCD * AinvM;
    const MatrixXd covC = sol.d.asDiagonal() * covBeta * sol.d.asDiagonal() * (fit.seInflation * fit.seInflation);

    // Expand into per-channel terms: rows of M map feature coefficients to term coefficients.
    DataDrivenModel &model = fit.model;
    model.kind = o.kind;
    model.target = {target.id, target.unit, target.kind};
    const std::size_t nTl = bestStructure.temperatureLags.size();
    if (nTl > 0)
        for (const SignalColumn *c : inputs)
            model.inputs.push_back({c->id, c->unit, c->kind});
    if (drive && !bestStructure.driveLags.empty())
        model.inputs.push_back({drive->id, drive->unit, drive->kind});
    model.samplePeriod_s = SignalTable::medianInterval(times);
    const Index p = X.cols();
    std::vector<VectorXd> mapRows;
    for (Index i = 0; i < (nTl > 0 ? nT : 0); ++i) {
        ModelTerm term;
        term.input = static_cast<int>(i);
        term.offset = offset[static_cast<std::size_t>(i)];
        term.scale = scale[static_cast<std::size_t>(i)];
        term.lags_s = bestStructure.temperatureLags;
        for (std::size_t l = 0; l < nTl; ++l) {
            VectorXd row = VectorXd::Zero(p);
            if (bestStructure.components == 0) {
                row(static_cast<Index>(l) * nT + i) = 1.0;
            } else {
                const Index m = bestStructure.components;
                for (Index k = 0; k < m; ++k)
                    row(static_cast<Index>(l) * m + k) = W(k, i);
            }
            mapRows.push_back(row);
        }
        model.terms.push_back(term);
    }
    const Index firstDrive = static_cast<Index>(nTl) * (bestStructure.components == 0 ? nT : bestStructure.components);
    Index column = firstDrive;
    for (int power : {1, 2}) {
        if (bestStructure.driveLags.empty())
            break;
        ModelTerm term;
        term.input = static_cast<int>(model.inputs.size()) - 1;
        term.power = power;
        term.offset = 0.0;
        term.scale = driveScale;
        term.lags_s = bestStructure.driveLags;
        for (std::size_t l = 0; l < bestStructure.driveLags.size(); ++l) {
            VectorXd row = VectorXd::Zero(p);
            row(column++) = 1.0;
            mapRows.push_back(row);
        }
        model.terms.push_back(term);
    }
    MatrixXd M(static_cast<Index>(mapRows.size()), p);
    for (std::size_t r = 0; r < mapRows.size(); ++r)
        M.row(static_cast<Index>(r)) = mapRows[r].transpose();
    const VectorXd gamma = M * sol.c;
    const VectorXd gammaSe = (M * covC * M.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
    Index at = 0;
    for (ModelTerm &term : model.terms)
        for (std::size_t l = 0; l < term.lags_s.size(); ++l, ++at) {
            term.coefficients.push_back(gamma(at));
            term.standardErrors.push_back(gammaSe(at));
        }
    model.intercept = sol.intercept;
    model.interceptStandardError =
        std::sqrt(sigma2 * fit.seInflation * fit.seInflation / static_cast<double>(n) + sol.mu.dot(covC * sol.mu));

    // Training metrics through the predictor (the same code a controller runs).
    std::vector<std::vector<double>> columns;
    for (const ModelChannel &c : model.inputs)
        columns.push_back(table.column(c.id).v);
    const std::vector<double> predicted = DataDrivenPredictor::run(model, table.t, columns);
    std::vector<char> mask(N, 0);
    for (std::size_t r : rows)
        mask[r] = 1;
    fit.training = ErrorMetrics::compute(target.v, predicted, &mask);
    if (progress)
        progress(1.0);
    return fit;
}

} // namespace driftlab

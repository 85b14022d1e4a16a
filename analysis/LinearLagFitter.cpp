#include "LinearLagFitter.h"

#include "BlockGram.h"
#include "LinearLagDesign.h"
#include "DataDrivenPredictor.h"
#include "NonlinearUncertainty.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace driftlab {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

using Sums = DesignSums;

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

} // namespace

std::vector<TimeBlockedFold> LinearLagFitter::folds(const std::vector<std::size_t> &rowCounts,
                                                    const std::vector<double> &times, int timeFolds, double gap_s,
                                                    int maxRunFolds, std::string &rule)
{
    if (rowCounts.size() <= 1) {
        rule = "time-blocked";
        return TimeBlockedFolds::make(times, timeFolds, gap_s);
    }
    rule = "leave-runs-out";
    const std::size_t runs = rowCounts.size();
    const std::size_t groups = std::min<std::size_t>(runs, static_cast<std::size_t>(std::max(2, maxRunFolds)));
    std::vector<TimeBlockedFold> out;
    std::size_t at = 0, run = 0;
    for (std::size_t g = 0; g < groups; ++g) {
        const std::size_t last = runs * (g + 1) / groups; // runs [run, last)
        TimeBlockedFold f;
        f.begin = f.excludeBegin = at;
        for (; run < last; ++run)
            at += rowCounts[run];
        f.end = f.excludeEnd = at;
        out.push_back(f);
    }
    return out;
}

double LinearLagFitter::nestedCv(const std::vector<std::vector<double>> &candidateFoldSse,
                                 const std::vector<double> &foldLength, std::vector<double> &foldRmse)
{
    foldRmse.clear();
    double sse = 0.0, count = 0.0;
    for (std::size_t fi = 0; fi < foldLength.size(); ++fi) {
        std::size_t pick = 0;
        double lowest = std::numeric_limits<double>::infinity();
        for (std::size_t ci = 0; ci < candidateFoldSse.size(); ++ci) {
            double other = 0.0;
            for (std::size_t fj = 0; fj < foldLength.size(); ++fj)
                if (fj != fi)
                    other += candidateFoldSse[ci][fj];
            if (other < lowest) {
                lowest = other;
                pick = ci;
            }
        }
        const double e = candidateFoldSse.empty() ? std::numeric_limits<double>::quiet_NaN() : candidateFoldSse[pick][fi];
        foldRmse.push_back(std::sqrt(e / foldLength[fi]));
        sse += e;
        count += foldLength[fi];
    }
    return std::sqrt(sse / count);
}

LinearLagFit LinearLagFitter::fit(const SignalTable &table, const LinearLagOptions &o,
                                  const std::function<bool(double)> &progress)
{
    if (!o.trainRows.empty() && o.trainRows.size() != table.t.size())
        throw std::invalid_argument("training rows do not match the grid");
    return fit(std::vector<LinearLagRun>{LinearLagRun{&table, o.trainRows}}, o, progress);
}

LinearLagFit LinearLagFitter::fit(const std::vector<LinearLagRun> &runs, const LinearLagOptions &o,
                                  const std::function<bool(double)> &progress)
{
    if (o.kind != "mlr" && o.kind != "ridge" && o.kind != "lagridge" && o.kind != "dynamic")
        throw std::invalid_argument("model '" + o.kind + "' is not a linear-lag model (mlr, ridge, lagridge, dynamic)");
    if (runs.empty())
        throw std::invalid_argument(o.kind + ": no training runs");
    if (o.inputs.empty())
        throw std::invalid_argument(o.kind + ": no input channels");
    if (o.kind != "dynamic" && !o.drive.empty())
        throw std::invalid_argument(o.kind + ": a drive channel is used by the dynamic model only");
    if (o.references.empty())
        throw std::invalid_argument(o.kind + ": no temperature reference candidate");
    std::set<std::string> unique;
    for (const std::string &id : o.inputs) {
        if (id == o.target)
            throw std::invalid_argument("input '" + id + "' is the target");
        if (!unique.insert(id).second)
            throw std::invalid_argument("input '" + id + "' given twice");
    }

    LinearLagDesign d(runs, o);
    const std::size_t R = runs.size();
    const Index n = d.n, nT = d.nT;
    const bool hasDrive = d.hasDrive;
    const std::vector<LinearLagDesign::Row> &rows = d.rows;
    const std::vector<std::size_t> &rowCounts = d.rowCounts;
    const VectorXd &y = d.y;
    std::vector<LinearLagDesign::Prepared> &prepared = d.prepared;

    LinearLagFit fit;
    fit.trainingRows = rows.size();
    fit.runs = R;
    std::vector<LinearLagStructure> structures;
    auto checkBank = [&](const std::vector<double> &bank) {
        if (bank.empty())
            throw std::invalid_argument(o.kind + ": a temperature lag bank is empty");
        for (double tau : bank)
            if (!(tau >= 0))
                throw std::invalid_argument(o.kind + ": lag time constants must be >= 0");
    };
    for (std::size_t ci = 0; ci < o.references.size(); ++ci) {
        if (o.kind == "dynamic") {
            // Principal components of the z-scored temperatures over the training rows.
            const MatrixXd &Z0 = d.laggedZ(ci, 0.0);
            Eigen::JacobiSVD<MatrixXd> svd(Z0, Eigen::ComputeThinV);
            prepared[ci].W = svd.matrixV().transpose();
            const VectorXd s2 = svd.singularValues().array().square();
            double cum = 0.0;
            for (Index k = 0; k < s2.size(); ++k) {
                cum += s2(k);
                prepared[ci].componentVariance.push_back(cum / s2.sum());
            }
            std::set<int> comps;
            for (int m : o.components)
                if (m >= 1)
                    comps.insert(std::min<int>(m, static_cast<int>(nT)));
            if (comps.empty())
                throw std::invalid_argument("dynamic: no principal-component count >= 1 given");
            std::vector<std::vector<double>> driveSets = hasDrive ? o.driveLags : std::vector<std::vector<double>>{{}};
            if (o.temperatureLags.empty() || driveSets.empty())
                throw std::invalid_argument("dynamic: empty lag-bank candidate list");
            for (int m : comps)
                for (const std::vector<double> &tl : o.temperatureLags)
                    for (const std::vector<double> &dl : driveSets) {
                        checkBank(tl);
                        structures.push_back({m, tl, dl, ci});
                    }
            // The drive alone (no temperatures): seed 001's virtual sensor as a lag bank (once).
            if (hasDrive && ci == 0)
                for (const std::vector<double> &dl : o.driveLags)
                    if (!dl.empty())
                        structures.push_back({0, {}, dl, ci});
        } else if (o.kind == "lagridge") {
            if (o.ridgeLags.empty())
                throw std::invalid_argument("lagridge: empty lag-bank candidate list");
            for (const std::vector<double> &bank : o.ridgeLags) {
                checkBank(bank);
                structures.push_back({0, bank, {}, ci});
            }
        } else {
            structures.push_back({0, {0.0}, {}, ci});
        }
    }
    const std::vector<double> lambdas = o.kind == "mlr" ? std::vector<double>{0.0} : o.lambdas;
    if (lambdas.empty())
        throw std::invalid_argument(o.kind + ": empty penalty grid");
    for (double l : lambdas)
        if (!(l >= 0))
            throw std::invalid_argument(o.kind + ": penalties must be >= 0");

    d.buildDriveMatrix();
    BlockGram gram(y);

    const std::vector<double> times = d.times();
    fit.gap_s = R > 1 ? 0.0 : (o.gap_s >= 0 ? o.gap_s : TimeBlockedFolds::defaultGap(times, o.folds));
    const std::vector<TimeBlockedFold> folds =
        LinearLagFitter::folds(rowCounts, times, o.folds, fit.gap_s, o.maxRunFolds, fit.foldRule);
    fit.folds = static_cast<int>(folds.size());
    bool partition = !folds.empty() && folds.front().begin == 0 && folds.back().end == rows.size();
    for (std::size_t fi = 0; fi < folds.size(); ++fi)
        partition = partition && folds[fi].excludeBegin == folds[fi].begin && folds[fi].excludeEnd == folds[fi].end &&
                    (fi == 0 || folds[fi].begin == folds[fi - 1].end);

    // The training mean on the same folds.
    {
        std::vector<double> prefix(rows.size() + 1, 0.0);
        for (std::size_t r = 0; r < rows.size(); ++r)
            prefix[r + 1] = prefix[r] + y(static_cast<Index>(r));
        double sse = 0.0, count = 0.0;
        for (const TimeBlockedFold &f : folds) {
            const double trainN = static_cast<double>(rows.size() - (f.excludeEnd - f.excludeBegin));
            const double mean = trainN > 0 ? (prefix.back() - (prefix[f.excludeEnd] - prefix[f.excludeBegin])) / trainN : 0.0;
            double foldSse = 0.0;
            for (std::size_t r = f.begin; r < f.end; ++r)
                foldSse += (y(static_cast<Index>(r)) - mean) * (y(static_cast<Index>(r)) - mean);
            fit.mean.foldRmse.push_back(std::sqrt(foldSse / static_cast<double>(f.end - f.begin)));
            sse += foldSse;
            count += static_cast<double>(f.end - f.begin);
        }
        fit.mean.cvRmse = std::sqrt(sse / count);
        fit.mean.temperatureLags_s.clear();
        fit.mean.features = 0;
        fit.trainingMean = prefix.back() / static_cast<double>(rows.size());
    }

    CvCandidate best;
    best.cvRmse = std::numeric_limits<double>::infinity();
    LinearLagStructure bestStructure;
    // Every candidate's squared error per fold, for the nested estimate below.
    std::vector<std::vector<double>> candidateFoldSse;
    for (std::size_t si = 0; si < structures.size(); ++si) {
        const LinearLagStructure &s = structures[si];
        const std::vector<BlockGram::Block> blocks = d.designBlocks(s);
        Index columns = 0;
        for (const BlockGram::Block &b : blocks)
            columns += b.projection.size() == 0 ? b.matrix->cols() : b.projection.cols();
        const VectorXd prior = d.priorScale(s, columns);
        // Leave-runs-out folds partition the rows: each fold's sums give both its training sums
        // (total minus it) and its squared error. Time-blocked folds leave a gap: the training
        // sums are the total minus the excluded range, the error from the fold's own sums.
        std::vector<Sums> train, held;
        for (const TimeBlockedFold &f : folds)
            held.push_back(gram.sums(blocks, static_cast<Index>(f.begin), static_cast<Index>(f.end)));
        if (partition) {
            Sums total = held.front();
            for (std::size_t fi = 1; fi < held.size(); ++fi)
                total = total + held[fi];
            for (const Sums &h : held)
                train.push_back(total - h);
        } else {
            const Sums total = gram.sums(blocks, 0, n);
            for (const TimeBlockedFold &f : folds)
                train.push_back(total - gram.sums(blocks, static_cast<Index>(f.excludeBegin), static_cast<Index>(f.excludeEnd)));
        }
        CvCandidate structureBest;
        structureBest.cvRmse = std::numeric_limits<double>::infinity();
        for (double lambda : lambdas) {
            CvCandidate c;
            c.components = s.components;
            c.temperatureLags_s = s.temperatureLags;
            c.driveLags_s = s.driveLags;
            c.reference = o.references[s.reference];
            c.lambda = lambda;
            c.features = static_cast<std::size_t>(columns);
            double sse = 0.0, count = 0.0;
            for (std::size_t fi = 0; fi < folds.size(); ++fi) {
                const TimeBlockedFold &f = folds[fi];
                const Solution sol = solve(train[fi], lambda, prior);
                const double len = static_cast<double>(f.end - f.begin);
                const double foldSse = held[fi].squaredError(sol.c, sol.intercept);
                c.foldRmse.push_back(std::sqrt(foldSse / len));
                sse += foldSse;
                count += static_cast<double>(len);
            }
            c.cvRmse = std::sqrt(sse / count);
            if (!std::isfinite(c.cvRmse))
                continue;
            std::vector<double> foldSse;
            for (std::size_t fi = 0; fi < folds.size(); ++fi)
                foldSse.push_back(c.foldRmse[fi] * c.foldRmse[fi] * static_cast<double>(folds[fi].end - folds[fi].begin));
            candidateFoldSse.push_back(std::move(foldSse));
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
    // The family's own search scored honestly: each fold is predicted by the candidate that the
    // other folds choose (lowest squared error over them), so a larger search is not rewarded
    // for the luck of its best candidate on these folds.
    {
        std::vector<double> lengths;
        for (const TimeBlockedFold &f : folds)
            lengths.push_back(static_cast<double>(f.end - f.begin));
        fit.nestedCvRmse = nestedCv(candidateFoldSse, lengths, fit.nestedFoldRmse);
        fit.model.predictionSigma = fit.nestedCvRmse;
    }
    const LinearLagDesign::Prepared &chosenInputs = prepared[bestStructure.reference];
    fit.componentVariance = chosenInputs.componentVariance;
    const MatrixXd &W = chosenInputs.W;

    // Final fit on every training sample.
    const MatrixXd X = d.design(bestStructure);
    const Sums total = Sums::of(X, y, 0, n);
    const Solution sol = solve(total, best.lambda, d.priorScale(bestStructure, X.cols()));
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
    const SignalColumn &target = *d.targets.front();
    model.target = {target.id, target.unit, target.kind};
    const std::size_t nTl = bestStructure.temperatureLags.size();
    const bool rise = o.references[bestStructure.reference].kind == "start";
    if (nTl > 0) {
        model.reference = o.references[bestStructure.reference];
        for (const SignalColumn *c : d.inputs.front())
            model.inputs.push_back({c->id, c->unit, c->kind});
    }
    if (hasDrive && !bestStructure.driveLags.empty())
        model.inputs.push_back({d.drives.front()->id, d.drives.front()->unit, d.drives.front()->kind});
    model.samplePeriod_s = SignalTable::medianInterval(std::vector<double>(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(rowCounts.front())));
    const Index p = X.cols();
    std::vector<VectorXd> mapRows;
    for (Index i = 0; i < (nTl > 0 ? nT : 0); ++i) {
        ModelTerm term;
        term.input = static_cast<int>(i);
        term.rise = rise;
        term.offset = chosenInputs.offset[static_cast<std::size_t>(i)];
        term.scale = chosenInputs.scale[static_cast<std::size_t>(i)];
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
        term.scale = d.driveScale;
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

    // Training metrics through the predictor (the same code a controller runs), run by run.
    std::vector<double> measured, predicted;
    measured.reserve(rows.size());
    predicted.reserve(rows.size());
    std::size_t r0 = 0;
    for (std::size_t ri = 0; ri < R; ++ri) {
        const SignalTable &table = *runs[ri].table;
        std::vector<std::vector<double>> columns;
        for (const ModelChannel &c : model.inputs)
            columns.push_back(table.column(c.id).v);
        const std::vector<double> pr = DataDrivenPredictor::run(model, table.t, columns);
        for (std::size_t r = r0; r < r0 + rowCounts[ri]; ++r) {
            measured.push_back(d.targets[ri]->v[rows[r].k]);
            predicted.push_back(pr[rows[r].k]);
        }
        r0 += rowCounts[ri];
    }
    fit.training = ErrorMetrics::compute(measured, predicted);
    if (progress)
        progress(1.0);
    return fit;
}

} // namespace driftlab

// Data-driven models and sensitive-point selection: speed against plain references run in
// the same process, and (with the FL_THERMAL CSV) the held-out accuracy of the seed-003
// pipeline, ridge and the dynamic model.
//
//   bench_datadriven [FL_THERMAL.csv]
//
// 1. Selection over 64 channels x 100,000 samples (6 true thermal groups): DriftLab's
//    SensitivePointSelector (Gram-matrix embedding) against cv::kmeans and the silhouette on
//    the full z-scored series (the plain reference). Target <= 1 s.
// 2. With the CSV: every model fitted on the first 24 h, validated on the rest (hyperparameters
//    by time-blocked CV inside the training part), wall time per fit (target <= 1 s, CV searches
//    <= 10 s), and a plain reference for the dynamic fit (the same search with the design matrix
//    rebuilt and solved by QR for every fold and penalty).

#include "DataDrivenPredictor.h"
#include "ErrorMetrics.h"
#include "ExponentialWarmupFitter.h"
#include "LinearLagFitter.h"
#include "SensitivePointSelector.h"
#include "SignalTable.h"

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace driftlab;

namespace {

double seconds(std::chrono::steady_clock::time_point a)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

// Runs `work`, stores its wall time in *elapsed_s and returns what it returned.
template <class Work>
auto timed(double *elapsed_s, Work work)
{
    const auto a = std::chrono::steady_clock::now();
    auto result = work();
    *elapsed_s = seconds(a);
    return result;
}

// 64 channels in 6 groups: each group a distinct smooth thermal history, channels = group
// history + per-channel gain, offset and noise; the target mixes the groups.
SignalTable syntheticTable(std::size_t samples, int channels)
{
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    SignalTable t;
    t.t.resize(samples);
    for (std::size_t k = 0; k < samples; ++k)
        t.t[k] = static_cast<double>(k);
    const int groups = 6;
    std::vector<std::vector<double>> g(groups, std::vector<double>(samples));
    for (int j = 0; j < groups; ++j)
        for (std::size_t k = 0; k < samples; ++k) {
            const double x = static_cast<double>(k) / static_cast<double>(samples);
            g[static_cast<std::size_t>(j)][k] = std::sin(2 * M_PI * (j + 1) * x + j) + 0.5 * std::cos(2 * M_PI * (2 * j + 3) * x);
        }
    for (int c = 0; c < channels; ++c) {
        SignalColumn col;
        col.id = "T" + std::to_string(c + 1);
        col.kind = "temperature";
        col.unit = "degC";
        col.v.resize(samples);
        const auto &h = g[static_cast<std::size_t>(c % groups)];
        const double gain = 1.0 + 0.3 * (c % 5);
        for (std::size_t k = 0; k < samples; ++k)
            col.v[k] = 20.0 + gain * h[k] + 0.05 * noise(rng);
        t.columns.push_back(std::move(col));
    }
    SignalColumn y;
    y.id = "S1";
    y.kind = "displacement";
    y.unit = "um";
    y.v.resize(samples);
    for (std::size_t k = 0; k < samples; ++k) {
        double s = 0.0;
        for (int j = 0; j < groups; ++j)
            s += (j + 1) * g[static_cast<std::size_t>(j)][k];
        y.v[k] = s + 0.1 * noise(rng);
    }
    t.columns.push_back(std::move(y));
    return t;
}

// Plain reference: z-score, cv::kmeans on the full series, silhouette from full distances.
double referenceSelection(const SignalTable &t, int kMin, int kMax, int attempts, std::vector<int> &bestLabels)
{
    const int n = static_cast<int>(t.columns.size()) - 1;
    const int m = static_cast<int>(t.t.size());
    cv::Mat data(n, m, CV_32F);
    for (int i = 0; i < n; ++i) {
        const std::vector<double> &v = t.columns[static_cast<std::size_t>(i)].v;
        double mean = 0, var = 0;
        for (double x : v)
            mean += x;
        mean /= m;
        for (double x : v)
            var += (x - mean) * (x - mean);
        const double sd = std::sqrt(var / m);
        for (int k = 0; k < m; ++k)
            data.at<float>(i, k) = static_cast<float>((v[static_cast<std::size_t>(k)] - mean) / sd);
    }
    std::vector<double> d(static_cast<std::size_t>(n * n));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            d[static_cast<std::size_t>(i * n + j)] = cv::norm(data.row(i), data.row(j));
    double best = -2;
    for (int k = kMin; k <= kMax; ++k) {
        cv::theRNG().state = 1;
        cv::Mat labels, centers;
        cv::kmeans(data, k, labels, cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 300, 1e-8), attempts,
                   cv::KMEANS_PP_CENTERS, centers);
        std::vector<int> l(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i)
            l[static_cast<std::size_t>(i)] = labels.at<int>(i);
        const double s = SensitivePointSelector::silhouette(d, l);
        if (s > best) {
            best = s;
            bestLabels = l;
        }
    }
    return best;
}

void benchSelection()
{
    const SignalTable t = syntheticTable(100000, 64);
    SelectionOptions o;
    o.target = "S1";
    o.kMin = 2;
    o.kMax = 8;
    o.attempts = 5;
    auto a = std::chrono::steady_clock::now();
    SelectionResult r;
    double fast = 1e9;
    for (int rep = 0; rep < 3; ++rep) {
        a = std::chrono::steady_clock::now();
        r = SensitivePointSelector::select(t, o);
        fast = std::min(fast, seconds(a));
    }
    std::vector<int> refLabels;
    a = std::chrono::steady_clock::now();
    const double refSil = referenceSelection(t, o.kMin, o.kMax, o.attempts, refLabels);
    const double slow = seconds(a);
    double sil = 0;
    for (const ClusteringForK &e : r.perK)
        if (e.k == r.chosenK)
            sil = e.silhouette;
    std::printf("selection 64 ch x 100000 samples, K 2..8, 5 attempts: DriftLab %.3f s (K* = %d, silhouette %.4f), "
                "reference (full-series k-means + silhouette) %.3f s (silhouette %.4f), ratio %.1fx\n",
                fast, r.chosenK, sil, slow, refSil, slow / fast);
}

bool loadCsv(const std::string &path, SignalTable &table)
{
    std::ifstream in(path);
    if (!in)
        return false;
    std::string line;
    std::getline(in, line);
    if (!line.empty() && line.back() == '\r')
        line.pop_back();
    std::vector<std::string> header;
    {
        std::stringstream ss(line);
        std::string h;
        while (std::getline(ss, h, ','))
            header.push_back(h);
    }
    table.columns.clear();
    for (std::size_t i = 1; i < header.size(); ++i) {
        SignalColumn c;
        const std::string &h = header[i];
        if (h.size() > 2 && h.substr(h.size() - 2) == "_C") {
            c.id = h.substr(0, h.size() - 2);
            c.kind = "temperature";
            c.unit = "degC";
        } else if (h.size() > 3 && h.substr(h.size() - 3) == "_um") {
            c.id = h.substr(0, h.size() - 3);
            c.kind = "displacement";
            c.unit = "um";
        } else {
            c.id = h;
            c.kind = "other";
            c.unit = "rpm";
            c.role = "spindle";
        }
        table.columns.push_back(c);
    }
    while (std::getline(in, line)) {
        if (line.empty())
            continue;
        std::stringstream ss(line);
        std::string cell;
        std::getline(ss, cell, ',');
        table.t.push_back(std::stod(cell));
        for (SignalColumn &c : table.columns) {
            std::getline(ss, cell, ',');
            c.v.push_back(std::stod(cell));
        }
    }
    return true;
}

std::vector<std::vector<double>> inputColumns(const SignalTable &t, const DataDrivenModel &m)
{
    std::vector<std::vector<double>> cols;
    for (const ModelChannel &c : m.inputs)
        cols.push_back(t.column(c.id).v);
    return cols;
}

// Plain reference of the ridge penalty search: for every fold and penalty, the training
// design matrix is built, standardised and solved by QR of [X; sqrt(lambda n) I].
double naiveRidgeSearch(const SignalTable &t, const std::vector<std::string> &inputs, const std::string &target,
                        const std::vector<char> &train, const std::vector<double> &lambdas, int folds, double gap_s,
                        double *bestLambda)
{
    std::vector<std::size_t> rows;
    for (std::size_t k = 0; k < t.t.size(); ++k)
        if (train[k])
            rows.push_back(k);
    const Eigen::Index n = static_cast<Eigen::Index>(rows.size()), p = static_cast<Eigen::Index>(inputs.size());
    Eigen::MatrixXd X(n, p);
    Eigen::VectorXd y(n);
    for (Eigen::Index r = 0; r < n; ++r) {
        for (Eigen::Index j = 0; j < p; ++j)
            X(r, j) = t.column(inputs[static_cast<std::size_t>(j)]).v[rows[static_cast<std::size_t>(r)]];
        y(r) = t.column(target).v[rows[static_cast<std::size_t>(r)]];
    }
    double best = 1e300;
    for (double lambda : lambdas) {
        double sse = 0;
        for (int f = 0; f < folds; ++f) {
            const Eigen::Index b = n * f / folds, e = n * (f + 1) / folds;
            std::vector<Eigen::Index> idx;
            for (Eigen::Index r = 0; r < n; ++r)
                if (t.t[rows[static_cast<std::size_t>(r)]] < t.t[rows[static_cast<std::size_t>(b)]] - gap_s ||
                    t.t[rows[static_cast<std::size_t>(r)]] > t.t[rows[static_cast<std::size_t>(e - 1)]] + gap_s)
                    idx.push_back(r);
            const Eigen::Index m = static_cast<Eigen::Index>(idx.size());
            Eigen::MatrixXd A(m + p, p);
            Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + p);
            Eigen::RowVectorXd mu = Eigen::RowVectorXd::Zero(p);
            double ybar = 0;
            for (Eigen::Index i : idx) {
                mu += X.row(i);
                ybar += y(i);
            }
            mu /= static_cast<double>(m);
            ybar /= static_cast<double>(m);
            Eigen::RowVectorXd sd = Eigen::RowVectorXd::Zero(p);
            for (Eigen::Index i : idx)
                sd += (X.row(i) - mu).array().square().matrix();
            sd = (sd / static_cast<double>(m)).array().sqrt().max(1e-12).matrix();
            for (Eigen::Index i = 0; i < m; ++i) {
                A.row(i) = (X.row(idx[static_cast<std::size_t>(i)]) - mu).cwiseQuotient(sd);
                rhs(i) = y(idx[static_cast<std::size_t>(i)]) - ybar;
            }
            A.bottomRows(p) = std::sqrt(lambda * static_cast<double>(m)) * Eigen::MatrixXd::Identity(p, p);
            const Eigen::VectorXd beta = A.householderQr().solve(rhs);
            for (Eigen::Index r = b; r < e; ++r) {
                const double pred = ybar + ((X.row(r) - mu).cwiseQuotient(sd)).dot(beta);
                sse += (y(r) - pred) * (y(r) - pred);
            }
        }
        const double cv = std::sqrt(sse / static_cast<double>(n));
        if (cv < best) {
            best = cv;
            *bestLambda = lambda;
        }
    }
    return best;
}

double heldOut(const SignalTable &t, const DataDrivenModel &m, const std::vector<char> &test)
{
    const std::vector<double> p = DataDrivenPredictor::run(m, t.t, inputColumns(t, m));
    return ErrorMetrics::compute(t.column(m.target.id).v, p, &test).rmse;
}

void benchFlThermal(const std::string &path)
{
    SignalTable t;
    if (!loadCsv(path, t)) {
        std::printf("FL_THERMAL: %s not readable, skipped\n", path.c_str());
        return;
    }
    const std::vector<char> train = t.rowsIn(0, 24 * 3600.0), test = t.rowsIn(24 * 3600.0, 1e12);
    std::vector<std::string> temps;
    for (const SignalColumn &c : t.columns)
        if (c.kind == "temperature")
            temps.push_back(c.id);
    std::printf("FL_THERMAL %zu samples; train 0-24 h, validate 24-46.3 h; held-out RMSE (um)\n", t.t.size());
    std::printf("| channel | mean predictor | (a) K-means+grey -> MLR | points | (b) ridge, 16 ch | (c) dynamic | exp (seed 001) |\n");
    for (const char *target : {"ch1", "ch2", "ch3", "ch4", "ch5"}) {
        const std::vector<double> &y = t.column(target).v;
        double mean = 0;
        int nTrain = 0;
        for (std::size_t k = 0; k < y.size(); ++k)
            if (train[k]) {
                mean += y[k];
                ++nTrain;
            }
        mean /= nTrain;
        const ErrorMetrics meanPred = ErrorMetrics::compute(y, std::vector<double>(y.size(), mean), &test);
        SelectionOptions so;
        so.target = target;
        so.rows = train;
        double tSel = 0, tA = 0, tB = 0, tC = 0, tE = 0;
        const SelectionResult sel = timed(&tSel, [&] { return SensitivePointSelector::select(t, so); });
        LinearLagOptions mlr;
        mlr.kind = "mlr";
        mlr.target = target;
        mlr.inputs = sel.chosen;
        mlr.trainRows = train;
        const LinearLagFit fa = timed(&tA, [&] { return LinearLagFitter::fit(t, mlr); });
        LinearLagOptions ridge = mlr;
        ridge.kind = "ridge";
        ridge.inputs = temps;
        const LinearLagFit fb = timed(&tB, [&] { return LinearLagFitter::fit(t, ridge); });
        LinearLagOptions dyn = ridge;
        dyn.kind = "dynamic";
        dyn.drive = "spindle_rpm";
        const LinearLagFit fc = timed(&tC, [&] { return LinearLagFitter::fit(t, dyn); });
        ExponentialOptions eo;
        eo.target = target;
        eo.drive = "spindle_rpm";
        eo.trainRows = train;
        const ExponentialFit fe = timed(&tE, [&] { return ExponentialWarmupFitter::fit(t, eo); });
        std::string pts;
        for (const std::string &p : sel.chosen)
            pts += (pts.empty() ? "" : ",") + p;
        std::printf("| %s | %.2f | %.2f | %s (K=%d) | %.2f | %.2f | %.2f |\n", target, meanPred.rmse,
                    heldOut(t, fa.model, test), pts.c_str(), sel.chosenK, heldOut(t, fb.model, test),
                    heldOut(t, fc.model, test), heldOut(t, fe.model, test));
        std::printf("    CV RMSE: mlr %.2f ridge %.2f (lambda %g) dynamic %.2f (m=%d, %zu T lags, %zu drive lags, lambda %g) exp %.2f; "
                    "time: select %.3f s, mlr %.3f s, ridge %.3f s, dynamic %.3f s, exp %.3f s (with its 4-fold CV)\n",
                    fa.chosen.cvRmse, fb.chosen.cvRmse, fb.chosen.lambda, fc.chosen.cvRmse, fc.chosen.components,
                    fc.chosen.temperatureLags_s.size(), fc.chosen.driveLags_s.size(), fc.chosen.lambda, fe.cvRmse, tSel, tA,
                    tB, tC, tE);
    }

    // Speed against plain references on ch3 (46-h session, training 24 h).
    LinearLagOptions ridge;
    ridge.kind = "ridge";
    ridge.target = "ch3";
    ridge.inputs = temps;
    ridge.trainRows = train;
    auto a = std::chrono::steady_clock::now();
    const LinearLagFit fr = LinearLagFitter::fit(t, ridge);
    const double tRidge = seconds(a);
    double refLambda = 0;
    a = std::chrono::steady_clock::now();
    const double refCv = naiveRidgeSearch(t, temps, "ch3", train, ridge.lambdas, 4, fr.gap_s, &refLambda);
    const double tRidgeRef = seconds(a);
    std::printf("ridge penalty search (16 ch, 9 penalties, 4 folds): DriftLab %.3f s (lambda %g, CV %.4f), reference "
                "(per-fold design matrix + QR) %.3f s (lambda %g, CV %.4f), ratio %.1fx\n",
                tRidge, fr.chosen.lambda, fr.chosen.cvRmse, tRidgeRef, refLambda, refCv, tRidgeRef / tRidge);
    LinearLagOptions dyn = ridge;
    dyn.kind = "dynamic";
    dyn.drive = "spindle_rpm";
    a = std::chrono::steady_clock::now();
    const LinearLagFit fd = LinearLagFitter::fit(t, dyn);
    const double tDyn = seconds(a);
    // Reference: the same grid as independent fits, one per (structure, penalty).
    a = std::chrono::steady_clock::now();
    double refBest = 1e300;
    std::size_t fits = 0;
    for (int m : dyn.components)
        for (const auto &tl : dyn.temperatureLags)
            for (const auto &dl : dyn.driveLags)
                for (double lambda : dyn.lambdas) {
                    LinearLagOptions one = dyn;
                    one.components = {m};
                    one.temperatureLags = {tl};
                    one.driveLags = {dl};
                    one.lambdas = {lambda};
                    refBest = std::min(refBest, LinearLagFitter::fit(t, one).chosen.cvRmse);
                    ++fits;
                }
    const double tDynRef = seconds(a);
    std::printf("dynamic structure + penalty search (%zu candidates incl. drive-only, 4 folds): DriftLab %.3f s (CV %.4f), reference "
                "(%zu independent fits of the temperature structures) %.3f s (best CV %.4f), ratio %.1fx\n",
                fd.structures.size() * dyn.lambdas.size(), tDyn, fd.chosen.cvRmse, fits, tDynRef, refBest, tDynRef / tDyn);
    LinearLagOptions fixed = dyn;
    fixed.components = {fd.chosen.components > 0 ? fd.chosen.components : 2};
    fixed.temperatureLags = {fd.chosen.temperatureLags_s.empty() ? std::vector<double>{0.0} : fd.chosen.temperatureLags_s};
    fixed.driveLags = {fd.chosen.driveLags_s};
    fixed.lambdas = {fd.chosen.lambda};
    a = std::chrono::steady_clock::now();
    LinearLagFitter::fit(t, fixed);
    const double tFixed = seconds(a);
    ExponentialOptions eo;
    eo.target = "ch3";
    eo.drive = "spindle_rpm";
    eo.trainRows = train;
    eo.crossValidate = false;
    a = std::chrono::steady_clock::now();
    ExponentialWarmupFitter::fit(t, eo);
    const double tExp = seconds(a);
    std::printf("single fits (no search): dynamic with the chosen structure %.3f s, exp (seed 001) %.3f s\n", tFixed, tExp);

    // Sensitivity of the held-out RMSE of (c) to the design choices (hyperparameters by CV each time).
    std::printf("dynamic held-out RMSE (um) by input scale floor and CV folds:\n| floor | folds | ch1 | ch2 | ch3 | ch4 | ch5 |\n");
    for (double floor : {0.0, 0.5, 1.0})
        for (int folds : {3, 4, 5, 6}) {
            if (floor != 0.5 && folds != 4)
                continue;
            std::printf("| %.1f K | %d |", floor, folds);
            for (const char *target : {"ch1", "ch2", "ch3", "ch4", "ch5"}) {
                LinearLagOptions o = dyn;
                o.target = target;
                o.scaleFloor = floor;
                o.folds = folds;
                std::printf(" %.2f |", heldOut(t, LinearLagFitter::fit(t, o).model, test));
            }
            std::printf("\n");
        }
}

} // namespace

int main(int argc, char **argv)
{
    benchSelection();
    if (argc > 1)
        benchFlThermal(argv[1]);
    return 0;
}

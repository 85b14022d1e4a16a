#include "SensitivePointSelector.h"

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

namespace driftlab {

namespace {

const char *kRule =
    "rows: grid samples where the target is present; channels present on fewer than %d %% of them are "
    "excluded (gaps); channels with a standard deviation below 1e-9 (1 + |mean|) are excluded (constant); "
    "rows used: those where the target and every remaining channel are present; normalisation: z-score of "
    "the temperature rise and of the displacement over the rows used; grey grade: Deng, rho = %.2f, "
    "dmin/dmax over the members of each cluster";

std::string ruleText(double fraction, double rho)
{
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, kRule, static_cast<int>(std::lround(fraction * 100)), rho);
    return buffer;
}

// Z-scores v over the rows (population standard deviation). Returns false if constant.
bool zscore(const std::vector<double> &v, const std::vector<std::size_t> &rows, std::vector<double> &out)
{
    double mean = 0.0;
    for (std::size_t r : rows)
        mean += v[r];
    mean /= static_cast<double>(rows.size());
    double var = 0.0;
    for (std::size_t r : rows)
        var += (v[r] - mean) * (v[r] - mean);
    const double sd = std::sqrt(var / static_cast<double>(rows.size()));
    if (!(sd > 1e-9 * (1.0 + std::fabs(mean))))
        return false;
    out.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
        out[i] = (v[rows[i]] - mean) / sd;
    return true;
}

} // namespace

double SensitivePointSelector::silhouette(const std::vector<double> &d, const std::vector<int> &labels)
{
    const std::size_t n = labels.size();
    if (d.size() != n * n)
        throw std::invalid_argument("silhouette: distance matrix does not match the labels");
    const int k = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
    double total = 0.0;
    std::vector<double> sum(static_cast<std::size_t>(k));
    std::vector<int> count(static_cast<std::size_t>(k));
    for (std::size_t i = 0; i < n; ++i) {
        std::fill(sum.begin(), sum.end(), 0.0);
        std::fill(count.begin(), count.end(), 0);
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i)
                continue;
            sum[static_cast<std::size_t>(labels[j])] += d[i * n + j];
            ++count[static_cast<std::size_t>(labels[j])];
        }
        const std::size_t own = static_cast<std::size_t>(labels[i]);
        if (count[own] == 0)
            continue; // singleton: s(i) = 0
        const double a = sum[own] / count[own];
        double b = std::numeric_limits<double>::infinity();
        for (std::size_t c = 0; c < sum.size(); ++c)
            if (c != own && count[c] > 0)
                b = std::min(b, sum[c] / count[c]);
        if (!std::isfinite(b))
            continue;
        const double m = std::max(a, b);
        total += m > 0 ? (b - a) / m : 0.0;
    }
    return n > 0 ? total / static_cast<double>(n) : 0.0;
}

std::vector<double> SensitivePointSelector::greyGrades(const std::vector<double> &x0,
                                                       const std::vector<std::vector<double>> &xs, double rho)
{
    double dmin = std::numeric_limits<double>::infinity(), dmax = 0.0;
    for (const std::vector<double> &x : xs) {
        if (x.size() != x0.size())
            throw std::invalid_argument("grey grade: sequences of different lengths");
        for (std::size_t k = 0; k < x0.size(); ++k) {
            const double d = std::fabs(x0[k] - x[k]);
            dmin = std::min(dmin, d);
            dmax = std::max(dmax, d);
        }
    }
    std::vector<double> grades(xs.size(), 1.0);
    if (!(dmax > 0) || x0.empty())
        return grades; // identical sequences: every coefficient is 1
    for (std::size_t i = 0; i < xs.size(); ++i) {
        double sum = 0.0;
        for (std::size_t k = 0; k < x0.size(); ++k)
            sum += (dmin + rho * dmax) / (std::fabs(x0[k] - xs[i][k]) + rho * dmax);
        grades[i] = sum / static_cast<double>(x0.size());
    }
    return grades;
}

SelectionResult SensitivePointSelector::select(const SignalTable &table, const SelectionOptions &o,
                                               const std::function<bool(double)> &progress)
{
    auto report = [&](double f) {
        if (progress && !progress(f))
            throw std::runtime_error("cancelled");
    };
    if (o.kMin < 2 || o.kMax < o.kMin)
        throw std::invalid_argument("k-range: need 2 <= K_min <= K_max, got " + std::to_string(o.kMin) + ":" +
                                    std::to_string(o.kMax));
    if (o.attempts < 1)
        throw std::invalid_argument("attempts must be at least 1");
    const SignalColumn &target = table.column(o.target);
    SelectionResult result;
    result.target = o.target;
    result.rule = ruleText(o.minValidFraction, o.rho);

    std::vector<const SignalColumn *> candidates;
    if (o.channels.empty()) {
        for (const SignalColumn &c : table.columns)
            if (c.kind == "temperature" && c.id != o.target)
                candidates.push_back(&c);
    } else {
        for (const std::string &id : o.channels) {
            if (id == o.target)
                throw std::invalid_argument("channel '" + id + "' is the target");
            candidates.push_back(&table.column(id));
        }
    }
    // Rows where the target is present.
    std::vector<std::size_t> targetRows;
    for (std::size_t k = 0; k < table.t.size(); ++k)
        if ((o.rows.empty() || o.rows[k]) && std::isfinite(target.v[k]))
            targetRows.push_back(k);
    if (targetRows.size() < 10)
        throw std::invalid_argument("target '" + o.target + "' has " + std::to_string(targetRows.size()) +
                                    " samples in the range; at least 10 are needed");
    std::vector<const SignalColumn *> kept;
    for (const SignalColumn *c : candidates) {
        std::size_t valid = 0;
        for (std::size_t r : targetRows)
            valid += std::isfinite(c->v[r]) ? 1 : 0;
        const double fraction = static_cast<double>(valid) / static_cast<double>(targetRows.size());
        if (fraction < o.minValidFraction) {
            char why[96];
            std::snprintf(why, sizeof why, "gaps: present on %.1f %% of the target's samples", 100.0 * fraction);
            result.excluded.push_back({c->id, why});
        } else {
            kept.push_back(c);
        }
    }
    std::vector<std::size_t> rows;
    for (std::size_t r : targetRows) {
        bool ok = true;
        for (const SignalColumn *c : kept)
            ok = ok && std::isfinite(c->v[r]);
        if (ok)
            rows.push_back(r);
    }
    if (rows.size() < 10)
        throw std::invalid_argument("only " + std::to_string(rows.size()) +
                                    " samples have the target and every channel; at least 10 are needed");
    std::vector<std::vector<double>> z;
    for (const SignalColumn *c : kept) {
        std::vector<double> zc;
        if (!zscore(c->v, rows, zc)) {
            result.excluded.push_back({c->id, "constant over the rows used"});
            continue;
        }
        result.channels.push_back(c->id);
        z.push_back(std::move(zc));
    }
    std::vector<double> zTarget;
    if (!zscore(target.v, rows, zTarget))
        throw std::invalid_argument("target '" + o.target + "' is constant over the rows used");
    const std::size_t n = z.size();
    if (n < 3)
        throw std::invalid_argument("only " + std::to_string(n) + " usable temperature channels; at least 3 are needed");
    result.rows = rows.size();
    result.from_s = table.t[rows.front()];
    result.to_s = table.t[rows.back()];
    report(0.1);

    // Gram matrix of the z-scored channels and the target correlations.
    const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd Z(m, static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i)
        Z.col(static_cast<Eigen::Index>(i)) = Eigen::Map<const Eigen::VectorXd>(z[i].data(), m);
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    gram.selfadjointView<Eigen::Lower>().rankUpdate(Z.transpose());
    gram = gram.selfadjointView<Eigen::Lower>();
    gram /= static_cast<double>(m);
    const Eigen::VectorXd targetCorr = Z.transpose() * Eigen::Map<const Eigen::VectorXd>(zTarget.data(), m) /
                                       static_cast<double>(m);
    report(0.4);
    result.correlationMatrix.assign(gram.data(), gram.data() + gram.size());
    result.correlation.assign(targetCorr.data(), targetCorr.data() + targetCorr.size());
    std::vector<double> distance(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            const auto a = static_cast<Eigen::Index>(i), b = static_cast<Eigen::Index>(j);
            distance[i * n + j] = std::sqrt(std::max(0.0, gram(a, a) + gram(b, b) - 2.0 * gram(a, b)));
        }
    // Exact embedding: gram = V L V' -> points V L^(1/2).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram);
    const Eigen::VectorXd lambda = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    const Eigen::MatrixXd points = eig.eigenvectors() * lambda.asDiagonal();
    cv::Mat data(static_cast<int>(n), static_cast<int>(n), CV_32F);
    for (int i = 0; i < static_cast<int>(n); ++i)
        for (int j = 0; j < static_cast<int>(n); ++j)
            data.at<float>(i, j) = static_cast<float>(points(i, j));

    const int kMax = std::min(o.kMax, static_cast<int>(n) - 1);
    if (kMax < o.kMin)
        throw std::invalid_argument("k-range " + std::to_string(o.kMin) + ":" + std::to_string(o.kMax) + " needs at least " +
                                    std::to_string(o.kMin + 1) + " usable channels, have " + std::to_string(n));
    for (int k = o.kMin; k <= kMax; ++k) {
        cv::theRNG().state = o.seed;
        cv::Mat labels, centers;
        const double compactness =
            cv::kmeans(data, k, labels, cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 300, 1e-8),
                       o.attempts, cv::KMEANS_PP_CENTERS, centers);
        // Number clusters by their first member so results read the same every run.
        std::map<int, int> renumber;
        ClusteringForK entry;
        entry.k = k;
        entry.compactness = compactness;
        for (int i = 0; i < static_cast<int>(n); ++i) {
            const int raw = labels.at<int>(i);
            const auto it = renumber.emplace(raw, static_cast<int>(renumber.size())).first;
            entry.labels.push_back(it->second);
        }
        entry.silhouette = silhouette(distance, entry.labels);
        result.perK.push_back(entry);
        report(0.4 + 0.5 * (k - o.kMin + 1) / (kMax - o.kMin + 1));
    }
    const ClusteringForK *best = &result.perK.front();
    for (const ClusteringForK &e : result.perK)
        if (e.silhouette > best->silhouette + 1e-12)
            best = &e;
    result.chosenK = best->k;
    result.labels = best->labels;
    result.clusters.assign(static_cast<std::size_t>(best->k), {});
    for (std::size_t i = 0; i < n; ++i)
        result.clusters[static_cast<std::size_t>(result.labels[i])].push_back(static_cast<int>(i));

    result.grade.assign(n, 0.0);
    result.gradeAll = greyGrades(zTarget, z, o.rho);
    for (const std::vector<int> &members : result.clusters) {
        std::vector<std::vector<double>> seq;
        for (int i : members)
            seq.push_back(z[static_cast<std::size_t>(i)]);
        const std::vector<double> g = greyGrades(zTarget, seq, o.rho);
        std::size_t bestMember = 0;
        for (std::size_t j = 0; j < members.size(); ++j) {
            result.grade[static_cast<std::size_t>(members[j])] = g[j];
            if (g[j] > g[bestMember])
                bestMember = j;
        }
        result.chosen.push_back(result.channels[static_cast<std::size_t>(members[bestMember])]);
    }
    report(1.0);
    return result;
}

} // namespace driftlab

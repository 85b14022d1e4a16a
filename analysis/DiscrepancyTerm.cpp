#include "DiscrepancyTerm.h"

#include "FixedText.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace driftlab {

namespace {

// First-order lag of a sampled series (input held between samples), started at rest.
TimeSeries lagged(const TimeSeries &s, double tau)
{
    TimeSeries out;
    out.t = s.t;
    std::vector<double> &y = out.v;
    y.resize(s.v.size());
    if (y.empty())
        return out;
    y[0] = s.v[0];
    for (size_t k = 1; k < y.size(); ++k) {
        const double a = tau > 0 ? 1.0 - std::exp(-std::max(0.0, s.t[k] - s.t[k - 1]) / tau) : 1.0;
        y[k] = y[k - 1] + a * (s.v[k] - y[k - 1]);
    }
    return out;
}

// Least squares of r on the columns `cols` of X over the rows in `rows`.
Eigen::VectorXd solve(const std::vector<std::vector<double>> &X, const std::vector<double> &r, const std::vector<size_t> &cols,
                      const std::vector<size_t> &rows)
{
    Eigen::MatrixXd A(rows.size(), cols.size());
    Eigen::VectorXd b(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
        for (size_t j = 0; j < cols.size(); ++j)
            A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = X[rows[i]][cols[j]];
        b(static_cast<Eigen::Index>(i)) = r[rows[i]];
    }
    return A.colPivHouseholderQr().solve(b);
}

} // namespace

std::string DiscrepancyTerm::Feature::describe() const
{
    std::string s = "dT(" + role + ")";
    if (tau_s > 0)
        s = "lag" + fixedText(tau_s / 60.0, 0) + "min[" + s + "]";
    if (power == 1)
        s += " * x";
    else if (power == 2)
        s += " * x^2";
    return s;
}

DiscrepancyTerm::DiscrepancyTerm(const Options &options) : m_options(options) {}

std::vector<std::vector<double>> DiscrepancyTerm::design(const std::vector<Feature> &features, double xMid, double xHalf,
                                                         const DiagnosisRecording &rec, const std::vector<ObservationFit> &points) const
{
    std::map<std::pair<std::string, double>, TimeSeries> cache;
    std::vector<std::vector<double>> X;
    // Each point's reference time from the recording's interferometer point at that time and
    // target (the points may be a subset, e.g. the cross-validation's held-out blocks).
    std::map<std::pair<long long, long long>, double> refOf;
    for (const PositioningErrorPoint &q : rec.screw.interferometer)
        refOf[{std::llround(q.t_s * 10.0), std::llround(q.position_mm * 10.0)}] = q.referenceTime_s;
    for (const ObservationFit &p : points) {
        if (p.elongation || p.temperature)
            continue;
        const auto it = refOf.find({std::llround(p.t_s * 10.0), std::llround(p.position_mm * 10.0)});
        double ref = it != refOf.end() && std::isfinite(it->second) ? it->second : rec.screw.referenceTime_s;
        if (!std::isfinite(ref))
            ref = p.t_s;
        std::vector<double> row(features.size(), 0.0);
        for (size_t j = 0; j < features.size(); ++j) {
            const Feature &f = features[j];
            const auto s = rec.channelsByRole.find(f.role);
            if (s == rec.channelsByRole.end() || s->second.size() < 2)
                continue;
            auto it = cache.find({f.role, f.tau_s});
            if (it == cache.end())
                it = cache.emplace(std::make_pair(f.role, f.tau_s), lagged(s->second, f.tau_s)).first;
            const double dT = it->second.at(p.t_s) - it->second.at(ref);
            row[j] = dT * std::pow((p.position_mm - xMid) / xHalf, f.power);
        }
        X.push_back(std::move(row));
    }
    return X;
}

DiscrepancyTerm::Fit DiscrepancyTerm::fit(const DiagnosisRecording &rec, const std::vector<ObservationFit> &points) const
{
    Fit out;
    std::vector<double> r, t;
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (const ObservationFit &p : points) {
        if (p.elongation || p.temperature)
            continue;
        r.push_back(p.measured_um - p.predicted_um);
        t.push_back(p.t_s);
        lo = std::min(lo, p.position_mm);
        hi = std::max(hi, p.position_mm);
    }
    out.points = static_cast<int>(r.size());
    if (r.size() < 10)
        return out;
    out.xMid_mm = 0.5 * (lo + hi);
    out.xHalf_mm = std::max(1.0, 0.5 * (hi - lo));
    double ss = 0.0;
    for (double e : r)
        ss += e * e;
    out.trainRmsBefore_um = out.trainRmsAfter_um = std::sqrt(ss / static_cast<double>(r.size()));
    out.cvRmsBefore_um = out.cvRmsAfter_um = out.trainRmsBefore_um; // the zero correction

    std::vector<Feature> all;
    for (const auto &[role, series] : rec.channelsByRole) {
        if (role == "screw_surface" || series.size() < 2)
            continue;
        for (double tau : m_options.lags_s)
            for (int p = 0; p <= m_options.maxPower; ++p)
                all.push_back({role, tau, p});
    }
    if (all.empty())
        return out;
    const std::vector<std::vector<double>> X = design(all, out.xMid_mm, out.xHalf_mm, rec, points);

    // Time blocks for the cross-validation.
    const double t0 = *std::min_element(t.begin(), t.end()), t1 = *std::max_element(t.begin(), t.end());
    const int K = std::max(2, m_options.folds);
    std::vector<int> fold(t.size());
    for (size_t i = 0; i < t.size(); ++i)
        fold[i] = std::min(K - 1, static_cast<int>(K * (t[i] - t0) / std::max(1e-9, t1 - t0)));
    auto cv = [&](const std::vector<size_t> &cols) {
        double sq = 0.0;
        size_t n = 0;
        for (int k = 0; k < K; ++k) {
            std::vector<size_t> fitRows, heldRows;
            for (size_t i = 0; i < t.size(); ++i)
                (fold[i] == k ? heldRows : fitRows).push_back(i);
            if (heldRows.empty() || fitRows.size() <= cols.size())
                continue;
            const Eigen::VectorXd c = solve(X, r, cols, fitRows);
            for (size_t i : heldRows) {
                double pred = 0.0;
                for (size_t j = 0; j < cols.size(); ++j)
                    pred += c(static_cast<Eigen::Index>(j)) * X[i][cols[j]];
                sq += (r[i] - pred) * (r[i] - pred);
                ++n;
            }
        }
        return n ? std::sqrt(sq / static_cast<double>(n)) : std::numeric_limits<double>::infinity();
    };

    std::vector<size_t> chosen;
    double current = out.cvRmsBefore_um;
    while (static_cast<int>(chosen.size()) < m_options.maxTerms) {
        double best = std::numeric_limits<double>::infinity();
        size_t which = 0;
        for (size_t j = 0; j < all.size(); ++j) {
            if (std::find(chosen.begin(), chosen.end(), j) != chosen.end())
                continue;
            std::vector<size_t> cols = chosen;
            cols.push_back(j);
            const double e = cv(cols);
            if (e < best) {
                best = e;
                which = j;
            }
        }
        if (!(best < current * (1.0 - m_options.minCvGain)))
            break;
        chosen.push_back(which);
        current = best;
    }
    if (chosen.empty())
        return out;
    std::vector<size_t> rows(r.size());
    for (size_t i = 0; i < rows.size(); ++i)
        rows[i] = i;
    const Eigen::VectorXd c = solve(X, r, chosen, rows);
    ss = 0.0;
    for (size_t i = 0; i < r.size(); ++i) {
        double pred = 0.0;
        for (size_t j = 0; j < chosen.size(); ++j)
            pred += c(static_cast<Eigen::Index>(j)) * X[i][chosen[j]];
        ss += (r[i] - pred) * (r[i] - pred);
    }
    for (size_t j = 0; j < chosen.size(); ++j) {
        out.terms.push_back(all[chosen[j]]);
        out.coefficients.push_back(c(static_cast<Eigen::Index>(j)));
    }
    out.trainRmsAfter_um = std::sqrt(ss / static_cast<double>(r.size()));
    out.cvRmsAfter_um = current;
    return out;
}

std::vector<double> DiscrepancyTerm::predict(const Fit &fit, const DiagnosisRecording &rec, const std::vector<ObservationFit> &points) const
{
    const std::vector<std::vector<double>> X = design(fit.terms, fit.xMid_mm, fit.xHalf_mm, rec, points);
    std::vector<double> out;
    out.reserve(X.size());
    for (const std::vector<double> &row : X) {
        double v = 0.0;
        for (size_t j = 0; j < row.size(); ++j)
            v += fit.coefficients[j] * row[j];
        out.push_back(v);
    }
    return out;
}

std::string DiscrepancyTerm::hypothesis(const Fit &fit, double fixedEnd_mm)
{
    if (fit.empty())
        return {};
    // The driver of the first term (chosen first: it explains the most) and its time scale.
    const Feature &lead = fit.terms.front();
    std::string s = "Empirical hypothesis (a discrepancy term fitted to the data, not a physical model): the residual "
                    "follows the '" + lead.role + "' temperature rise";
    s += lead.tau_s > 0 ? " through a first-order lag of about " + fixedText(lead.tau_s / 60.0, 0) + " min" : " directly (no lag)";
    // Shape along the travel: the terms of the lead driver evaluated at both ends and mid-travel
    // per kelvin of its rise.
    double lo = 0.0, mid = 0.0, hi = 0.0;
    for (size_t j = 0; j < fit.terms.size(); ++j) {
        if (fit.terms[j].role != lead.role)
            continue;
        lo += fit.coefficients[j] * std::pow(-1.0, fit.terms[j].power);
        mid += fit.terms[j].power == 0 ? fit.coefficients[j] : 0.0;
        hi += fit.coefficients[j];
    }
    const double xLo = fit.xMid_mm - fit.xHalf_mm, xHi = fit.xMid_mm + fit.xHalf_mm;
    const double big = std::max({std::fabs(lo), std::fabs(mid), std::fabs(hi)});
    if (big > 0 && std::min(std::fabs(lo), std::fabs(hi)) > 0.7 * big && lo * hi > 0) {
        s += ", about the same along the travel (" + fixedText(mid, 2) + " \u00b5m per K: a shift of every target)";
    } else {
        const bool loIsFixedEnd = !std::isfinite(fixedEnd_mm) || std::fabs(xLo - fixedEnd_mm) <= std::fabs(xHi - fixedEnd_mm);
        const bool largerAtLo = std::fabs(lo) > std::fabs(hi);
        const std::string end = largerAtLo == loIsFixedEnd ? "fixed" : "free";
        s += ", largest towards the " + end + " end of the screw (" + fixedText(lo, 2) + " \u00b5m/K at " + fixedText(xLo, 0) + " mm, " +
             fixedText(hi, 2) + " \u00b5m/K at " + fixedText(xHi, 0) + " mm)";
    }
    s += ". Terms: ";
    for (size_t j = 0; j < fit.terms.size(); ++j)
        s += (j ? ", " : "") + fixedText(fit.coefficients[j], 3) + " " + fit.terms[j].describe();
    s += " (x scaled to [-1, 1] over the travel).";
    return s;
}

} // namespace driftlab

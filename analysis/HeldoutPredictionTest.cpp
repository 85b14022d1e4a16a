#include "HeldoutPredictionTest.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <map>

namespace driftlab {

double HeldoutPredictionTest::studentUpperTail(double t, int df)
{
    if (!std::isfinite(t))
        return t > 0 ? 0.0 : 1.0;
    df = std::max(df, 1);
    // A(t | df) = P(|T| <= |t|), A&S 26.7.3 (odd df) and 26.7.4 (even df).
    const double x = std::fabs(t);
    const double theta = std::atan(x / std::sqrt(static_cast<double>(df)));
    const double c = std::cos(theta), s = std::sin(theta), c2 = c * c;
    double a = 0.0;
    if (df % 2 == 1) {
        double sum = 0.0;
        if (df > 1) {
            double term = c;
            sum = term;
            for (int k = 3; k <= df - 2; k += 2) {
                term *= c2 * static_cast<double>(k - 1) / static_cast<double>(k);
                sum += term;
            }
        }
        a = 2.0 / M_PI * (theta + s * sum);
    } else {
        double term = 1.0, sum = 1.0;
        for (int k = 2; k <= df - 2; k += 2) {
            term *= c2 * static_cast<double>(k - 1) / static_cast<double>(k);
            sum += term;
        }
        a = s * sum;
    }
    a = std::clamp(a, 0.0, 1.0);
    return t >= 0 ? 0.5 * (1.0 - a) : 0.5 * (1.0 + a);
}

namespace {

// Appends, per run of `reference`'s interferometer points (a new run where consecutive points
// are more than gap_s apart), log(RMS_ref / RMS_cand) over the run's points; the candidate's
// point is the one at the same time and position (a fold one of the two models could not fit
// is skipped).
void addRuns(const std::vector<ObservationFit> &reference, const std::vector<ObservationFit> &candidate, double gap_s,
             std::vector<double> &perRun)
{
    std::map<std::pair<long long, long long>, double> cand;
    for (const ObservationFit &b : candidate)
        if (!b.elongation && !b.temperature)
            cand[{std::llround(b.t_s * 1000.0), std::llround(b.position_mm * 1000.0)}] = b.measured_um - b.predicted_um;
    double sa = 0.0, sb = 0.0, last_t = 0.0;
    int count = 0;
    auto close = [&] {
        const double floor = 1e-12; // um^2: a run both models predict exactly says nothing
        if (count > 0 && (sa > floor || sb > floor))
            perRun.push_back(0.5 * std::log(std::max(sa, floor) / std::max(sb, floor)));
        sa = sb = 0.0;
        count = 0;
    };
    for (const ObservationFit &a : reference) {
        if (a.elongation || a.temperature)
            continue;
        const auto it = cand.find({std::llround(a.t_s * 1000.0), std::llround(a.position_mm * 1000.0)});
        if (it == cand.end())
            continue;
        const double ea = a.measured_um - a.predicted_um, eb = it->second;
        if (ea == 0.0 && eb == 0.0)
            continue; // the reference run: zero by definition for every model
        if (count > 0 && std::fabs(a.t_s - last_t) > gap_s)
            close();
        sa += ea * ea;
        sb += eb * eb;
        ++count;
        last_t = a.t_s;
    }
    close();
}

HeldoutPredictionTest::Result oneSampleT(const std::vector<double> &perRun)
{
    HeldoutPredictionTest::Result r;
    r.runs = static_cast<int>(perRun.size());
    if (perRun.size() < 3)
        return r;
    const double n = static_cast<double>(perRun.size());
    const Eigen::Map<const Eigen::ArrayXd> d(perRun.data(), static_cast<Eigen::Index>(perRun.size()));
    const double mean = d.mean();
    const double var = (d - mean).square().sum() / (n - 1.0);
    r.meanLogRatio = mean;
    if (var <= 0.0) {
        r.t = mean > 0 ? INFINITY : mean < 0 ? -INFINITY : 0.0;
        r.p = mean > 0 ? 0.0 : 1.0;
        return r;
    }
    r.t = mean / std::sqrt(var / n);
    r.p = HeldoutPredictionTest::studentUpperTail(r.t, r.runs - 1);
    return r;
}

} // namespace

HeldoutPredictionTest::Result HeldoutPredictionTest::run(const FitStatistics &reference, const FitStatistics &candidate, double runGap_s)
{
    std::vector<double> perRun;
    addRuns(reference.points, candidate.points, runGap_s, perRun);
    return oneSampleT(perRun);
}

HeldoutPredictionTest::Result HeldoutPredictionTest::run(const FitStatistics &reference, const FitStatistics &candidate,
                                                         const std::vector<ObservationFit> &referenceOutOfFold,
                                                         const std::vector<ObservationFit> &candidateOutOfFold, double runGap_s)
{
    std::vector<double> perRun;
    addRuns(reference.points, candidate.points, runGap_s, perRun);
    addRuns(referenceOutOfFold, candidateOutOfFold, runGap_s, perRun);
    return oneSampleT(perRun);
}

double HeldoutPredictionTest::benjaminiHochbergThreshold(std::vector<double> pValues, double q)
{
    std::sort(pValues.begin(), pValues.end());
    const double m = static_cast<double>(pValues.size());
    double threshold = -1.0;
    for (size_t k = 0; k < pValues.size(); ++k)
        if (pValues[k] <= static_cast<double>(k + 1) * q / m)
            threshold = pValues[k];
    return threshold;
}

} // namespace driftlab

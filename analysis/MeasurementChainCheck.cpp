#include "MeasurementChainCheck.h"

#include "ChannelErrorTerm.h"
#include "FixedText.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

namespace driftlab {

namespace {

// Ordinary least squares; standard errors scaled by the lag-1 autocorrelation of the residual
// (in the order given: time order), n_eff = n (1 - rho) / (1 + rho).
struct Ols {
    bool ok = false;
    Eigen::VectorXd beta, se;
    double r2 = 0.0;
    double t(int k) const { return se(k) > 0 ? beta(k) / se(k) : 0.0; }
};

Ols ols(const Eigen::MatrixXd &X, const Eigen::VectorXd &y)
{
    Ols o;
    const Eigen::Index n = X.rows(), p = X.cols();
    if (n < p + 5)
        return o;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
    if (qr.rank() < p)
        return o;
    o.beta = qr.solve(y);
    const Eigen::VectorXd e = y - X * o.beta;
    double num = 0.0;
    for (Eigen::Index i = 0; i + 1 < n; ++i)
        num += e(i) * e(i + 1);
    const double ss = e.squaredNorm();
    const double rho = ss > 0 ? std::clamp(num / ss, 0.0, 0.95) : 0.0;
    const double neff = std::max(static_cast<double>(p) + 2.0, n * (1.0 - rho) / (1.0 + rho));
    const double sigma2 = ss / std::max(1.0, neff - static_cast<double>(p));
    const Eigen::MatrixXd cov = (X.transpose() * X).inverse() * sigma2 * (static_cast<double>(n) / neff);
    o.se = cov.diagonal().cwiseMax(0.0).cwiseSqrt();
    const double mean = y.mean();
    const double tss = (y.array() - mean).square().sum();
    o.r2 = tss > 0 ? 1.0 - ss / tss : 0.0;
    o.ok = true;
    return o;
}

std::vector<ObservationFit> sortedByTime(const std::vector<ObservationFit> &pts, bool elongation)
{
    std::vector<ObservationFit> out;
    for (const ObservationFit &p : pts)
        if (!p.temperature && p.elongation == elongation)
            out.push_back(p);
    std::stable_sort(out.begin(), out.end(), [](const ObservationFit &a, const ObservationFit &b) { return a.t_s < b.t_s; });
    return out;
}

const TimeSeries *channel(const DiagnosisRecording &r, const std::string &role)
{
    if (r.hasRole(role))
        return &r.channelsByRole.at(role);
    if (role == "ambient" && r.screw.drive.ambient_C.size() >= 2)
        return &r.screw.drive.ambient_C;
    return nullptr;
}

// Interferometer regression y = b0 + b1 dT x/1000 + b2 dT on the residual points of `r`.
Ols airRegression(const DiagnosisRecording &r, const std::vector<ObservationFit> &pts, const TimeSeries &s)
{
    std::map<std::pair<double, double>, double> refOf;
    for (const PositioningErrorPoint &p : r.screw.interferometer)
        refOf[{p.t_s, p.position_mm}] = MeasurementChainCheck::referenceTime(r.screw, p);
    const std::vector<ObservationFit> v = sortedByTime(pts, false);
    Eigen::MatrixXd X(static_cast<Eigen::Index>(v.size()), 3);
    Eigen::VectorXd y(X.rows());
    for (size_t i = 0; i < v.size(); ++i) {
        const auto it = refOf.find({v[i].t_s, v[i].position_mm});
        const double ref = it != refOf.end() ? it->second : MeasurementChainCheck::referenceTime(r.screw, {});
        const double dT = s.at(v[i].t_s) - s.at(ref);
        const auto k = static_cast<Eigen::Index>(i);
        X(k, 0) = 1.0;
        X(k, 1) = dT * v[i].position_mm / 1000.0;
        X(k, 2) = dT;
        y(k) = v[i].measured_um - v[i].predicted_um;
    }
    return ols(X, y);
}

// Probe (or interferometer) residual vs a driver: y = b0 + b1 d(t), d = dT since the start or
// hours since the start.
Ols driverRegression(const std::vector<ObservationFit> &v, const TimeSeries *s, double t0, double *range = nullptr)
{
    Eigen::MatrixXd X(static_cast<Eigen::Index>(v.size()), 2);
    Eigen::VectorXd y(X.rows());
    double lo = 0.0, hi = 0.0;
    for (size_t i = 0; i < v.size(); ++i) {
        const double d = s ? s->at(v[i].t_s) - s->at(t0) : (v[i].t_s - t0) / 3600.0;
        const auto k = static_cast<Eigen::Index>(i);
        X(k, 0) = 1.0;
        X(k, 1) = d;
        y(k) = v[i].measured_um - v[i].predicted_um;
        lo = i ? std::min(lo, d) : d;
        hi = i ? std::max(hi, d) : d;
    }
    if (range)
        *range = hi - lo;
    return ols(X, y);
}

// Level step statistic of a series at each sample boundary: lines fitted over `window` s on
// either side, right minus left at the boundary. NaN where a side has too few samples.
std::vector<double> stepStatistic(const TimeSeries &s, double window)
{
    const size_t n = s.size();
    std::vector<double> out(n, std::nan(""));
    auto line = [&](size_t a, size_t b, double at) { // samples [a, b)
        const double m = static_cast<double>(b - a);
        double st = 0, sv = 0, stt = 0, stv = 0;
        for (size_t i = a; i < b; ++i) {
            const double t = s.t[i] - at;
            st += t;
            sv += s.v[i];
            stt += t * t;
            stv += t * s.v[i];
        }
        const double den = m * stt - st * st;
        if (den <= 0)
            return sv / m;
        const double slope = (m * stv - st * sv) / den;
        return (sv - slope * st) / m;
    };
    size_t a = 0, c = 0;
    for (size_t i = 1; i < n; ++i) {
        const double at = 0.5 * (s.t[i - 1] + s.t[i]);
        while (a < i && s.t[a] < at - window)
            ++a;
        while (c < n && s.t[c] <= at + window)
            ++c;
        if (i - a < 10 || c - i < 10)
            continue;
        out[i] = line(i, c, at) - line(a, i, at);
    }
    return out;
}

// The same right-minus-left level at boundary i with quadratics instead of lines on either side:
// a first-order response switching direction (a heater cycling on and off through a 20-min lag)
// bends hard right after the kink, and lines over 300 s then disagree at the kink by 0.3 K
// (the rig's hydraulic unit, 'none' seed 1) although nothing jumped; quadratics follow the
// bend, a real jump stays.
double quadraticStep(const TimeSeries &s, size_t i, double window)
{
    const double at = 0.5 * (s.t[i - 1] + s.t[i]);
    auto level = [&](size_t a, size_t b) { // quadratic through samples [a, b), value at `at`
        Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
        Eigen::Vector3d r = Eigen::Vector3d::Zero();
        for (size_t k = a; k < b; ++k) {
            const double u = (s.t[k] - at) / window;
            const Eigen::Vector3d x(1.0, u, u * u);
            A += x * x.transpose();
            r += x * s.v[k];
        }
        return A.ldlt().solve(r)(0);
    };
    size_t a = i, c = i;
    while (a > 0 && s.t[a - 1] >= at - window)
        --a;
    while (c < s.size() && s.t[c] <= at + window)
        ++c;
    if (i - a < 10 || c - i < 10)
        return std::nan("");
    return level(i, c) - level(a, i);
}

double robustSpread(const std::vector<double> &x)
{
    std::vector<double> a;
    for (double v : x)
        if (std::isfinite(v))
            a.push_back(std::fabs(v));
    if (a.empty())
        return 0.0;
    std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2), a.end());
    return 1.4826 * a[a.size() / 2];
}

// The baseline refitted together with an interferometer-only air law (c1 P_x + c0)(T_air(t) -
// T_air(t_ref)) on one recording: the probe, which the air does not reach, anchors the screw, so
// the fit cannot bend the machine's parameters to absorb the law (it did: the baseline's residual
// kept t = -0.8 of an injected 0.93 um/m/K on othersim). SE scaled by the lag-1 autocorrelation
// of the interferometer residual in time order, as ols() does.
struct AirJoint {
    bool ok = false;
    double k = 0.0, se = 0.0, c0 = 0.0, heldoutRms = 0.0;
    double t() const { return se > 0 ? k / se : 0.0; }
};

AirJoint airJoint(const DiagnosisRecording &fitOn, const DiagnosisRecording *predictOn, const ScrewGeometry &geometry,
                  const IdentificationOptions &options, const MeasurementChainCheck::Machine &machine)
{
    AirJoint a;
    const TimeSeries *air = channel(fitOn, "ambient");
    const TimeSeries *airP = predictOn ? channel(*predictOn, "ambient") : nullptr;
    if (!air || (predictOn && !airP))
        return a;
    try {
        auto slope = std::make_shared<ChannelErrorTerm>(ChannelErrorTerm::Mode::Linear);
        auto offset = std::make_shared<ChannelErrorTerm>(ChannelErrorTerm::Mode::Offset);
        slope->bind(air, fitOn.screw);
        offset->bind(air, fitOn.screw);
        ScrewModelIdentifier id(geometry, options);
        const CandidateModel built = machine ? machine() : CandidateModel{};
        built.addTo(id);
        built.bindTo(fitOn);
        id.addErrorTerm(slope);
        id.addErrorTerm(offset);
        const IdentificationResult fit = id.fit({fitOn.screw});
        for (const IdentifiedParameter &p : fit.all) {
            if (p.name == slope->amplitude().name) {
                a.k = p.value;
                a.se = p.standardError;
            } else if (p.name == offset->amplitude().name) {
                a.c0 = p.value;
            }
        }
        const std::vector<ObservationFit> v = sortedByTime(fit.fit.points, false);
        double num = 0.0, ss = 0.0;
        for (size_t i = 0; i < v.size(); ++i) {
            const double e = v[i].measured_um - v[i].predicted_um;
            ss += e * e;
            if (i + 1 < v.size())
                num += e * (v[i + 1].measured_um - v[i + 1].predicted_um);
        }
        const double rho = ss > 0 ? std::clamp(num / ss, 0.0, 0.95) : 0.0;
        a.se *= std::sqrt((1.0 + rho) / (1.0 - rho));
        if (predictOn) {
            slope->bind(airP, predictOn->screw);
            offset->bind(airP, predictOn->screw);
            built.bindTo(*predictOn);
            a.heldoutRms = id.predict(fit, {predictOn->screw}).interferometerRms_um;
        }
        a.ok = a.se > 0 && std::isfinite(a.k);
    } catch (const std::exception &) {
        a.ok = false;
    }
    return a;
}

double rmsOf(const std::vector<ObservationFit> &pts)
{
    double ss = 0.0;
    int n = 0;
    for (const ObservationFit &p : pts)
        if (!p.temperature && !p.elongation) {
            ss += (p.measured_um - p.predicted_um) * (p.measured_um - p.predicted_um);
            ++n;
        }
    return n ? std::sqrt(ss / n) : 0.0;
}

} // namespace

std::vector<SensorFinding> MeasurementChainCheck::airByJointFit(const DiagnosisRecording &train, const DiagnosisRecording &validate,
                                                                const ScrewGeometry &geometry, const IdentificationOptions &options,
                                                                const std::vector<ObservationFit> &validateFit, const Options &o,
                                                                const Machine &machine)
{
    std::vector<SensorFinding> out;
    if (train.screw.elongation_um.size() <= 20) // nothing the air does not reach to anchor the screw
        return out;
    const AirJoint a = airJoint(train, &validate, geometry, options, machine);
    if (!a.ok)
        return out;
    const double baseHeldout = rmsOf(validateFit);
    const bool inRange = std::fabs(a.k) >= o.airLow_um_mK && std::fabs(a.k) <= o.airHigh_um_mK;
    const bool significant = std::fabs(a.t()) >= o.airJointMinT;
    AirJoint b;
    if (inRange && significant)
        b = airJoint(validate, nullptr, geometry, options, machine);
    const bool confirmed = b.ok && b.k * a.k > 0 && std::fabs(b.t()) >= o.confirmT;
    const bool predicts = a.heldoutRms < baseHeldout;
    if (!(inRange && significant && confirmed && predicts))
        return out;
    SensorFinding f;
    f.sensor = "interferometer";
    f.role = "interferometer";
    f.kind = "air";
    f.driver = "ambient";
    f.coefficient = a.k;
    f.standardError = a.se;
    f.intercept = a.c0;
    f.unit = "um/(m K)";
    f.recording = train.screw.name;
    f.law = "the interferometer reading follows the air temperature at " + fixedText(a.k, 2) +
            " \u00b5m/m/K over the axis position (air compensation off or wrong); the probe and the screw model do not";
    f.evidence.push_back("training, refitted with the screw model (the probe anchors the screw): k = " + fixedText(a.k, 3) +
                         " +- " + fixedText(a.se, 3) + " \u00b5m/m/K (t = " + fixedText(a.t(), 1) + ")");
    f.evidence.push_back("validation, refitted on its own: k = " + fixedText(b.k, 3) + " \u00b5m/m/K (t = " + fixedText(b.t(), 1) + ")");
    f.evidence.push_back("validation interferometer RMS predicted with the law " + fixedText(a.heldoutRms, 3) + " \u00b5m, without " +
                         fixedText(baseHeldout, 3) + " \u00b5m");
    out.push_back(std::move(f));
    return out;
}

double MeasurementChainCheck::referenceTime(const ScrewRecording &r, const PositioningErrorPoint &p)
{
    if (std::isfinite(p.referenceTime_s))
        return p.referenceTime_s;
    if (std::isfinite(r.referenceTime_s))
        return r.referenceTime_s;
    return r.drive.position_mm.empty() ? 0.0 : r.drive.position_mm.t.front();
}

std::vector<SensorFinding> MeasurementChainCheck::steps(const DiagnosisRecording &r, const Options &o)
{
    struct Stat {
        std::string role;
        std::vector<double> d;
        const TimeSeries *s;
        double spread;
    };
    std::vector<Stat> stats;
    for (const auto &c : r.channelsByRole)
        if (c.second.size() >= 40) {
            Stat st{c.first, stepStatistic(c.second, o.stepWindow_s), &c.second, 0.0};
            st.spread = robustSpread(st.d);
            stats.push_back(std::move(st));
        }
    std::vector<SensorFinding> out;
    for (const Stat &st : stats) {
        size_t best = 0;
        double big = 0.0;
        for (size_t i = 0; i < st.d.size(); ++i)
            if (std::isfinite(st.d[i]) && std::fabs(st.d[i]) > big) {
                big = std::fabs(st.d[i]);
                best = i;
            }
        if (big < o.minStep_K || big < o.stepNoiseFactor * st.spread)
            continue;
        // A kink that bends hard is not a jump: quadratics on either side must see it too.
        const double bent = quadraticStep(*st.s, best, o.stepWindow_s);
        if (!(bent * st.d[best] > 0) || std::fabs(bent) < 0.6 * big)
            continue;
        const double at = 0.5 * (st.s->t[best - 1] + st.s->t[best]);
        // No other channel steps at that moment (a common jump would be the logger's or real).
        std::string others;
        bool alone = true;
        for (const Stat &q : stats) {
            if (&q == &st)
                continue;
            const TimeSeries &s = *q.s;
            const size_t at_i = static_cast<size_t>(std::lower_bound(s.t.begin(), s.t.end(), at) - s.t.begin());
            double local = 0.0;
            for (size_t j = at_i > 3 ? at_i - 3 : 1; j < std::min(s.size(), at_i + 3); ++j)
                if (std::isfinite(q.d[j]))
                    local = std::max(local, std::fabs(q.d[j]));
            if (local >= std::max(0.5 * o.minStep_K, o.stepNoiseFactor * q.spread) || local >= 0.5 * big)
                alone = false;
            others += (others.empty() ? "" : ", ") + q.role + " " + fixedText(local, 2) + " K";
        }
        if (!alone)
            continue;
        SensorFinding f;
        f.sensor = st.role + " PT100";
        f.role = st.role;
        f.kind = "step";
        f.driver = "time";
        f.coefficient = st.d[best];
        f.standardError = st.spread;
        f.unit = "K";
        f.time_s = at;
        f.recording = r.screw.name;
        f.law = "the " + st.role + " PT100 of '" + r.screw.name + "' jumps by " + fixedText(st.d[best], 2) + " K at t = " +
                fixedText(at, 0) + " s and stays there (a step, not heat: heat bends a temperature, it does not make it jump); "
                "no other sensor moves then";
        f.evidence.push_back("step " + fixedText(st.d[best], 3) + " K = " + fixedText(big / std::max(st.spread, 1e-9), 0) +
                             " x the channel's robust spread of the statistic (" + fixedText(st.spread, 4) + " K)");
        if (!others.empty())
            f.evidence.push_back("other channels at that moment: " + others);
        out.push_back(std::move(f));
    }
    return out;
}

std::vector<SensorFinding> MeasurementChainCheck::check(const DiagnosisRecording &train, const DiagnosisRecording &validate,
                                                        const std::vector<ObservationFit> &trainFit,
                                                        const std::vector<ObservationFit> &validateFit,
                                                        const std::vector<ObservationFit> &trainIO,
                                                        const std::vector<ObservationFit> &validateIO, const Options &o)
{
    std::vector<SensorFinding> out;
    const double t0 = train.screw.drive.position_mm.empty() ? 0.0 : train.screw.drive.position_mm.t.front();

    // 1. Interferometer vs the air.
    const TimeSeries *air = channel(train, "ambient");
    const TimeSeries *airB = channel(validate, "ambient");
    if (air && airB) {
        const Ols a = airRegression(train, trainFit, *air);
        if (a.ok) {
            const double k = a.beta(1), tk = a.t(1);
            double bestOther = 0.0;
            std::string bestOtherRole;
            for (const auto &c : train.channelsByRole) {
                if (c.first == "ambient" || c.second.size() < 2)
                    continue;
                const Ols q = airRegression(train, trainFit, c.second);
                if (q.ok && q.r2 > bestOther) {
                    bestOther = q.r2;
                    bestOtherRole = c.first;
                }
            }
            const std::vector<ObservationFit> probe = sortedByTime(trainFit, true);
            const Ols p = probe.size() > 20 ? driverRegression(probe, air, t0) : Ols{};
            double xMax = 0.0;
            for (const PositioningErrorPoint &q : train.screw.interferometer)
                xMax = std::max(xMax, std::fabs(q.position_mm) / 1000.0);
            const bool probeQuiet = !p.ok || std::fabs(p.t(1)) < o.confirmT || std::fabs(p.beta(1)) < 0.5 * std::fabs(k) * xMax;
            const Ols b = airRegression(validate, validateFit, *airB);
            const bool confirmed = b.ok && b.beta(1) * k > 0 && std::fabs(b.t(1)) >= o.confirmT;
            if (std::fabs(tk) >= o.minT && std::fabs(k) >= o.airLow_um_mK && std::fabs(k) <= o.airHigh_um_mK &&
                a.r2 > bestOther && probeQuiet && confirmed) {
                SensorFinding f;
                f.sensor = "interferometer";
                f.role = "interferometer";
                f.kind = "air";
                f.driver = "ambient";
                f.coefficient = k;
                f.standardError = a.se(1);
                f.intercept = a.beta(2);
                f.unit = "um/(m K)";
                f.recording = train.screw.name;
                f.law = "the interferometer reading follows the air temperature at " + fixedText(k, 2) +
                        " \u00b5m/m/K over the axis position (air compensation off or wrong); the " +
                        (p.ok ? "probe does not (" + fixedText(p.beta(1), 2) + " \u00b5m/K, t = " + fixedText(p.t(1), 1) + ")"
                              : "model's screw temperatures do not");
                f.evidence.push_back("training: k = " + fixedText(k, 3) + " +- " + fixedText(a.se(1), 3) + " \u00b5m/m/K (t = " +
                                     fixedText(tk, 1) + "), R2 " + fixedText(a.r2, 2) + " of the baseline's residual");
                f.evidence.push_back("validation: k = " + fixedText(b.beta(1), 3) + " \u00b5m/m/K (t = " + fixedText(b.t(1), 1) + ")");
                if (!bestOtherRole.empty())
                    f.evidence.push_back("best other temperature for the same law: " + bestOtherRole + " (R2 " +
                                         fixedText(bestOther, 2) + ")");
                out.push_back(std::move(f));
            }
        }
    }

    // 2. Probe vs a model fitted to the interferometer alone. Drivers a holder can follow: the
    // structure, the air, the coolant, time (not the bearing, nut or motor housings: heat there
    // reaches the screw, and the probe then sees real physics).
    const std::vector<ObservationFit> probe = sortedByTime(trainIO, true);
    const std::vector<ObservationFit> probeB = sortedByTime(validateIO, true);
    if (probe.size() > 20 && probeB.size() > 20) {
        struct Best {
            std::string driver;
            Ols fit;
            double range = 0.0;
        } best;
        for (const char *role : {"structure", "ambient", "coolant", ""}) {
            const TimeSeries *s = *role ? channel(train, role) : nullptr;
            if (*role && !s)
                continue;
            double range = 0.0;
            const Ols q = driverRegression(probe, s, probe.front().t_s, &range);
            if (q.ok && (best.driver.empty() || q.r2 > best.fit.r2))
                best = {*role ? role : "time", q, range};
        }
        if (!best.driver.empty() && best.fit.r2 >= o.minProbeR2 && std::fabs(best.fit.t(1)) >= o.minT &&
            std::fabs(best.fit.beta(1)) * best.range >= o.minProbeDrift_um) {
            const TimeSeries *s = best.driver == "time" ? nullptr : channel(train, best.driver);
            const TimeSeries *sB = best.driver == "time" ? nullptr : channel(validate, best.driver);
            // The interferometer's own residual must not follow the same driver (relative to
            // each point's reference run).
            const std::vector<ObservationFit> inter = sortedByTime(trainIO, false);
            Eigen::MatrixXd X(static_cast<Eigen::Index>(inter.size()), 2);
            Eigen::VectorXd y(X.rows());
            std::map<std::pair<double, double>, double> refOf;
            for (const PositioningErrorPoint &p : train.screw.interferometer)
                refOf[{p.t_s, p.position_mm}] = referenceTime(train.screw, p);
            for (size_t i = 0; i < inter.size(); ++i) {
                const auto it = refOf.find({inter[i].t_s, inter[i].position_mm});
                const double ref = it != refOf.end() ? it->second : t0;
                const auto k = static_cast<Eigen::Index>(i);
                X(k, 0) = 1.0;
                X(k, 1) = s ? s->at(inter[i].t_s) - s->at(ref) : (inter[i].t_s - ref) / 3600.0;
                y(k) = inter[i].measured_um - inter[i].predicted_um;
            }
            const Ols qi = ols(X, y);
            // (by size, not significance: autocorrelated run residuals can hide a real share)
            const bool interQuiet = !qi.ok || std::fabs(qi.beta(1)) <= o.maxInterferometerShare * std::fabs(best.fit.beta(1));
            const Ols qb = (best.driver == "time" || sB) ? driverRegression(probeB, sB, probeB.front().t_s) : Ols{};
            const bool confirmed = qb.ok && qb.beta(1) * best.fit.beta(1) > 0 && std::fabs(qb.t(1)) >= o.confirmT;
            if (interQuiet && confirmed) {
                const bool time = best.driver == "time";
                const std::string unit = time ? "um/h" : "um/K";
                const std::string shown = time ? "\u00b5m/h" : "\u00b5m/K"; // the unit code above is stored, this one is read
                SensorFinding f;
                f.sensor = "screw_elongation probe";
                f.role = "screw_elongation";
                f.kind = "drift";
                f.driver = best.driver;
                f.coefficient = best.fit.beta(1);
                f.standardError = best.fit.se(1);
                f.unit = unit;
                f.recording = train.screw.name;
                f.law = "the screw-end probe reading follows " +
                        (time ? std::string("time") : "the " + best.driver + " temperature") + " at " +
                        fixedText(best.fit.beta(1), 2) + " " + shown + " (its holder moves); the interferometer does not (" +
                        (qi.ok ? fixedText(qi.beta(1), 2) + " " + shown + ", t = " + fixedText(qi.t(1), 1) : "n/a") +
                        "): the probe is left out";
                f.evidence.push_back("training: " + fixedText(best.fit.beta(1), 3) + " +- " + fixedText(best.fit.se(1), 3) + " " +
                                     shown + " (t = " + fixedText(best.fit.t(1), 1) + "), R2 " + fixedText(best.fit.r2, 2) +
                                     " of the probe's disagreement with a model fitted to the interferometer alone");
                f.evidence.push_back("validation: " + fixedText(qb.beta(1), 3) + " " + shown + " (t = " + fixedText(qb.t(1), 1) + ")");
                out.push_back(std::move(f));
            }
        }
    }
    return out;
}

void MeasurementChainCheck::correct(DiagnosisRecording &r, const SensorFinding &f)
{
    if (f.kind == "air") {
        const TimeSeries *air = channel(r, "ambient");
        if (!air)
            return;
        for (PositioningErrorPoint &p : r.screw.interferometer) {
            const double dT = air->at(p.t_s) - air->at(referenceTime(r.screw, p));
            p.error_um -= (f.coefficient * p.position_mm / 1000.0 + f.intercept) * dT;
        }
    } else if (f.kind == "drift" && f.role == "screw_elongation") {
        r.screw.elongation_um = TimeSeries{};
    } else if (f.kind == "step" && f.recording == r.screw.name) {
        auto fix = [&](TimeSeries &s) {
            for (size_t i = 0; i < s.size(); ++i)
                if (s.t[i] >= f.time_s)
                    s.v[i] -= f.coefficient;
        };
        const auto it = r.channelsByRole.find(f.role);
        if (it != r.channelsByRole.end())
            fix(it->second);
        if (f.role == "ambient")
            fix(r.screw.drive.ambient_C);
    }
}

std::vector<SensorFinding> MeasurementChainCheck::correctSteps(DiagnosisRecording &r)
{
    std::vector<SensorFinding> found = steps(r, Options{});
    for (const SensorFinding &f : found)
        correct(r, f);
    return found;
}

std::vector<SensorFinding> MeasurementChainCheck::examine(DiagnosisRecording &train, DiagnosisRecording &validate,
                                                          const ScrewGeometry &geometry, const IdentificationOptions &options,
                                                          const std::vector<ObservationFit> &trainFit,
                                                          const std::vector<ObservationFit> &validateFit, const Machine &machine)
{
    std::vector<ObservationFit> trainIO, validateIO;
    if (train.screw.elongation_um.size() > 20 && validate.screw.elongation_um.size() > 20) {
        try {
            DiagnosisRecording io = train;
            io.screw.elongation_um = TimeSeries{};
            ScrewModelIdentifier id(geometry, options);
            const CandidateModel built = machine ? machine() : CandidateModel{};
            built.addTo(id);
            built.bindTo(io);
            const IdentificationResult fit = id.fit({io.screw});
            built.bindTo(train);
            trainIO = id.predict(fit, {train.screw}).points;
            built.bindTo(validate);
            validateIO = id.predict(fit, {validate.screw}).points;
        } catch (const std::exception &) {
            trainIO.clear(); // no probe cross-check when the interferometer alone cannot be fitted
            validateIO.clear();
        }
    }
    std::vector<SensorFinding> found = check(train, validate, trainFit, validateFit, trainIO, validateIO, Options{});
    // The baseline may have absorbed part of an air law (or the residual regression may take
    // some of the machine's own air response for it): refit the baseline with the law, the
    // probe anchoring the screw. When that names the law, its coefficient replaces the
    // residual regression's.
    DiagnosisRecording trainProbe = train, validateProbe = validate;
    for (const SensorFinding &f : found) // a probe found drifting cannot anchor anything
        if (f.kind != "air") {
            correct(trainProbe, f);
            correct(validateProbe, f);
        }
    const std::vector<SensorFinding> joint =
        airByJointFit(trainProbe, validateProbe, geometry, options, validateFit, Options{}, machine);
    if (!joint.empty()) {
        found.erase(std::remove_if(found.begin(), found.end(), [](const SensorFinding &f) { return f.kind == "air"; }), found.end());
        found.insert(found.begin(), joint.begin(), joint.end());
    }
    for (const SensorFinding &f : found) {
        correct(train, f);
        correct(validate, f);
    }
    return found;
}

} // namespace driftlab

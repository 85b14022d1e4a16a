#include "ResidualLocator.h"

#include "FixedText.h"
#include "ParameterPlausibility.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace driftlab {

namespace {

struct Accumulator {
    int n = 0;
    double sum = 0.0, sq = 0.0;
    void add(double r)
    {
        ++n;
        sum += r;
        sq += r * r;
    }
    ResidualGroup group(const std::string &label) const
    {
        ResidualGroup g;
        g.label = label;
        g.count = n;
        g.mean_um = n ? sum / n : 0.0;
        g.rms_um = n ? std::sqrt(sq / n) : 0.0;
        return g;
    }
};

double pearson(const std::vector<double> &a, const std::vector<double> &b)
{
    const size_t n = a.size();
    if (n < 3)
        return 0.0;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; ++i) {
        ma += a[i];
        mb += b[i];
    }
    ma /= n;
    mb /= n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    if (saa <= 1e-300 || sbb <= 1e-300)
        return 0.0;
    return sab / std::sqrt(saa * sbb);
}

double meanFeed(const TimeSeries &feed, double t0, double t1)
{
    const int n = 30;
    double s = 0.0;
    for (int k = 0; k < n; ++k)
        s += std::fabs(feed.at(t0 + (t1 - t0) * (k + 0.5) / n));
    return s / n;
}

std::string fmt(double v, int prec = 2)
{
    std::ostringstream o;
    o.setf(std::ios::fixed);
    o.precision(prec);
    o << v;
    return o.str();
}

} // namespace

std::string ResidualLocator::phaseAt(const ScrewDrive &drive, double t)
{
    const TimeSeries &feed = drive.feed_mm_min;
    if (feed.empty())
        return "unknown";
    const double t0 = feed.t.front();
    auto moving = [&](double at) { return meanFeed(feed, at - 60.0, at) > 1.0; };
    const bool now = moving(t);
    // How long the current state has lasted (minute steps back, at most 4 h), ever moved before.
    double since = 0.0;
    bool everMoved = now;
    for (double back = 60.0; t - back >= t0 && back <= 4 * 3600.0; back += 60.0) {
        const bool m = moving(t - back);
        everMoved = everMoved || m;
        if (m != now)
            break;
        since = back;
    }
    if (!everMoved)
        for (double back = 0.0; t - back >= t0; back += 300.0)
            if (moving(t - back)) {
                everMoved = true;
                break;
            }
    if (!now)
        return everMoved ? "cooling" : "standstill";
    if (since < 1800.0)
        return "warm-up";
    const double f = meanFeed(feed, t - 600.0, t);
    return "feed " + std::to_string(static_cast<long>(std::lround(f / 500.0) * 500)) + " mm/min";
}

double ResidualLocator::lag1Autocorrelation(const std::vector<ObservationFit> &points)
{
    std::map<long, std::vector<std::pair<double, double>>> streams; // target key -> (t, r)
    double mean = 0.0;
    for (const ObservationFit &p : points)
        mean += p.predicted_um - p.measured_um;
    if (points.empty())
        return 0.0;
    mean /= static_cast<double>(points.size());
    for (const ObservationFit &p : points) {
        const long key = p.temperature   ? -2000000000L + std::lround(p.distance_m * 1000.0)
                         : p.elongation ? -999999999L
                                        : std::lround(p.position_mm * 10.0);
        streams[key].emplace_back(p.t_s, p.predicted_um - p.measured_um - mean);
    }
    double num = 0.0, den = 0.0;
    for (auto &s : streams) {
        auto &v = s.second;
        std::sort(v.begin(), v.end());
        for (size_t i = 0; i < v.size(); ++i) {
            den += v[i].second * v[i].second;
            if (i + 1 < v.size())
                num += v[i].second * v[i + 1].second;
        }
    }
    return den > 0 ? std::clamp(num / den, -0.99, 0.99) : 0.0;
}

double ResidualLocator::effectiveSampleSize(const std::vector<ObservationFit> &points)
{
    std::map<long, std::vector<std::pair<double, double>>> streams;
    for (const ObservationFit &p : points) {
        const long key = p.temperature   ? -2000000000L + std::lround(p.distance_m * 1000.0)
                         : p.elongation ? -999999999L
                                        : std::lround(p.position_mm * 10.0);
        streams[key].emplace_back(p.t_s, p.predicted_um - p.measured_um);
    }
    double total = 0.0;
    for (auto &s : streams) {
        auto &v = s.second;
        std::sort(v.begin(), v.end());
        const double n = static_cast<double>(v.size());
        double mean = 0.0;
        for (const auto &x : v)
            mean += x.second;
        mean /= n;
        double num = 0.0, den = 0.0;
        for (size_t i = 0; i < v.size(); ++i) {
            den += (v[i].second - mean) * (v[i].second - mean);
            if (i + 1 < v.size())
                num += (v[i].second - mean) * (v[i + 1].second - mean);
        }
        const double rho = den > 0 ? std::clamp(num / den, 0.0, 0.98) : 0.0;
        total += std::max(1.0, n * (1.0 - rho) / (1.0 + rho));
    }
    return total;
}

double ResidualLocator::chiSquareUpperTail(double x, int k)
{
    if (k <= 0)
        return 1.0;
    if (x <= 0)
        return 1.0;
    const double a = 2.0 / (9.0 * k);
    const double z = (std::cbrt(x / k) - (1.0 - a)) / std::sqrt(a);
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

ResidualLocation ResidualLocator::locate(const DiagnosisRecording &rec, const std::vector<ObservationFit> &points)
{
    ResidualLocation loc;
    const ScrewDrive &drive = rec.screw.drive;
    const double t0 = drive.position_mm.empty() ? 0.0 : drive.position_mm.t.front();
    std::map<std::string, Accumulator> phase, hour;
    std::map<long, Accumulator> target;
    Accumulator interf, elong;
    std::map<std::string, std::string> phaseCache;
    std::vector<const ObservationFit *> ip;
    for (const ObservationFit &p : points) {
        if (p.temperature)
            continue; // located by locateTemperatures()
        const double r = p.predicted_um - p.measured_um;
        (p.elongation ? elong : interf).add(r);
        if (p.elongation)
            continue;
        ip.push_back(&p);
        phase[phaseAt(drive, p.t_s)].add(r);
        target[std::lround(p.position_mm * 10.0)].add(r);
        const int h = static_cast<int>((p.t_s - t0) / 3600.0);
        char label[32];
        std::snprintf(label, sizeof label, "%02d h", h);
        hour[label].add(r);
    }
    for (const auto &g : phase)
        loc.byPhase.push_back(g.second.group(g.first));
    for (const auto &g : hour)
        loc.byHour.push_back(g.second.group(g.first));
    for (const auto &g : target)
        loc.byPosition.push_back(g.second.group(fmt(g.first / 10.0, 1) + " mm"));
    if (interf.n)
        loc.bySensor.push_back(interf.group("interferometer"));
    if (elong.n)
        loc.bySensor.push_back(elong.group("screw_elongation"));

    // Part of the screw: targets in thirds of their span (order along the travel).
    if (!target.empty()) {
        const double lo = target.begin()->first / 10.0, hi = target.rbegin()->first / 10.0;
        Accumulator parts[3];
        for (const ObservationFit *p : ip) {
            const double u = hi > lo ? (p->position_mm - lo) / (hi - lo) : 0.5;
            parts[std::min(2, static_cast<int>(u * 3.0))].add(p->predicted_um - p->measured_um);
        }
        const char *names[3] = {"low third of the travel", "middle third of the travel", "high third of the travel"};
        for (int k = 0; k < 3; ++k)
            if (parts[k].n)
                loc.byScrewPart.push_back(parts[k].group(names[k]));
    }

    // Whiteness.
    loc.lag1Autocorrelation = lag1Autocorrelation(points);
    {
        // Run means of the interferometer (points within 15 min belong to one run), else probe.
        std::vector<std::pair<double, double>> tr;
        for (const ObservationFit *p : ip)
            tr.emplace_back(p->t_s, p->predicted_um - p->measured_um);
        std::sort(tr.begin(), tr.end());
        std::vector<double> series;
        double runStart = -1e300, s = 0.0;
        int n = 0;
        for (const auto &x : tr) {
            if (x.first - runStart > 900.0) {
                if (n)
                    series.push_back(s / n);
                runStart = x.first;
                s = 0.0;
                n = 0;
            }
            s += x.second;
            ++n;
        }
        if (n)
            series.push_back(s / n);
        if (series.size() < 8) {
            series.clear();
            for (const ObservationFit &p : points)
                if (p.elongation)
                    series.push_back(p.predicted_um - p.measured_um);
        }
        const int N = static_cast<int>(series.size());
        const int h = std::min(10, N / 4);
        if (h >= 1) {
            double m = 0.0;
            for (double v : series)
                m += v;
            m /= N;
            double c0 = 0.0;
            for (double v : series)
                c0 += (v - m) * (v - m);
            double q = 0.0;
            for (int k = 1; k <= h && c0 > 0; ++k) {
                double ck = 0.0;
                for (int i = k; i < N; ++i)
                    ck += (series[static_cast<size_t>(i)] - m) * (series[static_cast<size_t>(i - k)] - m);
                const double rk = ck / c0;
                q += rk * rk / (N - k);
            }
            loc.ljungBoxQ = N * (N + 2.0) * q;
            loc.ljungBoxLags = h;
            loc.ljungBoxP = chiSquareUpperTail(loc.ljungBoxQ, h);
        }
        loc.white = loc.ljungBoxP > 0.01 && std::fabs(loc.lag1Autocorrelation) < 0.5;
    }

    // Cross-correlation of the interferometer residuals with inputs and auxiliary channels.
    if (ip.size() >= 5) {
        std::vector<double> res, feed, time, pos;
        for (const ObservationFit *p : ip) {
            res.push_back(p->predicted_um - p->measured_um);
            feed.push_back(drive.feed_mm_min.empty() ? 0.0 : meanFeed(drive.feed_mm_min, p->t_s - 1800.0, p->t_s));
            time.push_back(p->t_s - t0);
            pos.push_back(p->position_mm);
        }
        loc.correlations.push_back({"feed (30-min mean)", pearson(res, feed)});
        loc.correlations.push_back({"time", pearson(res, time)});
        loc.correlations.push_back({"position", pearson(res, pos)});
        // Reference time per target from the recording.
        auto refTime = [&](double position) {
            double best = 1e300, ref = std::isfinite(rec.screw.referenceTime_s) ? rec.screw.referenceTime_s : t0;
            for (const PositioningErrorPoint &q : rec.screw.interferometer)
                if (std::isfinite(q.referenceTime_s) && std::fabs(q.position_mm - position) < best) {
                    best = std::fabs(q.position_mm - position);
                    ref = q.referenceTime_s;
                }
            return ref;
        };
        std::map<long, double> refs;
        for (const ObservationFit *p : ip) {
            const long key = std::lround(p->position_mm * 10.0);
            if (!refs.count(key))
                refs[key] = refTime(p->position_mm);
        }
        std::map<std::string, const TimeSeries *> channels;
        for (const auto &c : rec.channelsByRole)
            channels[c.first] = &c.second;
        if (!drive.ambient_C.empty())
            channels["ambient"] = &drive.ambient_C;
        for (const auto &c : channels) {
            if (c.second->size() < 2)
                continue;
            std::vector<double> d, dx;
            for (const ObservationFit *p : ip) {
                const double v = c.second->at(p->t_s) - c.second->at(refs[std::lround(p->position_mm * 10.0)]);
                d.push_back(v);
                dx.push_back(v * p->position_mm);
            }
            loc.correlations.push_back({c.first, pearson(res, d)});
            loc.correlations.push_back({c.first + " x position", pearson(res, dx)});
        }
        std::sort(loc.correlations.begin(), loc.correlations.end(),
                  [](const ChannelCorrelation &a, const ChannelCorrelation &b) {
                      return std::fabs(a.correlation) > std::fabs(b.correlation);
                  });
    }
    return loc;
}

void ResidualLocator::locateTemperatures(const DiagnosisRecording &rec, const std::vector<ObservationFit> &points,
                                         double length_m, ResidualLocation &loc)
{
    loc.temperaturePoints = 0;
    loc.temperatureRms_K = 0.0;
    loc.temperatureBySensor.clear();
    loc.temperatureByScrewPart.clear();
    loc.temperatureByPhase.clear();
    std::map<int, Accumulator> sensor;
    std::map<std::string, Accumulator> phase;
    std::map<std::string, std::string> phaseOf;
    Accumulator parts[3], all;
    for (const ObservationFit &p : points) {
        if (!p.temperature)
            continue;
        const double r = p.predicted_um - p.measured_um;
        all.add(r);
        sensor[p.recording].add(r);
        const double u = length_m > 0 ? p.distance_m / length_m : 0.5;
        parts[std::clamp(static_cast<int>(u * 3.0), 0, 2)].add(r);
        // Phase per time (many profile points share a frame time).
        const std::string key = std::to_string(std::lround(p.t_s));
        auto it = phaseOf.find(key);
        if (it == phaseOf.end())
            it = phaseOf.emplace(key, phaseAt(rec.screw.drive, p.t_s)).first;
        phase[it->second].add(r);
    }
    if (!all.n)
        return;
    loc.temperaturePoints = all.n;
    loc.temperatureRms_K = all.group("all").rms_um;
    for (const auto &g : sensor) {
        const size_t k = static_cast<size_t>(g.first);
        loc.temperatureBySensor.push_back(
            g.second.group(k < rec.screwTemperatures.size() ? rec.screwTemperatures[k].sensor : "sensor " + std::to_string(k)));
    }
    const char *names[3] = {"fixed-end third of the screw", "middle third of the screw", "free-end third of the screw"};
    for (int k = 0; k < 3; ++k)
        if (parts[k].n)
            loc.temperatureByScrewPart.push_back(parts[k].group(names[k]));
    for (const auto &g : phase)
        loc.temperatureByPhase.push_back(g.second.group(g.first));
}

void ResidualLocator::checkPlausibility(const IdentificationResult &r, const IdentificationOptions &o,
                                        double drawingFixedEnd_mm, ResidualLocation &loc)
{
    const std::vector<PlausibilityFlag> flags = ParameterPlausibility::implausible(r, o, drawingFixedEnd_mm);
    loc.implausible.insert(loc.implausible.end(), flags.begin(), flags.end());
}

void ResidualLocator::summarise(ResidualLocation &loc)
{
    std::ostringstream s;
    auto worst = [](const std::vector<ResidualGroup> &g) {
        const ResidualGroup *w = nullptr;
        for (const ResidualGroup &x : g)
            if (!w || x.rms_um > w->rms_um)
                w = &x;
        return w;
    };
    double total = 0.0;
    int n = 0;
    for (const ResidualGroup &g : loc.byPhase) {
        total += g.rms_um * g.rms_um * g.count;
        n += g.count;
    }
    if (n)
        s << "interferometer residual RMS " << fmt(std::sqrt(total / n)) << " \u00b5m";
    if (const ResidualGroup *w = worst(loc.byPhase))
        s << "; largest in phase '" << w->label << "' (RMS " << fmt(w->rms_um) << " \u00b5m, mean " << fmt(w->mean_um)
          << " \u00b5m)";
    if (const ResidualGroup *w = worst(loc.byScrewPart))
        s << "; along the axis largest in the " << w->label << " (RMS " << fmt(w->rms_um) << " \u00b5m)";
    if (const ResidualGroup *w = worst(loc.byHour))
        s << "; in time largest at " << w->label << " (RMS " << fmt(w->rms_um) << " \u00b5m)";
    s << "; residuals " << (loc.white ? "look white" : "are NOT white") << " (lag-1 r = " << fmt(loc.lag1Autocorrelation)
      << ", Ljung-Box p = " << fmt(loc.ljungBoxP, 3) << ")";
    if (!loc.correlations.empty())
        s << "; strongest correlation with " << loc.correlations.front().channel << " (r = "
          << fmt(loc.correlations.front().correlation) << ")";
    if (loc.temperaturePoints) {
        s << "; screw temperature residual RMS " << fmt(loc.temperatureRms_K) << " K over " << loc.temperaturePoints
          << " points";
        if (const ResidualGroup *w = worst(loc.temperatureByScrewPart))
            s << ", largest in the " << w->label << " (model " << (w->mean_um > 0 ? "warmer" : "colder")
              << " than measured by " << fmt(std::fabs(w->mean_um)) << " K on average)";
        if (const ResidualGroup *w = worst(loc.temperatureByPhase))
            s << " and in phase '" << w->label << "' (RMS " << fmt(w->rms_um) << " K)";
        if (loc.temperatureByScrewPart.size() > 1) {
            s << " (mean model - measured by third:";
            for (const ResidualGroup &g : loc.temperatureByScrewPart)
                s << ' ' << g.label.substr(0, g.label.find(" third")) << ' ' << (g.mean_um >= 0 ? "+" : "")
                  << fmt(g.mean_um) << " K";
            s << ')';
        }
    }
    for (const PlausibilityFlag &f : loc.implausible)
        s << "; implausible: " << f.message;
    loc.summary = s.str();
}

bool ResidualLocator::isLocated(const ResidualLocation &location, std::string *why)
{
    const ChannelCorrelation *driver = nullptr;
    for (const ChannelCorrelation &c : location.correlations)
        if (c.channel.rfind("feed", 0) != 0 && c.channel != "time" && c.channel != "position" && std::fabs(c.correlation) >= 0.5 &&
            (!driver || std::fabs(c.correlation) > std::fabs(driver->correlation)))
            driver = &c;
    if (why) {
        std::string w;
        if (!location.white)
            w = "not white: lag-1 r = " + fixedText(location.lag1Autocorrelation, 2) + ", Ljung-Box p = " + fixedText(location.ljungBoxP, 3);
        if (driver)
            w += (w.empty() ? "" : "; ") + std::string("follows '") + driver->channel + "' (r = " + fixedText(driver->correlation, 2) + ")";
        *why = w;
    }
    return !location.white || driver != nullptr;
}

} // namespace driftlab

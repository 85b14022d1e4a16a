#include "Iso230Report.h"


#include <QJsonArray>
#include <QStringList>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

QJsonValue num(double v)
{
    return std::isfinite(v) ? QJsonValue(v) : QJsonValue(QJsonValue::Null);
}

QString dirName(int d)
{
    return d > 0 ? QStringLiteral("+") : d < 0 ? QStringLiteral("-") : QString();
}

QJsonArray runList(const std::vector<int> &runs)
{
    QJsonArray a;
    for (int r : runs)
        a.append(r);
    return a;
}

QJsonObject axisJson(const Iso230Axis &a)
{
    return QJsonObject{{QStringLiteral("B_um"), num(a.reversal_um)},
                       {QStringLiteral("B_mean_um"), num(a.meanReversal_um)},
                       {QStringLiteral("R_up_um"), num(a.repeatUp_um)},
                       {QStringLiteral("R_down_um"), num(a.repeatDown_um)},
                       {QStringLiteral("R_um"), num(a.repeat_um)},
                       {QStringLiteral("E_up_um"), num(a.systematicUp_um)},
                       {QStringLiteral("E_down_um"), num(a.systematicDown_um)},
                       {QStringLiteral("E_um"), num(a.systematic_um)},
                       {QStringLiteral("M_um"), num(a.meanRange_um)},
                       {QStringLiteral("A_up_um"), num(a.accuracyUp_um)},
                       {QStringLiteral("A_down_um"), num(a.accuracyDown_um)},
                       {QStringLiteral("A_um"), num(a.accuracy_um)}};
}

QJsonObject targetJson(const Iso230Target &t)
{
    return QJsonObject{{QStringLiteral("position_mm"), t.position_mm},
                       {QStringLiteral("n_up"), t.approachesUp},
                       {QStringLiteral("n_down"), t.approachesDown},
                       {QStringLiteral("mean_up_um"), num(t.meanUp_um)},
                       {QStringLiteral("mean_down_um"), num(t.meanDown_um)},
                       {QStringLiteral("mean_um"), num(t.mean_um)},
                       {QStringLiteral("B_um"), num(t.reversal_um)},
                       {QStringLiteral("s_up_um"), num(t.sUp_um)},
                       {QStringLiteral("s_down_um"), num(t.sDown_um)},
                       {QStringLiteral("R_up_um"), num(t.repeatUp_um)},
                       {QStringLiteral("R_down_um"), num(t.repeatDown_um)},
                       {QStringLiteral("R_um"), num(t.repeat_um)}};
}

QString um(double v)
{
    return std::isfinite(v) ? QString::number(v, 'f', 2) : QStringLiteral("-");
}

// Reading a toJson() document back: every field is required, an error names its path.
class Reader {
public:
    Reader(const QJsonObject &o, const QString &path) : m_o(o), m_path(path) {}

    QJsonValue value(const char *key) const
    {
        const QJsonValue v = m_o.value(QLatin1String(key));
        if (v.isUndefined())
            bad(key, "is missing");
        return v;
    }
    // A number; null is NaN (num() writes non-finite values as null).
    double number(const char *key) const
    {
        const QJsonValue v = value(key);
        if (v.isNull())
            return NAN;
        if (!v.isDouble())
            bad(key, "is not a number");
        return v.toDouble();
    }
    int integer(const char *key) const
    {
        const double v = number(key);
        if (!(std::fabs(v) < 1e9) || v != std::floor(v))
            bad(key, "is not an integer");
        return static_cast<int>(v);
    }
    bool flag(const char *key) const
    {
        const QJsonValue v = value(key);
        if (!v.isBool())
            bad(key, "is not true or false");
        return v.toBool();
    }
    QString text(const char *key) const
    {
        const QJsonValue v = value(key);
        if (!v.isString())
            bad(key, "is not a string");
        return v.toString();
    }
    QJsonArray array(const char *key) const
    {
        const QJsonValue v = value(key);
        if (!v.isArray())
            bad(key, "is not an array");
        return v.toArray();
    }
    Reader object(const char *key) const
    {
        const QJsonValue v = value(key);
        if (!v.isObject())
            bad(key, "is not an object");
        return Reader(v.toObject(), field(key));
    }
    Reader element(const char *key, const QJsonValue &v, int i) const
    {
        if (!v.isObject())
            bad(key, "holds a value that is not an object");
        return Reader(v.toObject(), QStringLiteral("%1[%2]").arg(field(key)).arg(i));
    }
    int direction(const char *key) const
    {
        const QString d = text(key);
        if (d == QLatin1String("+"))
            return 1;
        if (d == QLatin1String("-"))
            return -1;
        if (!d.isEmpty())
            bad(key, "is not \"+\", \"-\" or \"\"");
        return 0;
    }

private:
    QString field(const char *key) const { return m_path.isEmpty() ? QString::fromLatin1(key) : m_path + QLatin1Char('.') + QLatin1String(key); }
    [[noreturn]] void bad(const char *key, const char *what) const
    {
        throw std::invalid_argument(QStringLiteral("ISO 230 result: \"%1\" %2").arg(field(key), QLatin1String(what)).toStdString());
    }

    QJsonObject m_o;
    QString m_path;
};

Iso230Axis readAxis(const Reader &r)
{
    Iso230Axis a;
    a.reversal_um = r.number("B_um");
    a.meanReversal_um = r.number("B_mean_um");
    a.repeatUp_um = r.number("R_up_um");
    a.repeatDown_um = r.number("R_down_um");
    a.repeat_um = r.number("R_um");
    a.systematicUp_um = r.number("E_up_um");
    a.systematicDown_um = r.number("E_down_um");
    a.systematic_um = r.number("E_um");
    a.meanRange_um = r.number("M_um");
    a.accuracyUp_um = r.number("A_up_um");
    a.accuracyDown_um = r.number("A_down_um");
    a.accuracy_um = r.number("A_um");
    return a;
}

Iso230Target readTarget(const Reader &r)
{
    Iso230Target t;
    t.position_mm = r.number("position_mm");
    t.approachesUp = r.integer("n_up");
    t.approachesDown = r.integer("n_down");
    t.meanUp_um = r.number("mean_up_um");
    t.meanDown_um = r.number("mean_down_um");
    t.mean_um = r.number("mean_um");
    t.reversal_um = r.number("B_um");
    t.sUp_um = r.number("s_up_um");
    t.sDown_um = r.number("s_down_um");
    t.repeatUp_um = r.number("R_up_um");
    t.repeatDown_um = r.number("R_down_um");
    t.repeat_um = r.number("R_um");
    return t;
}

Iso230Test readTest(const Reader &r)
{
    Iso230Test t;
    for (const QJsonValue &v : r.array("runs"))
        t.runs.push_back(v.toInt());
    t.time_s = r.number("time_s");
    t.directionRecorded = r.flag("direction_recorded");
    t.bidirectional = r.flag("bidirectional");
    t.minApproaches = r.integer("approaches_min");
    t.axis = readAxis(r.object("axis"));
    const QJsonArray targets = r.array("targets");
    for (int i = 0; i < targets.size(); ++i)
        t.targets.push_back(readTarget(r.element("targets", targets[i], i)));
    for (const QJsonValue &n : r.array("notes"))
        t.notes.push_back(n.toString().toStdString());
    return t;
}

Iso230DriftSeries readSeries(const Reader &r)
{
    Iso230DriftSeries s;
    s.position_mm = r.number("position_mm");
    s.direction = r.direction("direction");
    s.maxDrift_um = r.number("max_drift_um");
    s.maxDriftTime_s = r.number("max_drift_time_s");
    s.maxDriftRun = r.integer("max_drift_run");
    s.slope_um_per_K = r.number("slope_um_per_K");
    s.offset_um = r.number("offset_um");
    s.correlation = r.number("correlation");
    const QJsonArray points = r.array("points");
    for (int i = 0; i < points.size(); ++i) {
        const Reader p = r.element("points", points[i], i);
        Iso230DriftPoint d;
        d.run = p.integer("run");
        d.time_s = p.number("time_s");
        d.drift_um = p.number("drift_um");
        d.temperatureChange_K = p.number("delta_T_K");
        s.points.push_back(d);
    }
    return s;
}

} // namespace

Iso230Report::Iso230Report(const Iso230Request &request, const QString &sessionName, int referenceRun,
                           std::vector<Iso230Test> tests, Iso230DriftSummary drift, QStringList leftOut)
    : m_request(request), m_name(sessionName), m_referenceRun(referenceRun), m_tests(std::move(tests)),
      m_drift(std::move(drift)), m_leftOut(std::move(leftOut))
{
    if (m_tests.empty())
        throw std::invalid_argument("Iso230Report: no ISO 230-2 test");
}

int Iso230Report::referenceTest() const
{
    for (std::size_t i = 0; i < m_tests.size(); ++i) {
        const std::vector<int> &runs = m_tests[i].runs;
        if (std::find(runs.begin(), runs.end(), m_referenceRun) != runs.end())
            return static_cast<int>(i);
    }
    return 0;
}

QJsonObject Iso230Report::toJson() const
{
    QJsonArray tests;
    for (const Iso230Test &t : m_tests) {
        QJsonArray targets, notes;
        for (const Iso230Target &target : t.targets)
            targets.append(targetJson(target));
        for (const std::string &n : t.notes)
            notes.append(QString::fromStdString(n));
        tests.append(QJsonObject{{QStringLiteral("runs"), runList(t.runs)},
                                 {QStringLiteral("time_s"), t.time_s},
                                 {QStringLiteral("direction_recorded"), t.directionRecorded},
                                 {QStringLiteral("bidirectional"), t.bidirectional},
                                 {QStringLiteral("approaches_min"), t.minApproaches},
                                 {QStringLiteral("axis"), axisJson(t.axis)},
                                 {QStringLiteral("targets"), targets},
                                 {QStringLiteral("notes"), notes}});
    }
    QJsonArray series;
    for (const Iso230DriftSeries &s : m_drift.series) {
        QJsonArray points;
        for (const Iso230DriftPoint &p : s.points)
            points.append(QJsonObject{{QStringLiteral("run"), p.run},
                                      {QStringLiteral("time_s"), p.time_s},
                                      {QStringLiteral("drift_um"), p.drift_um},
                                      {QStringLiteral("delta_T_K"), num(p.temperatureChange_K)}});
        series.append(QJsonObject{{QStringLiteral("position_mm"), s.position_mm},
                                  {QStringLiteral("direction"), dirName(s.direction)},
                                  {QStringLiteral("max_drift_um"), s.maxDrift_um},
                                  {QStringLiteral("max_drift_time_s"), num(s.maxDriftTime_s)},
                                  {QStringLiteral("max_drift_run"), s.maxDriftRun},
                                  {QStringLiteral("slope_um_per_K"), num(s.slope_um_per_K)},
                                  {QStringLiteral("offset_um"), num(s.offset_um)},
                                  {QStringLiteral("correlation"), num(s.correlation)},
                                  {QStringLiteral("points"), points}});
    }
    const Iso230DriftSummary &d = m_drift;
    const QJsonObject drift{{QStringLiteral("reference_run"), d.referenceRun},
                            {QStringLiteral("temperature_channel"),
                             d.withTemperature ? QJsonValue(m_request.temperatureChannel) : QJsonValue(QJsonValue::Null)},
                            {QStringLiteral("temperature_range_K"), num(d.temperatureRange_K)},
                            {QStringLiteral("max_drift_um"), d.maxDrift_um},
                            {QStringLiteral("max_drift_position_mm"), d.maxDriftPosition_mm},
                            {QStringLiteral("max_drift_direction"), dirName(d.maxDriftDirection)},
                            {QStringLiteral("max_drift_time_s"), num(d.maxDriftTime_s)},
                            {QStringLiteral("max_drift_run"), d.maxDriftRun},
                            {QStringLiteral("series"), series}};
    return QJsonObject{{QStringLiteral("schema_version"), kSchemaVersion},
                       {QStringLiteral("session"), static_cast<double>(m_request.session)},
                       {QStringLiteral("name"), m_name},
                       {QStringLiteral("standard"), QStringLiteral("ISO 230-2:2014 positioning evaluation; ISO 230-3-style thermal drift")},
                       {QStringLiteral("unit"), QStringLiteral("um")},
                       {QStringLiteral("reference_run"), m_referenceRun},
                       {QStringLiteral("runs_per_test"), m_request.runsPerTest},
                       {QStringLiteral("target_tolerance_mm"), m_request.targetTolerance_mm},
                       {QStringLiteral("tests"), tests},
                       {QStringLiteral("left_out"), QJsonArray::fromStringList(m_leftOut)},
                       {QStringLiteral("drift"), drift}};
}

Iso230Report Iso230Report::fromJson(const QJsonObject &json)
{
    const Reader r(json, QString());
    const int version = r.integer("schema_version");
    if (version < 1 || version > kSchemaVersion)
        throw std::invalid_argument(QStringLiteral("ISO 230 result: schema_version %1 is not one this version reads (1..%2)")
                                        .arg(version)
                                        .arg(kSchemaVersion)
                                        .toStdString());
    Iso230Request request;
    request.session = static_cast<qint64>(r.number("session"));
    request.runsPerTest = r.integer("runs_per_test");
    request.targetTolerance_mm = r.number("target_tolerance_mm");
    std::vector<Iso230Test> tests;
    const QJsonArray testArray = r.array("tests");
    for (int i = 0; i < testArray.size(); ++i)
        tests.push_back(readTest(r.element("tests", testArray[i], i)));
    const Reader d = r.object("drift");
    Iso230DriftSummary drift;
    drift.referenceRun = d.integer("reference_run");
    const QJsonValue channel = d.value("temperature_channel");
    drift.withTemperature = !channel.isNull();
    if (drift.withTemperature)
        request.temperatureChannel = d.text("temperature_channel");
    drift.temperatureRange_K = d.number("temperature_range_K");
    drift.maxDrift_um = d.number("max_drift_um");
    drift.maxDriftPosition_mm = d.number("max_drift_position_mm");
    drift.maxDriftDirection = d.direction("max_drift_direction");
    drift.maxDriftTime_s = d.number("max_drift_time_s");
    drift.maxDriftRun = d.integer("max_drift_run");
    const QJsonArray series = d.array("series");
    for (int i = 0; i < series.size(); ++i)
        drift.series.push_back(readSeries(d.element("series", series[i], i)));
    QStringList leftOut;
    for (const QJsonValue &n : r.array("left_out"))
        leftOut << n.toString();
    if (tests.empty())
        throw std::invalid_argument("ISO 230 result: \"tests\" is empty");
    return Iso230Report(request, r.text("name"), r.integer("reference_run"), std::move(tests), std::move(drift), std::move(leftOut));
}

QString Iso230Report::text() const
{
    QStringList lines;
    const Iso230Test *ref = &m_tests[static_cast<std::size_t>(referenceTest())];
    lines << QStringLiteral("session %1 '%2': %3 test(s) of %4 target(s), %5, at least %6 approach(es) per target and direction")
                 .arg(m_request.session)
                 .arg(m_name)
                 .arg(m_tests.size())
                 .arg(ref->targets.size())
                 .arg(ref->bidirectional ? QStringLiteral("bidirectional")
                                         : ref->directionRecorded ? QStringLiteral("one direction") : QStringLiteral("direction not recorded"))
                 .arg(ref->minApproaches);
    const Iso230Axis &a = ref->axis;
    lines << QStringLiteral("reference test (run %1, %2 h), um: B %3  B_mean %4  R+ %5  R- %6  R %7  E+ %8  E- %9  E %10  M %11  A+ %12  A- %13  A %14")
                 .arg(ref->runs.front())
                 .arg(ref->time_s / 3600.0, 0, 'f', 2)
                 .arg(um(a.reversal_um), um(a.meanReversal_um), um(a.repeatUp_um), um(a.repeatDown_um), um(a.repeat_um),
                      um(a.systematicUp_um), um(a.systematicDown_um), um(a.systematic_um), um(a.meanRange_um))
                 .arg(um(a.accuracyUp_um), um(a.accuracyDown_um), um(a.accuracy_um));
    for (const std::string &n : ref->notes)
        lines << QStringLiteral("  note: %1").arg(QString::fromStdString(n));
    for (const QString &n : m_leftOut)
        lines << QStringLiteral("  note: %1").arg(n);
    if (m_tests.size() > 1) {
        double loE = INFINITY, hiE = -INFINITY, loB = INFINITY, hiB = -INFINITY;
        for (const Iso230Test &t : m_tests) {
            const double e = t.bidirectional ? t.axis.systematic_um : t.axis.systematicUp_um;
            loE = std::min(loE, e);
            hiE = std::max(hiE, e);
            if (t.bidirectional) {
                loB = std::min(loB, t.axis.reversal_um);
                hiB = std::max(hiB, t.axis.reversal_um);
            }
        }
        lines << QStringLiteral("over the %1 tests: E %2 .. %3 um%4")
                     .arg(m_tests.size())
                     .arg(um(loE), um(hiE))
                     .arg(hiB >= loB ? QStringLiteral(", B %1 .. %2 um").arg(um(loB), um(hiB)) : QString());
    }
    const Iso230DriftSummary &d = m_drift;
    lines << QStringLiteral("largest drift from the reference: %1 um at %2 mm%3, %4 h (run %5)")
                 .arg(d.maxDrift_um, 0, 'f', 2)
                 .arg(d.maxDriftPosition_mm, 0, 'f', 1)
                 .arg(d.maxDriftDirection ? QStringLiteral(" (%1)").arg(dirName(d.maxDriftDirection)) : QString())
                 .arg(d.maxDriftTime_s / 3600.0, 0, 'f', 2)
                 .arg(d.maxDriftRun);
    if (d.withTemperature) {
        for (const Iso230DriftSeries &s : d.series) {
            if (s.position_mm == d.maxDriftPosition_mm && s.direction == d.maxDriftDirection)
                lines << QStringLiteral("against %1 (range %2 K): %3 um/K there (r = %4)")
                             .arg(m_request.temperatureChannel)
                             .arg(d.temperatureRange_K, 0, 'f', 2)
                             .arg(um(s.slope_um_per_K), std::isfinite(s.correlation) ? QString::number(s.correlation, 'f', 3) : QStringLiteral("-"));
        }
    }
    return lines.join(QLatin1Char('\n')) + QLatin1Char('\n');
}

} // namespace driftlab

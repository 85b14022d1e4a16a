#include "Iso230Report.h"

#include "UnitLabels.h"

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

// The numbers of an axis and a target and their JSON keys, written and read through one list.
template <class T>
struct NumberField {
    const char *key;
    double T::*member;
};

const NumberField<Iso230Axis> kAxisFields[] = {
    {"B_um", &Iso230Axis::reversal_um},         {"B_mean_um", &Iso230Axis::meanReversal_um},
    {"R_up_um", &Iso230Axis::repeatUp_um},      {"R_down_um", &Iso230Axis::repeatDown_um},
    {"R_um", &Iso230Axis::repeat_um},           {"E_up_um", &Iso230Axis::systematicUp_um},
    {"E_down_um", &Iso230Axis::systematicDown_um}, {"E_um", &Iso230Axis::systematic_um},
    {"M_um", &Iso230Axis::meanRange_um},        {"A_up_um", &Iso230Axis::accuracyUp_um},
    {"A_down_um", &Iso230Axis::accuracyDown_um}, {"A_um", &Iso230Axis::accuracy_um}};

const NumberField<Iso230Target> kTargetFields[] = {
    {"position_mm", &Iso230Target::position_mm}, {"mean_up_um", &Iso230Target::meanUp_um},
    {"mean_down_um", &Iso230Target::meanDown_um}, {"mean_um", &Iso230Target::mean_um},
    {"B_um", &Iso230Target::reversal_um},        {"s_up_um", &Iso230Target::sUp_um},
    {"s_down_um", &Iso230Target::sDown_um},      {"R_up_um", &Iso230Target::repeatUp_um},
    {"R_down_um", &Iso230Target::repeatDown_um}, {"R_um", &Iso230Target::repeat_um}};

const NumberField<Iso230DriftSeries> kSeriesFields[] = {
    {"position_mm", &Iso230DriftSeries::position_mm},       {"max_drift_um", &Iso230DriftSeries::maxDrift_um},
    {"max_drift_time_s", &Iso230DriftSeries::maxDriftTime_s}, {"slope_um_per_K", &Iso230DriftSeries::slope_um_per_K},
    {"offset_um", &Iso230DriftSeries::offset_um},           {"correlation", &Iso230DriftSeries::correlation}};

const NumberField<Iso230DriftSummary> kDriftFields[] = {
    {"temperature_range_K", &Iso230DriftSummary::temperatureRange_K},
    {"max_drift_um", &Iso230DriftSummary::maxDrift_um},
    {"max_drift_position_mm", &Iso230DriftSummary::maxDriftPosition_mm},
    {"max_drift_time_s", &Iso230DriftSummary::maxDriftTime_s}};

template <class T, std::size_t N>
QJsonObject numbersJson(const T &value, const NumberField<T> (&fields)[N])
{
    QJsonObject o;
    for (const NumberField<T> &f : fields)
        o.insert(QLatin1String(f.key), num(value.*(f.member)));
    return o;
}

QJsonObject axisJson(const Iso230Axis &a)
{
    return numbersJson(a, kAxisFields);
}

QJsonObject targetJson(const Iso230Target &t)
{
    QJsonObject o = numbersJson(t, kTargetFields);
    o.insert(QStringLiteral("n_up"), t.approachesUp);
    o.insert(QStringLiteral("n_down"), t.approachesDown);
    return o;
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
    // The member `key`, refused unless (v.*is)().
    QJsonValue typed(const char *key, bool (QJsonValue::*is)() const, const char *isNot) const
    {
        const QJsonValue v = value(key);
        if (!(v.*is)())
            bad(key, isNot);
        return v;
    }
    bool flag(const char *key) const { return typed(key, &QJsonValue::isBool, "is not true or false").toBool(); }
    QString text(const char *key) const { return typed(key, &QJsonValue::isString, "is not a string").toString(); }
    QJsonArray array(const char *key) const { return typed(key, &QJsonValue::isArray, "is not an array").toArray(); }
    Reader object(const char *key) const
    {
        return Reader(typed(key, &QJsonValue::isObject, "is not an object").toObject(), field(key));
    }
    // Reads the numbers of `fields` into `value`.
    template <class T, std::size_t N>
    void numbers(T &value, const NumberField<T> (&fields)[N]) const
    {
        for (const NumberField<T> &f : fields)
            value.*(f.member) = number(f.key);
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

Iso230Target readTarget(const Reader &r)
{
    Iso230Target t;
    r.numbers(t, kTargetFields);
    t.approachesUp = r.integer("n_up");
    t.approachesDown = r.integer("n_down");
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
    r.object("axis").numbers(t.axis, kAxisFields);
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
    r.numbers(s, kSeriesFields);
    s.direction = r.direction("direction");
    s.maxDriftRun = r.integer("max_drift_run");
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
        QJsonObject o = numbersJson(s, kSeriesFields);
        o.insert(QStringLiteral("direction"), dirName(s.direction));
        o.insert(QStringLiteral("max_drift_run"), s.maxDriftRun);
        o.insert(QStringLiteral("points"), points);
        series.append(o);
    }
    const Iso230DriftSummary &d = m_drift;
    QJsonObject drift = numbersJson(d, kDriftFields);
    drift.insert(QStringLiteral("reference_run"), d.referenceRun);
    drift.insert(QStringLiteral("temperature_channel"),
                 d.withTemperature ? QJsonValue(m_request.temperatureChannel) : QJsonValue(QJsonValue::Null));
    drift.insert(QStringLiteral("max_drift_direction"), dirName(d.maxDriftDirection));
    drift.insert(QStringLiteral("max_drift_run"), d.maxDriftRun);
    drift.insert(QStringLiteral("series"), series);
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
    d.numbers(drift, kDriftFields);
    drift.maxDriftDirection = d.direction("max_drift_direction");
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
    lines << QStringLiteral("reference test (run %1, %2), \u00b5m: B %3  B_mean %4  R+ %5  R- %6  R %7  E+ %8  E- %9  E %10  M %11  A+ %12  A- %13  A %14")
                 .arg(ref->runs.front())
                 .arg(UnitLabels::clock(ref->time_s))
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
        lines << QStringLiteral("over the %1 tests: E %2 .. %3 \u00b5m%4")
                     .arg(m_tests.size())
                     .arg(um(loE), um(hiE))
                     .arg(hiB >= loB ? QStringLiteral(", B %1 .. %2 \u00b5m").arg(um(loB), um(hiB)) : QString());
    }
    const Iso230DriftSummary &d = m_drift;
    lines << QStringLiteral("largest drift from the reference: %1 \u00b5m at %2 mm%3, %4 (run %5)")
                 .arg(d.maxDrift_um, 0, 'f', 2)
                 .arg(d.maxDriftPosition_mm, 0, 'f', 1)
                 .arg(d.maxDriftDirection ? QStringLiteral(" (%1)").arg(dirName(d.maxDriftDirection)) : QString())
                 .arg(UnitLabels::clock(d.maxDriftTime_s))
                 .arg(d.maxDriftRun);
    if (d.withTemperature) {
        for (const Iso230DriftSeries &s : d.series) {
            if (s.position_mm == d.maxDriftPosition_mm && s.direction == d.maxDriftDirection)
                lines << QStringLiteral("against %1 (range %2 K): %3 \u00b5m/K there (r = %4)")
                             .arg(m_request.temperatureChannel)
                             .arg(d.temperatureRange_K, 0, 'f', 2)
                             .arg(um(s.slope_um_per_K), std::isfinite(s.correlation) ? QString::number(s.correlation, 'f', 3) : QStringLiteral("-"));
        }
    }
    return lines.join(QLatin1Char('\n')) + QLatin1Char('\n');
}

} // namespace driftlab

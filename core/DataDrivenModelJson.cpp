#include "DataDrivenModelJson.h"

#include "DataDrivenPredictor.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QSaveFile>

#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

QJsonObject channel(const ModelChannel &c)
{
    QJsonObject o{{QStringLiteral("channel"), QString::fromStdString(c.id)},
                  {QStringLiteral("unit"), QString::fromStdString(c.unit)},
                  {QStringLiteral("kind"), QString::fromStdString(c.kind)}};
    if (std::isfinite(c.trainingMin) && std::isfinite(c.trainingMax)) {
        o.insert(QStringLiteral("training_min"), c.trainingMin);
        o.insert(QStringLiteral("training_max"), c.trainingMax);
    }
    return o;
}

// Reads fields with messages naming source and path.
class Reader {
public:
    explicit Reader(const QString &source) : m_source(source) {}
    [[noreturn]] void fail(const QString &path, const QString &what) const
    {
        throw std::invalid_argument(QStringLiteral("%1: %2: %3").arg(m_source, path, what).toStdString());
    }
    QJsonValue member(const QJsonObject &o, const QString &path, const QString &key) const
    {
        if (!o.contains(key))
            fail(path.isEmpty() ? key : path + QLatin1Char('.') + key, QStringLiteral("missing"));
        return o.value(key);
    }
    // The member `key`, refused unless (v.*is)(): "expected <what>".
    QJsonValue typed(const QJsonObject &o, const QString &path, const QString &key, bool (QJsonValue::*is)() const,
                     const char *what) const
    {
        const QJsonValue v = member(o, path, key);
        if (!(v.*is)())
            fail(join(path, key), QStringLiteral("expected %1").arg(QLatin1String(what)));
        return v;
    }
    QString string(const QJsonObject &o, const QString &path, const QString &key) const
    {
        return typed(o, path, key, &QJsonValue::isString, "a string").toString();
    }
    double number(const QJsonObject &o, const QString &path, const QString &key) const
    {
        const double v = typed(o, path, key, &QJsonValue::isDouble, "a number").toDouble();
        if (!std::isfinite(v))
            fail(join(path, key), QStringLiteral("expected a number"));
        return v;
    }
    double optionalNumber(const QJsonObject &o, const QString &path, const QString &key, double fallback) const
    {
        return o.contains(key) ? number(o, path, key) : fallback;
    }
    QJsonObject object(const QJsonObject &o, const QString &path, const QString &key) const
    {
        return typed(o, path, key, &QJsonValue::isObject, "an object").toObject();
    }
    QJsonArray array(const QJsonObject &o, const QString &path, const QString &key) const
    {
        return typed(o, path, key, &QJsonValue::isArray, "an array").toArray();
    }
    std::vector<double> numberArray(const QJsonObject &o, const QString &path, const QString &key, bool allowNull) const
    {
        std::vector<double> out;
        for (const QJsonValue &v : array(o, path, key)) {
            if (allowNull && v.isNull()) {
                out.push_back(std::nan(""));
                continue;
            }
            if (!v.isDouble() || !std::isfinite(v.toDouble()))
                fail(join(path, key), QStringLiteral("expected an array of numbers"));
            out.push_back(v.toDouble());
        }
        return out;
    }
    int index(const QJsonObject &o, const QString &path, const QString &key, int count) const
    {
        const double v = number(o, path, key);
        if (v != std::floor(v) || v < 0 || v >= count)
            fail(join(path, key), QStringLiteral("expected an input index 0..%1, got %2").arg(count - 1).arg(v));
        return static_cast<int>(v);
    }
    static QString join(const QString &path, const QString &key) { return path.isEmpty() ? key : path + QLatin1Char('.') + key; }

private:
    QString m_source;
};

} // namespace

QJsonObject DataDrivenModelJson::toJson(const DataDrivenModel &m)
{
    QJsonArray inputs;
    for (const ModelChannel &c : m.inputs)
        inputs.append(channel(c));
    QJsonObject o{{QStringLiteral("format"), QStringLiteral("driftlab-model")},
                  {QStringLiteral("version"), m.usesRises() ? kVersion : kOldestVersion},
                  {QStringLiteral("model"), QString::fromStdString(m.kind)},
                  {QStringLiteral("target"), channel(m.target)},
                  {QStringLiteral("inputs"), inputs},
                  {QStringLiteral("sample_period_s"), m.samplePeriod_s}};
    if (m.linearLag()) {
        QJsonArray terms;
        for (const ModelTerm &t : m.terms) {
            QJsonObject term{{QStringLiteral("input"), t.input},
                                     {QStringLiteral("channel"), QString::fromStdString(m.inputs[static_cast<std::size_t>(t.input)].id)},
                                     {QStringLiteral("power"), t.power},
                                     {QStringLiteral("offset"), t.offset},
                                     {QStringLiteral("scale"), t.scale},
                                     {QStringLiteral("lags_s"), DataDrivenModelJson::numbers(t.lags_s)},
                                     {QStringLiteral("coefficients"), DataDrivenModelJson::numbers(t.coefficients)},
                                     {QStringLiteral("standard_errors"), DataDrivenModelJson::numbers(t.standardErrors)}};
            if (t.rise)
                term.insert(QStringLiteral("rise"), true);
            terms.append(term);
        }
        if (m.usesRises())
            o.insert(QStringLiteral("reference"), QJsonObject{{QStringLiteral("kind"), QString::fromStdString(m.reference.kind)},
                                                              {QStringLiteral("window_s"), m.reference.window_s}});
        o.insert(QStringLiteral("linear"), QJsonObject{{QStringLiteral("intercept"), m.intercept},
                                                       {QStringLiteral("intercept_standard_error"), m.interceptStandardError},
                                                       {QStringLiteral("terms"), terms}});
        o.insert(QStringLiteral("evaluation"),
                 QStringLiteral("y = intercept + sum over terms and lags of coefficient * x; feature f = ((u - offset) / scale)^power "
                                "of input u; x = f for a lag of 0 s, else x += (1 - exp(-dt / tau)) (f - x) each sample with the "
                                "actual step dt; x starts at f of the first sample (equilibrium); a term with rise: true reads u - r, "
                                "r = the input at the run's start (reference.kind start; with window_s > 0 the running mean of the "
                                "samples after a positive step within window_s of the start), captured by the evaluator"));
    } else if (m.kind == "exp") {
        const ExponentialLaw &e = m.exponential;
        QJsonObject law{{QStringLiteral("drive"), e.drive},
                        {QStringLiteral("on_threshold"), e.onThreshold},
                        {QStringLiteral("reference_drive"), e.referenceDrive},
                        {QStringLiteral("steady_state"), e.steadyState},
                        {QStringLiteral("exponent"), e.exponent},
                        {QStringLiteral("tau_warm_s"), e.tauWarm_s},
                        {QStringLiteral("tau_cool_s"), e.tauCool_s},
                        {QStringLiteral("baseline"), e.baseline}};
        if (e.expansion_per_K > 0 && e.length_m > 0) {
            law.insert(QStringLiteral("expansion_per_K"), e.expansion_per_K);
            law.insert(QStringLiteral("length_m"), e.length_m);
        }
        o.insert(QStringLiteral("exponential"), law);
        o.insert(QStringLiteral("evaluation"),
                 QStringLiteral("v = |drive|; on = v > on_threshold; goal = on ? steady_state (v / reference_drive)^exponent : 0; "
                                "x += (1 - exp(-dt / (on ? tau_warm_s : tau_cool_s))) (goal - x), x = 0 at the start; "
                                "y = baseline + x; virtual screw temperature rise = x 1e-6 / (expansion_per_K length_m) K"));
    } else if (m.kind == "synthetic") {
        const SyntheticLaw &s = m.synthetic;
        QJsonArray temps;
        for (int i : s.temperatures)
            temps.append(i);
        o.insert(QStringLiteral("synthetic"), QJsonObject{{QStringLiteral("temperatures"), temps},
                                                          {QStringLiteral("a"), s.a},
                                                          {QStringLiteral("b_perK"), s.b_perK},
                                                          {QStringLiteral("c"), s.c},
                                                          {QStringLiteral("t0_C"), s.t0_C},
                                                          {QStringLiteral("p0_mm"), s.p0_mm},
                                                          {QStringLiteral("p_ref_mm"), s.pRef_mm}});
        o.insert(QStringLiteral("evaluation"),
                 QStringLiteral("T = mean of the temperature inputs; g = c + a (exp(b_perK (T - t0_C)) - 1); "
                                "y(P) = g (P - p0_mm) / (p_ref_mm - p0_mm) at axis position P (P = p_ref_mm for a displacement target)"));
    }
    if (std::isfinite(m.predictionSigma))
        o.insert(QStringLiteral("prediction_uncertainty"),
                 QJsonObject{{QStringLiteral("sigma"), m.predictionSigma},
                             {QStringLiteral("unit"), QString::fromStdString(m.target.unit)},
                             {QStringLiteral("basis"), QStringLiteral("1 sigma of every prediction: the RMS of the out-of-fold "
                                                                      "prediction errors of the fit's nested cross-validation")}});
    if (!m.without.empty())
        o.insert(QStringLiteral("without"), QString::fromStdString(m.without));
    if (!m.reduced.empty()) {
        QJsonArray reduced;
        for (const DataDrivenModel &r : m.reduced)
            reduced.append(toJson(r));
        o.insert(QStringLiteral("reduced_models"), reduced);
    }
    return o;
}

DataDrivenModel DataDrivenModelJson::fromJson(const QJsonObject &o, const QString &source)
{
    const Reader r(source);
    if (r.string(o, QString(), QStringLiteral("format")) != QLatin1String("driftlab-model"))
        r.fail(QStringLiteral("format"), QStringLiteral("expected \"driftlab-model\""));
    const double version = r.number(o, QString(), QStringLiteral("version"));
    if (version != kVersion && version != kOldestVersion)
        r.fail(QStringLiteral("version"), QStringLiteral("version %1 is not readable by this DriftLab (reads %2 and %3)")
                                              .arg(version)
                                              .arg(kOldestVersion)
                                              .arg(kVersion));
    DataDrivenModel m;
    m.kind = r.string(o, QString(), QStringLiteral("model")).toStdString();
    auto readChannel = [&](const QJsonObject &c, const QString &path) {
        ModelChannel m;
        m.id = r.string(c, path, QStringLiteral("channel")).toStdString();
        m.unit = c.value(QStringLiteral("unit")).toString().toStdString();
        m.kind = c.value(QStringLiteral("kind")).toString().toStdString();
        if (c.contains(QStringLiteral("training_min")) || c.contains(QStringLiteral("training_max"))) {
            m.trainingMin = r.number(c, path, QStringLiteral("training_min"));
            m.trainingMax = r.number(c, path, QStringLiteral("training_max"));
            if (m.trainingMax < m.trainingMin)
                r.fail(path + QStringLiteral(".training_max"), QStringLiteral("below training_min"));
        }
        return m;
    };
    m.target = readChannel(r.object(o, QString(), QStringLiteral("target")), QStringLiteral("target"));
    const QJsonArray inputs = r.array(o, QString(), QStringLiteral("inputs"));
    for (int i = 0; i < inputs.size(); ++i) {
        const QString path = QStringLiteral("inputs[%1]").arg(i);
        if (!inputs[i].isObject())
            r.fail(path, QStringLiteral("expected an object"));
        m.inputs.push_back(readChannel(inputs[i].toObject(), path));
    }
    m.samplePeriod_s = r.optionalNumber(o, QString(), QStringLiteral("sample_period_s"), 0.0);
    const int n = static_cast<int>(m.inputs.size());
    if (m.linearLag()) {
        if (o.contains(QStringLiteral("reference"))) {
            const QJsonObject ref = r.object(o, QString(), QStringLiteral("reference"));
            m.reference.kind = r.string(ref, QStringLiteral("reference"), QStringLiteral("kind")).toStdString();
            if (m.reference.kind != "absolute" && m.reference.kind != "start")
                r.fail(QStringLiteral("reference.kind"), QStringLiteral("expected \"absolute\" or \"start\""));
            m.reference.window_s = r.optionalNumber(ref, QStringLiteral("reference"), QStringLiteral("window_s"), 0.0);
            if (m.reference.window_s < 0)
                r.fail(QStringLiteral("reference.window_s"), QStringLiteral("expected a number >= 0"));
        }
        const QJsonObject lin = r.object(o, QString(), QStringLiteral("linear"));
        m.intercept = r.number(lin, QStringLiteral("linear"), QStringLiteral("intercept"));
        m.interceptStandardError = r.optionalNumber(lin, QStringLiteral("linear"), QStringLiteral("intercept_standard_error"), 0.0);
        const QJsonArray terms = r.array(lin, QStringLiteral("linear"), QStringLiteral("terms"));
        for (int i = 0; i < terms.size(); ++i) {
            const QString path = QStringLiteral("linear.terms[%1]").arg(i);
            if (!terms[i].isObject())
                r.fail(path, QStringLiteral("expected an object"));
            const QJsonObject t = terms[i].toObject();
            ModelTerm term;
            term.input = r.index(t, path, QStringLiteral("input"), n);
            const double power = r.optionalNumber(t, path, QStringLiteral("power"), 1.0);
            if (power != 1.0 && power != 2.0)
                r.fail(path + QStringLiteral(".power"), QStringLiteral("expected 1 or 2"));
            term.power = static_cast<int>(power);
            term.offset = r.optionalNumber(t, path, QStringLiteral("offset"), 0.0);
            term.scale = r.optionalNumber(t, path, QStringLiteral("scale"), 1.0);
            if (!(term.scale > 0))
                r.fail(path + QStringLiteral(".scale"), QStringLiteral("expected a positive number"));
            term.lags_s = r.numberArray(t, path, QStringLiteral("lags_s"), false);
            for (double tau : term.lags_s)
                if (tau < 0)
                    r.fail(path + QStringLiteral(".lags_s"), QStringLiteral("expected time constants >= 0"));
            term.coefficients = r.numberArray(t, path, QStringLiteral("coefficients"), false);
            if (term.lags_s.empty() || term.coefficients.size() != term.lags_s.size())
                r.fail(path + QStringLiteral(".coefficients"), QStringLiteral("expected one coefficient per lag"));
            if (t.contains(QStringLiteral("rise"))) {
                if (!t.value(QStringLiteral("rise")).isBool())
                    r.fail(path + QStringLiteral(".rise"), QStringLiteral("expected true or false"));
                if (version < 2)
                    r.fail(path + QStringLiteral(".rise"), QStringLiteral("needs version 2"));
                term.rise = t.value(QStringLiteral("rise")).toBool();
            }
            if (t.contains(QStringLiteral("standard_errors")))
                term.standardErrors = r.numberArray(t, path, QStringLiteral("standard_errors"), true);
            m.terms.push_back(term);
        }
    } else if (m.kind == "exp") {
        const QString path = QStringLiteral("exponential");
        const QJsonObject e = r.object(o, QString(), path);
        ExponentialLaw &law = m.exponential;
        law.drive = r.index(e, path, QStringLiteral("drive"), n);
        law.onThreshold = r.number(e, path, QStringLiteral("on_threshold"));
        law.referenceDrive = r.number(e, path, QStringLiteral("reference_drive"));
        law.steadyState = r.number(e, path, QStringLiteral("steady_state"));
        law.exponent = r.number(e, path, QStringLiteral("exponent"));
        law.tauWarm_s = r.number(e, path, QStringLiteral("tau_warm_s"));
        law.tauCool_s = r.number(e, path, QStringLiteral("tau_cool_s"));
        law.baseline = r.number(e, path, QStringLiteral("baseline"));
        law.expansion_per_K = r.optionalNumber(e, path, QStringLiteral("expansion_per_K"), 0.0);
        law.length_m = r.optionalNumber(e, path, QStringLiteral("length_m"), 0.0);
        if (!(law.referenceDrive > 0))
            r.fail(path + QStringLiteral(".reference_drive"), QStringLiteral("expected a positive number"));
        if (!(law.tauWarm_s > 0) || !(law.tauCool_s > 0))
            r.fail(path, QStringLiteral("time constants must be positive"));
    } else if (m.kind == "synthetic") {
        const QString path = QStringLiteral("synthetic");
        const QJsonObject s = r.object(o, QString(), path);
        SyntheticLaw &law = m.synthetic;
        const QJsonArray temps = r.array(s, path, QStringLiteral("temperatures"));
        for (const QJsonValue &v : temps) {
            const double i = v.toDouble(-1);
            if (!v.isDouble() || i != std::floor(i) || i < 0 || i >= n)
                r.fail(path + QStringLiteral(".temperatures"), QStringLiteral("expected input indices 0..%1").arg(n - 1));
            law.temperatures.push_back(static_cast<int>(i));
        }
        if (law.temperatures.empty())
            r.fail(path + QStringLiteral(".temperatures"), QStringLiteral("expected at least one input index"));
        law.a = r.number(s, path, QStringLiteral("a"));
        law.b_perK = r.number(s, path, QStringLiteral("b_perK"));
        law.c = r.number(s, path, QStringLiteral("c"));
        law.t0_C = r.number(s, path, QStringLiteral("t0_C"));
        law.p0_mm = r.number(s, path, QStringLiteral("p0_mm"));
        law.pRef_mm = r.number(s, path, QStringLiteral("p_ref_mm"));
        if (law.p0_mm == law.pRef_mm)
            r.fail(path + QStringLiteral(".p_ref_mm"), QStringLiteral("must differ from p0_mm"));
    } else {
        r.fail(QStringLiteral("model"),
               QStringLiteral("unknown model '%1' (known: mean, mlr, ridge, lagridge, dynamic, exp, synthetic)").arg(QString::fromStdString(m.kind)));
    }
    if (o.contains(QStringLiteral("prediction_uncertainty"))) {
        const QJsonObject u = r.object(o, QString(), QStringLiteral("prediction_uncertainty"));
        m.predictionSigma = r.number(u, QStringLiteral("prediction_uncertainty"), QStringLiteral("sigma"));
        if (!(m.predictionSigma >= 0))
            r.fail(QStringLiteral("prediction_uncertainty.sigma"), QStringLiteral("expected a number >= 0"));
    }
    if (o.contains(QStringLiteral("without")))
        m.without = r.string(o, QString(), QStringLiteral("without")).toStdString();
    if (o.contains(QStringLiteral("reduced_models"))) {
        if (!m.without.empty())
            r.fail(QStringLiteral("reduced_models"), QStringLiteral("a reduced model has no reduced models of its own"));
        const QJsonArray reduced = r.array(o, QString(), QStringLiteral("reduced_models"));
        for (int i = 0; i < reduced.size(); ++i) {
            const QString path = QStringLiteral("reduced_models[%1]").arg(i);
            if (!reduced[i].isObject())
                r.fail(path, QStringLiteral("expected an object"));
            const QJsonObject ro = reduced[i].toObject();
            if (ro.contains(QStringLiteral("reduced_models")))
                r.fail(path + QStringLiteral(".reduced_models"), QStringLiteral("a reduced model has no reduced models of its own"));
            DataDrivenModel rm = fromJson(ro, source + QStringLiteral(" ") + path);
            if (rm.without.empty() || m.inputIndex(rm.without) < 0)
                r.fail(path + QStringLiteral(".without"), QStringLiteral("expected the id of one of the model's inputs"));
            m.reduced.push_back(std::move(rm));
        }
    }
    try {
        DataDrivenPredictor check(m);
    } catch (const std::invalid_argument &e) {
        throw std::invalid_argument(QStringLiteral("%1: %2").arg(source, QString::fromUtf8(e.what())).toStdString());
    }
    return m;
}

QJsonObject DataDrivenModelJson::object(const QByteArray &bytes, const QString &source)
{
    QJsonParseError error;
    const QJsonDocument doc = QJsonDocument::fromJson(bytes, &error);
    if (error.error != QJsonParseError::NoError)
        throw std::invalid_argument(
            QStringLiteral("%1: not JSON at byte %2: %3").arg(source).arg(error.offset).arg(error.errorString()).toStdString());
    if (!doc.isObject())
        throw std::invalid_argument(QStringLiteral("%1: expected a JSON object").arg(source).toStdString());
    return doc.object();
}

DataDrivenModel DataDrivenModelJson::parse(const QByteArray &bytes, const QString &source, QJsonObject *document)
{
    const QJsonObject o = object(bytes, source);
    if (document)
        *document = o;
    return fromJson(o, source);
}

DataDrivenModel DataDrivenModelJson::read(const QString &path, QJsonObject *document)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw std::invalid_argument(QStringLiteral("%1: cannot read: %2").arg(path, f.errorString()).toStdString());
    return parse(f.readAll(), path, document);
}

QJsonArray DataDrivenModelJson::numbers(const std::vector<double> &v)
{
    QJsonArray a;
    for (double x : v)
        a.append(std::isfinite(x) ? QJsonValue(x) : QJsonValue());
    return a;
}

void DataDrivenModelJson::write(const QJsonObject &document, const QString &path)
{
    QSaveFile f(path);
    if (!f.open(QIODevice::WriteOnly))
        throw std::runtime_error(QStringLiteral("%1: cannot write: %2").arg(path, f.errorString()).toStdString());
    // flush() first: QSaveFile::commit() does not see a buffered write that fails on close
    // (a full disk), and would keep an empty file.
    const QByteArray bytes = QJsonDocument(document).toJson(QJsonDocument::Indented);
    if (f.write(bytes) != bytes.size() || !f.flush() || !f.commit())
        throw std::runtime_error(QStringLiteral("%1: cannot write: %2").arg(path, f.errorString()).toStdString());
}

} // namespace driftlab

#include "DataDrivenPredictor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace driftlab {

namespace {

void require(bool ok, const std::string &what)
{
    if (!ok)
        throw std::invalid_argument("data-driven model: " + what);
}

} // namespace

DataDrivenPredictor::DataDrivenPredictor(const DataDrivenModel &model) : m_model(model)
{
    const int n = static_cast<int>(model.inputs.size());
    m_ref.assign(model.inputs.size(), 0.0);
    m_refSum.assign(model.inputs.size(), 0.0);
    m_rises = model.usesRises();
    require(model.reference.kind == "absolute" || model.reference.kind == "start",
            "reference.kind must be absolute or start");
    require(std::isfinite(model.reference.window_s) && model.reference.window_s >= 0, "reference.window_s must be >= 0");
    if (model.linearLag()) {
        for (std::size_t i = 0; i < model.terms.size(); ++i) {
            const ModelTerm &t = model.terms[i];
            const std::string where = "terms[" + std::to_string(i) + "]";
            require(t.input >= 0 && t.input < n, where + ".input out of range");
            require(t.power == 1 || t.power == 2, where + ".power must be 1 or 2");
            require(std::isfinite(t.scale) && t.scale > 0, where + ".scale must be positive");
            require(!t.lags_s.empty() && t.lags_s.size() == t.coefficients.size(),
                    where + ": one coefficient per lag");
            for (double tau : t.lags_s)
                require(std::isfinite(tau) && tau >= 0, where + ".lags_s must be >= 0");
            m_first.push_back(m_states.size());
            m_states.resize(m_states.size() + t.lags_s.size(), 0.0);
        }
    } else if (model.kind == "exp") {
        const ExponentialLaw &e = model.exponential;
        require(e.drive >= 0 && e.drive < n, "exponential.drive out of range");
        require(e.tauWarm_s > 0 && e.tauCool_s > 0, "exponential time constants must be positive");
        require(e.referenceDrive > 0, "exponential.reference_drive must be positive");
    } else if (model.kind == "synthetic") {
        const SyntheticLaw &s = model.synthetic;
        require(!s.temperatures.empty(), "synthetic needs at least one temperature input");
        for (int i : s.temperatures)
            require(i >= 0 && i < n, "synthetic temperature input out of range");
        require(s.pRef_mm != s.p0_mm, "synthetic reference position equals P0");
    } else {
        throw std::invalid_argument("data-driven model: unknown kind '" + model.kind + "'");
    }
}

double DataDrivenPredictor::lagStep(double x, double u, double dt_s, double tau_s)
{
    if (tau_s <= 0)
        return u;
    return x + (1.0 - std::exp(-dt_s / tau_s)) * (u - x);
}

std::vector<double> DataDrivenPredictor::lagSeries(const std::vector<double> &t, const std::vector<double> &u,
                                                  double tau_s)
{
    std::vector<double> x(u.size());
    if (tau_s <= 0 || u.empty()) {
        std::copy(u.begin(), u.end(), x.begin());
        return x;
    }
    // lagStep's update with its factor reused while the step repeats (a regular grid).
    double dt = std::numeric_limits<double>::quiet_NaN(), gain = 0.0;
    x[0] = u[0];
    for (std::size_t k = 1; k < u.size(); ++k) {
        const double step = t[k] - t[k - 1];
        if (step != dt) {
            dt = step;
            gain = 1.0 - std::exp(-dt / tau_s);
        }
        x[k] = x[k - 1] + gain * (u[k] - x[k - 1]);
    }
    return x;
}

std::vector<double> DataDrivenPredictor::referenceSeries(const TemperatureReference &reference,
                                                        const std::vector<double> &t, const std::vector<double> &u)
{
    std::vector<double> r(u.size(), 0.0);
    if (reference.kind != "start" || u.empty())
        return r;
    double sum = u[0], count = 1.0, elapsed = 0.0;
    r[0] = u[0];
    for (std::size_t k = 1; k < u.size(); ++k) {
        const double dt = t[k] - t[k - 1];
        elapsed += dt;
        if (reference.window_s > 0 && dt > 0 && elapsed <= reference.window_s) {
            sum += u[k];
            count += 1.0;
        }
        r[k] = sum / count;
    }
    return r;
}

void DataDrivenPredictor::captureReference(double dt_s, const double *inputs)
{
    if (!m_rises || m_model.reference.kind != "start")
        return;
    m_elapsed_s += dt_s;
    if (!(m_model.reference.window_s > 0 && dt_s > 0 && m_elapsed_s <= m_model.reference.window_s))
        return;
    m_refCount += 1.0;
    for (std::size_t i = 0; i < m_ref.size(); ++i) {
        m_refSum[i] += inputs[i];
        m_ref[i] = m_refSum[i] / m_refCount;
    }
}

double DataDrivenPredictor::termFeature(const ModelTerm &term, const double *inputs) const
{
    const double u = inputs[term.input];
    return feature(term, term.rise ? u - m_ref[static_cast<std::size_t>(term.input)] : u);
}

double DataDrivenPredictor::feature(const ModelTerm &term, double u)
{
    const double z = (u - term.offset) / term.scale;
    return term.power == 2 ? z * z : z;
}

double DataDrivenPredictor::linearOutput() const
{
    double y = m_model.intercept;
    for (std::size_t i = 0; i < m_model.terms.size(); ++i) {
        const ModelTerm &t = m_model.terms[i];
        for (std::size_t l = 0; l < t.coefficients.size(); ++l)
            y += t.coefficients[l] * m_states[m_first[i] + l];
    }
    return y;
}

double DataDrivenPredictor::characteristicTemperature(const double *inputs) const
{
    double sum = 0.0;
    for (int i : m_model.synthetic.temperatures)
        sum += inputs[i];
    return sum / static_cast<double>(m_model.synthetic.temperatures.size());
}

void DataDrivenPredictor::reset(const double *inputs)
{
    m_started = true;
    m_expState = 0.0;
    m_elapsed_s = 0.0;
    m_refCount = 1.0;
    const bool start = m_rises && m_model.reference.kind == "start";
    for (std::size_t i = 0; i < m_ref.size(); ++i)
        m_ref[i] = m_refSum[i] = start ? inputs[i] : 0.0;
    for (std::size_t i = 0; i < m_model.terms.size(); ++i) {
        const ModelTerm &t = m_model.terms[i];
        const double f = termFeature(t, inputs);
        for (std::size_t l = 0; l < t.lags_s.size(); ++l)
            m_states[m_first[i] + l] = f;
    }
}

double DataDrivenPredictor::step(double dt_s, const double *inputs)
{
    if (!m_started)
        reset(inputs);
    if (m_model.linearLag()) {
        captureReference(dt_s, inputs);
        for (std::size_t i = 0; i < m_model.terms.size(); ++i) {
            const ModelTerm &t = m_model.terms[i];
            const double f = termFeature(t, inputs);
            for (std::size_t l = 0; l < t.lags_s.size(); ++l) {
                double &x = m_states[m_first[i] + l];
                x = lagStep(x, f, dt_s, t.lags_s[l]);
            }
        }
        return linearOutput();
    }
    if (m_model.kind == "exp") {
        const ExponentialLaw &e = m_model.exponential;
        const double v = std::fabs(inputs[e.drive]);
        const bool on = v > e.onThreshold;
        const double goal = on ? e.steadyState * std::pow(v / e.referenceDrive, e.exponent) : 0.0;
        m_expState = lagStep(m_expState, goal, dt_s, on ? e.tauWarm_s : e.tauCool_s);
        return e.baseline + m_expState;
    }
    return predictAt(m_model.synthetic.pRef_mm, inputs);
}

double DataDrivenPredictor::virtualTemperatureRise_K() const
{
    const ExponentialLaw &e = m_model.exponential;
    if (m_model.kind != "exp" || !(e.expansion_per_K > 0) || !(e.length_m > 0))
        return std::numeric_limits<double>::quiet_NaN();
    return m_expState * 1e-6 / (e.expansion_per_K * e.length_m);
}

double DataDrivenPredictor::predictAt(double position_mm, const double *inputs) const
{
    if (m_model.kind != "synthetic")
        return std::numeric_limits<double>::quiet_NaN();
    const SyntheticLaw &s = m_model.synthetic;
    const double temperature = characteristicTemperature(inputs);
    const double g = s.c + s.a * (std::exp(s.b_perK * (temperature - s.t0_C)) - 1.0);
    return g * (position_mm - s.p0_mm) / (s.pRef_mm - s.p0_mm);
}

std::vector<double> DataDrivenPredictor::run(const DataDrivenModel &model, const std::vector<double> &t,
                                             const std::vector<std::vector<double>> &columns)
{
    DataDrivenPredictor p(model);
    const std::size_t n = model.inputs.size();
    if (columns.size() != n)
        throw std::invalid_argument("data-driven model: " + std::to_string(n) + " input columns expected, got " +
                                    std::to_string(columns.size()));
    std::vector<double> out(t.size(), std::numeric_limits<double>::quiet_NaN());
    if (t.empty())
        return out;
    // Hold the last finite value of each input; before the first finite value use the first one.
    std::vector<double> row(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        if (columns[i].size() != t.size())
            throw std::invalid_argument("data-driven model: input column " + model.inputs[i].id + " has " +
                                        std::to_string(columns[i].size()) + " samples, the grid " +
                                        std::to_string(t.size()));
        for (double v : columns[i])
            if (std::isfinite(v)) {
                row[i] = v;
                break;
            }
    }
    p.reset(row.data());
    double previous = t.front();
    for (std::size_t k = 0; k < t.size(); ++k) {
        for (std::size_t i = 0; i < n; ++i)
            if (std::isfinite(columns[i][k]))
                row[i] = columns[i][k];
        out[k] = p.step(t[k] - previous, row.data());
        previous = t[k];
    }
    return out;
}

} // namespace driftlab

#include "CompensationLaw.h"

#include "DataDrivenPredictor.h"
#include "ModelExporter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace driftlab {

std::vector<double> ExportRange::values() const
{
    std::vector<double> out;
    if (!(step > 0) || !(to >= from)) {
        out.push_back(from);
        return out;
    }
    const long n = std::lround(std::floor((to - from) / step + 1e-9));
    for (long i = 0; i <= n; ++i)
        out.push_back(from + static_cast<double>(i) * step);
    if (to - out.back() > 1e-9 * std::max(1.0, std::fabs(to)))
        out.push_back(to);
    return out;
}

CompensationLaw CompensationLaw::from(const ExportableModel &model)
{
    if (model.physics)
        throw ExportRefused("fdm-seed000: the screw model's error comes from a temperature field driven by the "
                            "feed and position history, not from temperatures the controller measures; export "
                            "it as C code (--target c) to run it in the controller");
    const DataDrivenModel &m = model.dataDriven;
    DataDrivenPredictor check(m); // throws std::invalid_argument for an inconsistent model
    CompensationLaw law(m);
    if (m.linearLag()) {
        if (m.usesRises())
            throw ExportRefused(m.kind + ": its temperatures enter as rises from each run's start (reference '" +
                                m.reference.label() + "'); a controller's temperature table assumes absolute "
                                "temperatures and holds no start state; refit with --reference absolute, or export "
                                "it as C code (--target c), which captures the reference at start-up");
        for (const ModelTerm &t : m.terms) {
            double sum = 0.0;
            for (std::size_t l = 0; l < t.lags_s.size(); ++l) {
                if (t.lags_s[l] > 0)
                    throw ExportRefused(m.kind + ": term on '" + m.inputs[static_cast<std::size_t>(t.input)].id +
                                        "' has a first-order lag (" + number(t.lags_s[l], 6) +
                                        " s): a controller's temperature compensation holds no time state; "
                                        "export it as C code (--target c) or run the live loop");
                sum += t.coefficients[l];
            }
            law.m_coefficients.push_back(sum);
        }
        return law;
    }
    if (m.kind == "synthetic") {
        law.m_reference = m.synthetic.p0_mm;
        return law;
    }
    throw ExportRefused(m.kind + ": the warm-up / cool-down state of the exponential model changes with time, "
                                 "not with a measured temperature; export it as C code (--target c)");
}

double CompensationLaw::characteristicTemperature(const double *u) const
{
    double sum = 0.0;
    for (int i : m_model.synthetic.temperatures)
        sum += u[i];
    return sum / static_cast<double>(m_model.synthetic.temperatures.size());
}

double CompensationLaw::offset_um(const double *u) const
{
    if (m_model.kind == "synthetic")
        return 0.0;
    double y = m_model.intercept;
    for (std::size_t i = 0; i < m_model.terms.size(); ++i)
        y += m_coefficients[i] * DataDrivenPredictor::feature(m_model.terms[i], u[m_model.terms[i].input]);
    return y;
}

double CompensationLaw::slope_um_per_mm(const double *u) const
{
    if (m_model.kind != "synthetic")
        return 0.0;
    const SyntheticLaw &s = m_model.synthetic;
    const double g = s.c + s.a * (std::exp(s.b_perK * (characteristicTemperature(u) - s.t0_C)) - 1.0);
    return g / (s.pRef_mm - s.p0_mm);
}

double CompensationLaw::error_um(double position_mm, const double *u) const
{
    return offset_um(u) + slope_um_per_mm(u) * (position_mm - m_reference);
}

bool CompensationLaw::scalarTemperature() const
{
    return m_model.kind == "synthetic" || m_model.inputs.size() == 1;
}

std::vector<double> CompensationLaw::inputsAt(double temperature_C) const
{
    return std::vector<double>(m_model.inputs.size(), temperature_C);
}

ExportRange CompensationLaw::defaultPositions() const
{
    if (m_model.kind == "synthetic") {
        const double a = m_model.synthetic.p0_mm, b = m_model.synthetic.pRef_mm;
        const double lo = std::min(a, b), hi = std::max(a, b);
        return {lo, hi, (hi - lo) / 20.0};
    }
    return {0.0, 1000.0, 50.0};
}

std::string CompensationLaw::number(double v, int digits)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v == 0.0 ? 0.0 : v); // no "-0"
    return buf;
}

std::string CompensationLaw::plain(double v, int digits)
{
    if (v == 0.0 || !std::isfinite(v))
        return "0";
    const int exponent = static_cast<int>(std::floor(std::log10(std::fabs(v))));
    const int decimals = std::max(0, digits - 1 - exponent);
    char buf[512];
    std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 300), v);
    std::string s = buf;
    if (s.find('.') != std::string::npos) {
        s.erase(s.find_last_not_of('0') + 1);
        if (s.back() == '.')
            s.pop_back();
    }
    return s == "-0" ? "0" : s;
}

std::string CompensationLaw::signedTerm(double v, int digits)
{
    return (v < 0 ? " - " : " + ") + plain(std::fabs(v), digits);
}

namespace {

std::string group(const FormulaSyntax &s, const std::string &inner)
{
    return std::string(1, s.open) + inner + std::string(1, s.close);
}

} // namespace

std::string CompensationLaw::compensationOffsetFormula(const FormulaSyntax &s) const
{
    if (m_model.kind == "synthetic")
        return "0";
    std::string sum = plain(m_model.intercept, s.digits);
    for (std::size_t i = 0; i < m_model.terms.size(); ++i) {
        const ModelTerm &t = m_model.terms[i];
        const std::string z = group(s, group(s, s.inputs.at(static_cast<std::size_t>(t.input)) +
                                                    signedTerm(-t.offset, s.digits)) +
                                           "/" + plain(t.scale, s.digits));
        sum += signedTerm(m_coefficients[i], s.digits) + "*" + z + (t.power == 2 ? "*" + z : std::string());
    }
    return "-" + group(s, sum) + "/1000";
}

std::string CompensationLaw::compensationSlopeFormula(const FormulaSyntax &s) const
{
    if (m_model.kind != "synthetic")
        return "0";
    const SyntheticLaw &l = m_model.synthetic;
    std::string mean;
    for (std::size_t k = 0; k < l.temperatures.size(); ++k)
        mean += (k ? " + " : "") + s.inputs.at(static_cast<std::size_t>(l.temperatures[k]));
    const std::string temperature =
        group(s, group(s, mean) + "/" + std::to_string(l.temperatures.size()));
    const std::string g = plain(l.c, s.digits) + signedTerm(l.a, s.digits) + "*" +
                          group(s, s.exp + group(s, plain(l.b_perK, s.digits) + "*" +
                                                       group(s, temperature + signedTerm(-l.t0_C, s.digits))) +
                                       " - 1");
    // -g / (1000 (P_ref - P0)) with a positive divisor.
    const double divisor = 1000.0 * (l.pRef_mm - l.p0_mm);
    return (divisor > 0 ? "-" : "") + group(s, g) + "/" + plain(std::fabs(divisor), s.digits);
}

} // namespace driftlab

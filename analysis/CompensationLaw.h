#pragma once
// The static part of a data-driven model in the form CNC temperature compensation takes
// (SINUMERIK 840D K3, TwinCAT P-AXIS-00272..274): E(P, u) = offset(u) + slope(u) (P - P_ref),
// with u the model's inputs (temperatures) at this moment. E in um, P in mm.
//  - mlr / ridge (every lag 0): offset = intercept + sum c ((u - o) / s)^p, slope = 0
//  - synthetic (seed 002, eq. 26): offset = 0, slope = g(T) / (P_ref - P0), reference = P0
// Models with a time state (dynamic lags, exp warm-up) and the FDM screw model have no such
// form: from() refuses them with the reason. Formulas are written for controller languages
// through FormulaSyntax; evaluation here is the check the tests hold the text to.

#include "ModelExporter.h"

#include <string>
#include <vector>

namespace driftlab {

struct FormulaSyntax {
    std::vector<std::string> inputs; // the controller variable holding each model input
    char open = '(', close = ')';    // grouping brackets (Fanuc: [ ])
    std::string exp = "EXP";         // exponential function name
    int digits = 12;                 // significant digits of every constant
};

class CompensationLaw {
public:
    // Throws ExportRefused for models without a static law.
    static CompensationLaw from(const ExportableModel &model);

    double offset_um(const double *inputs) const;
    double slope_um_per_mm(const double *inputs) const;
    double error_um(double position_mm, const double *inputs) const;
    double referencePosition_mm() const { return m_reference; }
    std::size_t inputCount() const { return m_model.inputs.size(); }
    const DataDrivenModel &model() const { return m_model; }

    // A table over one temperature is possible when the law depends on one temperature only
    // (synthetic: the mean of its inputs; a linear model with one input).
    bool scalarTemperature() const;
    std::vector<double> inputsAt(double temperature_C) const; // requires scalarTemperature()
    // Default position range: synthetic P0 .. P_ref, else 0 .. 1000 mm.
    ExportRange defaultPositions() const;

    // The compensation in mm, -offset(u) / 1000 and -slope(u) / 1000 (mm per mm), as controller
    // text: plain decimals (no exponent), no operator followed by a sign.
    std::string compensationOffsetFormula(const FormulaSyntax &syntax) const;
    std::string compensationSlopeFormula(const FormulaSyntax &syntax) const;

    static std::string number(double value, int digits); // printf %g
    static std::string plain(double value, int digits);  // fixed point, `digits` significant
    // " + |v|" or " - |v|" in plain digits.
    static std::string signedTerm(double value, int digits);

private:
    explicit CompensationLaw(const DataDrivenModel &m) : m_model(m) {}
    double characteristicTemperature(const double *inputs) const;

    DataDrivenModel m_model;
    std::vector<double> m_coefficients; // linear: sum of coefficients per term (all lags 0)
    double m_reference = 0.0;
};

} // namespace driftlab

#pragma once
// Evaluates a DataDrivenModel sample by sample, as a controller would: standard library only,
// no allocation per step. Inputs are passed in the order of DataDrivenModel::inputs.
//
//   DataDrivenPredictor p(model);
//   p.reset(firstInputs);              // lag states at equilibrium with the first inputs
//   y = p.step(dt_s, inputs);          // advance the states by dt and predict
//
// A first-order lag advances as x += (1 - exp(-dt / tau)) (u - x) with the input at the end
// of the step; the fitters build their lagged features with the same recursion.

#include "DataDrivenModel.h"

#include <cstddef>
#include <vector>

namespace driftlab {

class DataDrivenPredictor {
public:
    // Throws std::invalid_argument for an inconsistent model (index out of range, a term
    // with different numbers of lags and coefficients, a non-positive scale or time constant).
    explicit DataDrivenPredictor(const DataDrivenModel &model);

    std::size_t inputCount() const { return m_model.inputs.size(); }
    void reset(const double *inputs);
    double step(double dt_s, const double *inputs);
    // exp: the virtual screw temperature rise of seed 001 eq. (9)-(10), state / (alpha L), in K
    // (NaN when the model has no alpha and length or is not exp). Target unit um.
    double virtualTemperatureRise_K() const;
    // The synthetic model at an explicit axis position (mm); the other kinds ignore it.
    double predictAt(double position_mm, const double *inputs) const;

    // Runs the model over a whole series: columns[i][k] is input i at t[k]. The states start
    // at equilibrium with the first row. A NaN input holds the input's last finite value.
    static std::vector<double> run(const DataDrivenModel &model, const std::vector<double> &t,
                                   const std::vector<std::vector<double>> &columns);

    // x <- x + (1 - exp(-dt/tau)) (u - x); tau <= 0 returns u.
    static double lagStep(double x, double u, double dt_s, double tau_s);
    static double feature(const ModelTerm &term, double u);
    // u through a first-order lag on the grid t, starting at equilibrium with u[0]: the
    // features the fitters regress on are exactly what run() produces.
    static std::vector<double> lagSeries(const std::vector<double> &t, const std::vector<double> &u, double tau_s);

private:
    double linearOutput() const;
    double characteristicTemperature(const double *inputs) const;

    DataDrivenModel m_model;
    std::vector<double> m_states;     // linear-lag: one per (term, lag)
    std::vector<std::size_t> m_first; // first state index of each term
    double m_expState = 0.0;
    bool m_started = false;
};

} // namespace driftlab

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
// Terms with rise = true read u - r with the run's temperature reference r, which the
// predictor captures itself from the inputs it is given after reset() (referenceSeries()).

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
    // The stated 1-sigma uncertainty of every prediction (DataDrivenModel::predictionSigma,
    // target unit; NaN when the model states none).
    double sigma() const { return m_model.predictionSigma; }
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
    // The reference r[k] the predictor uses at each sample of a run that starts at t[0]
    // (all zero for kind absolute).
    static std::vector<double> referenceSeries(const TemperatureReference &reference, const std::vector<double> &t,
                                               const std::vector<double> &u);
    // The reference captured so far for input i (0 for kind absolute).
    double reference(std::size_t input) const { return m_ref[input]; }

private:
    double linearOutput() const;
    double characteristicTemperature(const double *inputs) const;
    double termFeature(const ModelTerm &term, const double *inputs) const;
    void captureReference(double dt_s, const double *inputs);

    DataDrivenModel m_model;
    std::vector<double> m_states;     // linear-lag: one per (term, lag)
    std::vector<std::size_t> m_first; // first state index of each term
    std::vector<double> m_ref, m_refSum; // per input
    double m_refCount = 0.0, m_elapsed_s = 0.0;
    bool m_rises = false;
    double m_expState = 0.0;
    bool m_started = false;
};

} // namespace driftlab

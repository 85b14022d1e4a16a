#pragma once
// A fitted data-driven thermal-error model in the plain form a controller evaluates:
// standard library only (driftlab_model). Saved as "driftlab-model" JSON version 1 (see
// docs/datadriven.md); core/DataDrivenModelJson reads and writes it.
//
// Kinds:
//  - mean, mlr, ridge, lagridge, dynamic ("linear-lag"): y = intercept + sum over terms and lags of
//    coefficient * x, where x is the feature ((u - offset) / scale)^power of an input channel
//    u passed through a first-order lag with time constant tau (tau = 0: no lag). mlr and
//    ridge use tau = 0 only; lagridge passes every temperature through a bank of lags;
//    dynamic adds lagged principal components and the drive (spindle speed or feed) through
//    lag banks; mean has no terms (the training mean, a plain reference).
//    A term with rise = true reads its input as a rise u - r from the run's temperature
//    reference r (TemperatureReference).
//  - exp (seed 001, eq. 6): a first-order warm-up / cool-down of the displacement towards a
//    steady state y_ss(v) = k (v / v_ref)^p while the drive v is on (time constant tau_warm)
//    and towards zero while it is off (tau_cool); y = baseline + state.
//  - synthetic (seed 002, eq. 26): E(P, T) = g(T) (P - P0) / (P_ref - P0) with the screw
//    characteristic temperature T = mean of the temperature inputs and
//    g(T) = c + a (exp(b (T - T0)) - 1); P is the position (the reference position P_ref when
//    the target is a displacement channel).

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace driftlab {

struct ModelChannel {
    std::string id;   // session channel id
    std::string unit; // e.g. degC, um, rpm
    std::string kind; // temperature | displacement | feed | other
    // The range of the input over the training samples, as the model reads it (a rise where
    // its terms take rises); NaN when unknown. Held-out or live inputs beyond it by more than
    // DataDrivenModel::extrapolationMargin are flagged.
    double trainingMin = std::numeric_limits<double>::quiet_NaN();
    double trainingMax = std::numeric_limits<double>::quiet_NaN();
};

// The temperature reference r of a run, captured by the evaluator itself: kind "start" takes
// r = the input's first value (window_s = 0) or the running mean of the inputs that arrive
// after a positive step within window_s of the start (frozen after that); "absolute": r = 0.
struct TemperatureReference {
    std::string kind = "absolute"; // absolute | start
    double window_s = 0.0;
    bool operator==(const TemperatureReference &o) const { return kind == o.kind && window_s == o.window_s; }
    // "absolute", "start", "start+10min"
    std::string label() const
    {
        if (kind != "start")
            return kind;
        if (window_s <= 0)
            return "start";
        const double min = window_s / 60.0;
        const long whole = static_cast<long>(min);
        return "start+" + (static_cast<double>(whole) == min ? std::to_string(whole) : std::to_string(min)) + "min";
    }
};

// One input feature family of a linear-lag model.
struct ModelTerm {
    int input = 0;      // index into DataDrivenModel::inputs
    int power = 1;      // 1 or 2
    double offset = 0.0;
    double scale = 1.0; // the feature is ((u - offset) / scale)^power
    std::vector<double> lags_s;         // first-order lag time constants; 0 = the feature itself
    std::vector<double> coefficients;   // target unit per feature unit, one per lag
    std::vector<double> standardErrors; // one per lag (NaN where not available)
    bool rise = false;  // the input enters as u - r (DataDrivenModel::reference)
};

struct ExponentialLaw {
    int drive = 0;                 // index into inputs (spindle speed or feed)
    double onThreshold = 0.0;      // drive > threshold = warming
    double referenceDrive = 1.0;   // v_ref (drive unit)
    double steadyState = 0.0;      // k: y_ss at v_ref (target unit)
    double exponent = 1.0;         // p
    double tauWarm_s = 1.0;
    double tauCool_s = 1.0;
    double baseline = 0.0;         // cold displacement (target unit)
    // Virtual sensor (seed 001 eq. 9-10): screw temperature rise = state / (alpha L); 0 = unknown.
    double expansion_per_K = 0.0;
    double length_m = 0.0;
};

struct SyntheticLaw {
    std::vector<int> temperatures; // indices into inputs; characteristic temperature = their mean
    double a = 0.0;                // target unit
    double b_perK = 0.0;
    double c = 0.0;                // target unit
    double t0_C = 0.0;
    double p0_mm = 0.0;            // zero-error point
    double pRef_mm = 1.0;          // reference position (ratio 1)
};

struct DataDrivenModel {
    std::string kind;                 // mean | mlr | ridge | lagridge | dynamic | exp | synthetic
    ModelChannel target;
    std::vector<ModelChannel> inputs; // channels the predictor reads, in this order
    double intercept = 0.0;
    double interceptStandardError = 0.0;
    std::vector<ModelTerm> terms;     // linear-lag kinds
    ExponentialLaw exponential;       // exp
    SyntheticLaw synthetic;           // synthetic
    double samplePeriod_s = 0.0;      // grid the model was fitted on (informational)
    TemperatureReference reference;   // of the terms with rise = true
    // The stated 1-sigma uncertainty of every prediction (target unit): the RMS of the
    // out-of-fold prediction errors of the fit's nested cross-validation (each fold predicted by
    // a model fitted without it, hyperparameters chosen without it); NaN when unknown.
    double predictionSigma = std::numeric_limits<double>::quiet_NaN();
    // Reduced models (linear-lag kinds): per input, the same family with the chosen
    // hyperparameters refitted without that input (`without` = its channel id), for a live loop
    // whose sensor fails or leaves its training range. Empty on a reduced model itself.
    std::string without;
    std::vector<DataDrivenModel> reduced;

    // The reduced model that does without the input `id` (nullptr when none was fitted).
    const DataDrivenModel *reducedWithout(const std::string &id) const
    {
        for (const DataDrivenModel &r : reduced)
            if (r.without == id)
                return &r;
        return nullptr;
    }
    int inputIndex(const std::string &id) const
    {
        for (std::size_t i = 0; i < inputs.size(); ++i)
            if (inputs[i].id == id)
                return static_cast<int>(i);
        return -1;
    }

    bool linearLag() const
    {
        return kind == "mean" || kind == "mlr" || kind == "ridge" || kind == "lagridge" || kind == "dynamic";
    }
    // Inputs may leave [trainingMin - m, trainingMax + m] with m = 10 % of the training span,
    // at least 0.5 (K for temperatures), before a prediction is flagged as extrapolated.
    static double extrapolationMargin(double min, double max) { return std::max(0.1 * (max - min), 0.5); }
    bool inputIsRise(int input) const
    {
        for (const ModelTerm &t : terms)
            if (t.input == input && t.rise)
                return true;
        return false;
    }
    bool usesRises() const
    {
        for (const ModelTerm &t : terms)
            if (t.rise)
                return true;
        return false;
    }
};

} // namespace driftlab

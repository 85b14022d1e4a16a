#pragma once
// Identification of the seed-000 screw model, eq. (20): k1..k4, lambda and P_f from one or
// several recordings, with bounds, by Ceres (Levenberg-Marquardt, box constraints) using
// variable projection: the nonlinear search runs over (k1, k2, lambda, P_f) and the
// nonlinear parameters of added components; for each trial the heat amplitudes (k3, k4 and
// added sources) and error-term amplitudes are the bounded linear least-squares solution
// given the unit responses of ScrewResponseSimulator.
//
// Objective: sum over observations of ((predicted - measured) / sigma)^2 with
//  - interferometer points: predicted TE(P_x, t) - TE(P_x, t_ref), sigma = interferometerSigma_um
//    (default 1 um: XM-60-class repeatability plus the optics' own drift);
//  - screw-end probe: elongation, at most one sample per elongationInterval_s (default 60 s,
//    so a 1 Hz probe does not outweigh a dozen interferometer runs), sigma = elongationSigma_um
//    (default 1 um).
// Uncertainties: covariance s^2 (J^T J)^-1 of all parameters (nonlinear by central
// differences, amplitudes analytically) at the optimum, s^2 = weighted RSS / (n - p).

#include "ErrorTermComponent.h"
#include "HeatSourceComponent.h"
#include "IdentificationTypes.h"
#include "ScrewResponseSimulator.h"

#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace driftlab {

struct IdentificationOptions {
    ResponseSimulatorOptions simulator;
    FdmParameters initial;               // start of k1, k2, lambda, P_f (k3, k4 are solved)
    double k1Lower = 0.0, k1Upper = 0.05;        // W/(m^2 K)/(mm/min)
    double k2Lower = 0.1, k2Upper = 500.0;       // W/(m^2 K)
    double lambdaLower = 5.0, lambdaUpper = 5000.0; // W/(m K)
    double fixedEndLower_mm = -3000.0, fixedEndUpper_mm = 3000.0;
    bool fitFixedEnd = true;             // false: P_f held at initial (e.g. known from the machine)
    // Priors from the drawing and the material (issue 36): Gaussian penalty residuals
    // (value - mean) / sigma in the same weighted units as the data (sigma <= 0: none). They
    // anchor lambda and P_f where the data cannot; weightedRms and the statistics are the
    // data's alone.
    double lambdaPriorMean = 45.0, lambdaPriorSigma = 0.0;          // W/(m K)
    double fixedEndPriorMean_mm = 0.0, fixedEndPriorSigma_mm = 0.0;
    int maxIterations = 100;
    // false: no covariance (it costs two simulations per nonlinear parameter): standard
    // errors stay 0 and the correlation empty, for fits whose parameters and predictions alone
    // are used (the folds of a cross-validation, a first pass). The fit itself is the same.
    bool standardErrors = true;
    // Called after every solver iteration (from the fitting thread) with the iteration
    // number and the cost; return false to cancel: fit() then throws IdentificationCancelled.
    std::function<bool(int iteration, double cost)> progress;
};

class IdentificationCancelled : public std::runtime_error {
public:
    IdentificationCancelled() : std::runtime_error("identification cancelled") {}
};

struct IdentifiedParameter {
    std::string name;
    std::string unit;
    double value = 0.0;
    double standardError = 0.0;
    bool linear = false;  // solved by linear least squares
    bool fitted = true;   // false: held fixed
};

struct ObservationFit {
    int recording = 0;
    bool elongation = false;
    double t_s = 0.0;
    double position_mm = 0.0;
    double measured_um = 0.0;
    double predicted_um = 0.0;  // K for screw temperatures
    bool temperature = false;
    double distance_m = 0.0;    // screw temperatures: distance from the fixed end
};

struct FitStatistics {
    int interferometerPoints = 0;
    int elongationPoints = 0;
    double interferometerRms_um = 0.0;
    double elongationRms_um = 0.0;
    double interferometerPeakToValley_um = 0.0; // of the measured values
    double elongationPeak_um = 0.0;
    int temperaturePoints = 0;
    double temperatureRms_K = 0.0;
    std::vector<ObservationFit> points;
};

struct IdentificationResult {
    FdmParameters parameters;                     // the seed-000 six
    std::vector<IdentifiedParameter> all;         // k1, k2, k3, k4, lambda, P_f, then components
    std::vector<double> nonlinearComponentValues; // values of the components' nonlinear parameters
    std::vector<double> amplitudes;               // heat sources then error terms (k3, k4 first)
    Eigen::MatrixXd correlation;                  // of the fitted entries of `all`, in that order
    std::vector<std::string> correlationNames;
    FitStatistics fit;
    double weightedRms = 0.0;  // sqrt(mean squared weighted residual)
    int iterations = 0;
    int evaluations = 0;
    bool converged = false;
    std::string solverReport;
    double wallTime_s = 0.0;
};

class ScrewModelIdentifier {
public:
    // The seed-000 sources (BearingHeatSource = k3, NutHeatSource = k4) are always present.
    explicit ScrewModelIdentifier(const ScrewGeometry &geometry, const IdentificationOptions &options = {});

    // Further components (the mismatch-diagnosis candidates). Added in order after k3, k4.
    void addHeatSource(std::shared_ptr<HeatSourceComponent> source);
    void addErrorTerm(std::shared_ptr<ErrorTermComponent> term);

    // Throws std::invalid_argument for unusable recordings, std::runtime_error if the solver fails.
    IdentificationResult fit(const std::vector<ScrewRecording> &recordings);
    // Predictions of a fitted model for (other) recordings on the same grid: validation.
    FitStatistics predict(const IdentificationResult &result, const std::vector<ScrewRecording> &recordings);

    const IdentificationOptions &options() const { return m_options; }

private:
    ScrewGeometry m_geometry;
    IdentificationOptions m_options;
    std::vector<std::shared_ptr<HeatSourceComponent>> m_sources;
    std::vector<std::shared_ptr<ErrorTermComponent>> m_terms;
};

} // namespace driftlab

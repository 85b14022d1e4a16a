#pragma once
// "Locate" step of the mismatch diagnosis: where a fitted model disagrees with a recording.
// Residuals (predicted - measured) broken down by operating phase (standstill, warm-up,
// steady feed, cooling), interferometer target and part of the screw, hour and sensor;
// whiteness (pooled lag-1 autocorrelation per target, Ljung-Box on the run means or the
// probe series); Pearson correlation of the interferometer residuals with the feed, time,
// position and every auxiliary temperature channel (and channel x position); identified
// parameters far from physics (lambda vs steel, P_f vs the drawing, values at bounds).

#include "DiagnosisTypes.h"
#include "ScrewModelIdentifier.h"

#include <vector>

namespace driftlab {

class ResidualLocator {
public:
    // points: the model's observations of `recording` (ScrewModelIdentifier fit or predict).
    static ResidualLocation locate(const DiagnosisRecording &recording, const std::vector<ObservationFit> &points);
    // Screw temperature residuals (model - measured rise, K): `points` are predictions of
    // recording.screwTemperatures with ObservationFit::recording = index of the sensor series.
    // Fills the temperature* groups of `location` (by sensor, third of the screw, phase).
    static void locateTemperatures(const DiagnosisRecording &recording, const std::vector<ObservationFit> &points,
                                   double screwLength_m, ResidualLocation &location);
    // Adds plausibility flags for the identified seed-000 parameters.
    static void checkPlausibility(const IdentificationResult &result, const IdentificationOptions &options,
                                  double drawingFixedEnd_mm, ResidualLocation &location);
    // Writes location.summary from the numbers.
    static void summarise(ResidualLocation &location);
    // Whether a residual is a located discrepancy rather than measurement noise: not white
    // (Ljung-Box on the run means, lag-1 r), or following a driver channel (|r| >= 0.5; not
    // feed, time or position). `why` (optional) gets the evidence in words.
    static bool isLocated(const ResidualLocation &location, std::string *why);

    // Lag-1 autocorrelation of residuals ordered by time within each interferometer target
    // and within the probe series, pooled (used for the effective sample size).
    static double lag1Autocorrelation(const std::vector<ObservationFit> &points);
    // Effective number of independent residuals: sum over streams (each interferometer target,
    // the probe) of n (1 - rho1) / (1 + rho1), rho1 the stream's lag-1 autocorrelation (>= 0).
    static double effectiveSampleSize(const std::vector<ObservationFit> &points);
    // Upper tail of the chi-square distribution (Wilson-Hilferty approximation).
    static double chiSquareUpperTail(double x, int dof);
    // Operating phase at time t of a drive.
    static std::string phaseAt(const ScrewDrive &drive, double t_s);
};

} // namespace driftlab

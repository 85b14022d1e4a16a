#pragma once
// Inputs and outputs of the mismatch diagnosis (DiagnosisEngine). No Qt.
//
// A DiagnosisRecording is an identification recording (drive + interferometer thermal
// errors + optional screw-end probe) plus every auxiliary temperature channel of the
// session keyed by its ROLE ("motor", "structure", "coolant", "free_bearing", ...): the
// candidate effects find their drivers there, never by channel name.

#include "IdentificationTypes.h"
#include "TimeSeries.h"

#include <limits>
#include <map>
#include <string>
#include <vector>

namespace driftlab {

// Screw temperatures of one sensor (the infrared axial profile, a surface PT100): observed,
// predicted by the model, never fitted by the diagnosis (they locate, they do not select).
struct ScrewTemperatureSeries {
    std::string sensor;
    std::vector<ScrewTemperaturePoint> points;
};

struct DiagnosisRecording {
    ScrewRecording screw;
    std::vector<ScrewTemperatureSeries> screwTemperatures;
    std::map<std::string, TimeSeries> channelsByRole; // auxiliary temperatures, degC
    // Drawing value of P_f (machine block); NaN = unknown (no plausibility check).
    double drawingFixedEnd_mm = std::numeric_limits<double>::quiet_NaN();

    bool hasRole(const std::string &role) const
    {
        const auto it = channelsByRole.find(role);
        return it != channelsByRole.end() && it->second.size() >= 2;
    }
};

// A residual statistic of one group (phase, target, hour, sensor). Temperature groups
// (ResidualLocation::temperature*) hold K in the _um fields.
struct ResidualGroup {
    std::string label;
    int count = 0;
    double mean_um = 0.0;
    double rms_um = 0.0;
};

struct ChannelCorrelation {
    std::string channel;   // "feed", "<role>", "<role> x position"
    double correlation = 0.0;
};

struct PlausibilityFlag {
    std::string parameter;
    double value = 0.0;
    double expected = 0.0;
    std::string message;
};

// Where the baseline disagrees with the recording, in numbers and in words.
struct ResidualLocation {
    std::vector<ResidualGroup> byPhase;
    std::vector<ResidualGroup> byPosition;   // one per interferometer target
    std::vector<ResidualGroup> byScrewPart;  // near fixed end / middle / near free end
    std::vector<ResidualGroup> byHour;
    std::vector<ResidualGroup> bySensor;     // interferometer, screw_elongation
    // Screw temperature residuals (model - measured rise, K) where the recording has them.
    int temperaturePoints = 0;
    double temperatureRms_K = 0.0;
    std::vector<ResidualGroup> temperatureBySensor;    // "infrared profile", surface PT100 ids
    std::vector<ResidualGroup> temperatureByScrewPart; // fixed-end / middle / free-end third
    std::vector<ResidualGroup> temperatureByPhase;
    double lag1Autocorrelation = 0.0;        // of the time-ordered residuals per target
    double ljungBoxQ = 0.0;                  // on the run-mean residual series
    int ljungBoxLags = 0;
    double ljungBoxP = 1.0;
    bool white = true;
    std::vector<ChannelCorrelation> correlations; // sorted by |r|, largest first
    std::vector<PlausibilityFlag> implausible;
    int implausibleRefits = 0; // candidate refits that bend lambda / P_f away from physics
    std::string summary;                      // the location in words
};

struct ParameterValue {
    std::string name;
    std::string unit;
    double value = 0.0;
    double standardError = 0.0;
    bool fitted = true;
};

struct ModelEvaluation {
    std::vector<ParameterValue> parameters;
    double trainRms_um = 0.0;      // interferometer RMS on the training recording
    double heldoutRms_um = 0.0;    // interferometer RMS on the validation recording
    double cvRms_um = 0.0;         // time-blocked cross-validation RMS on the training recording
    double informationCriterion = 0.0; // AICc with the effective sample size
    double effectiveSamples = 0.0;
    int parameterCount = 0;
    bool converged = false;
};

struct CandidateOutcome {
    std::string effect;
    std::string explanation;
    bool applicable = true;
    std::string notApplicableReason;
    ModelEvaluation evaluation;
    double score = 0.0;               // higher is better; <= 0 = does not earn its keep
    double heldoutImprovement = 0.0;  // 1 - heldout / baseline heldout
    double cvImprovement = 0.0;
    double deltaIc = 0.0;             // IC(candidate) - IC(baseline)
    double minAmplitudeZ = 0.0;       // largest |value / standard error| of its amplitudes
    bool insideBounds = true;
    // An empirical term that passed every rule but was withdrawn: no driver's term stood out
    // (ForwardSelection::tryEmpirical).
    bool notLocated = false;
    double plausibilityDistance = 0.0; // of the refit's lambda and P_f (DiagnosisEngine)
    double temperatureRms_K = std::numeric_limits<double>::quiet_NaN(); // predicted screw temperatures
    // Held-out prediction test against the reference (HeldoutPredictionTest): one-sided p over
    // the validation recording's runs, and how many runs.
    double heldoutP = 1.0;
    int heldoutRuns = 0;
    // The test that decides (CandidateAcceptance::predictionTest): pooled with the training
    // runs as the cross-validation predicted them when both models were cross-validated.
    double predictionP = 1.0;
    int predictionRuns = 0;
    // How many candidates the test's false-discovery threshold counted (Benjamini-Hochberg over
    // the round's candidates actually refitted; 0: a single test).
    int hypotheses = 0;
    bool othersPass = false;          // every rule but the held-out gain / test holds
    bool accepted = false;
    std::vector<std::string> reasons; // why accepted / rejected
};

// One validation interferometer point predicted by the baseline and the corrected model.
struct DiagnosisPrediction {
    double t_s = 0.0;
    double position_mm = 0.0;
    double measured_um = 0.0;
    double baseline_um = 0.0;
    double corrected_um = 0.0;
    bool reference = false; // measured in the reference run (thermal error 0 by definition)
};

// One effect accepted by the forward selection, tested against the model before it (the
// seed-000 baseline for the first, baseline + the effects accepted before for the others).
struct DiagnosisStep {
    std::string effect;
    std::string explanation;
    std::string description;                 // the grammar member in physical words (EffectGrammar)
    std::vector<ParameterValue> parameters;  // the effect's own parameters in the model after this step
    double heldoutBefore_um = 0.0;           // validation RMS of the model before the step
    double heldoutAfter_um = 0.0;
    double heldoutImprovement = 0.0;         // 1 - after / before
    double cvImprovement = 0.0;
    double deltaIc = 0.0;
    std::vector<std::string> reasons;        // the evidence that accepted it
    int candidatesTried = 0;                 // candidates refitted in this step
};

// The empirical discrepancy term tried on the final model's residual (DiscrepancyTerm): named
// "unexplained" when it passes, never a library effect.
struct DiagnosisDiscrepancy {
    bool tried = false;
    bool accepted = false;
    std::string hypothesis;               // in words, labelled empirical
    std::vector<std::string> terms;       // e.g. "lag60min[dT(hydraulic_unit)] * x"
    std::vector<double> coefficients;     // in `unit`
    // "heat_input": the empirical heat-input term fitted jointly with the model (a step of the
    // selection, W/(m K)); "residual": the sparse regression on the final model's residual (um/K).
    std::string kind = "residual";
    std::string unit = "um/K";
    double heldoutBefore_um = 0.0, heldoutAfter_um = 0.0;
    double cvBefore_um = 0.0, cvAfter_um = 0.0;
    std::vector<std::string> reasons;
};

// A sensor of the measurement chain whose reading disagrees with the others in a way that
// follows a temperature or time (MeasurementChainCheck): named, corrected, not charged to the
// machine.
struct SensorFinding {
    std::string sensor;      // "interferometer", "screw_elongation probe", "<role> PT100"
    std::string role;        // "interferometer", "screw_elongation" or the channel's role
    std::string kind;        // "air" (beam x air temperature), "drift" (follows a driver), "step"
    std::string driver;      // "ambient", "<role>", "time"
    std::string law;         // in words
    double coefficient = 0.0;
    double standardError = 0.0;
    double intercept = 0.0;  // air: the position-independent part (um/K)
    std::string unit;
    double time_s = std::numeric_limits<double>::quiet_NaN(); // a step's moment
    std::string recording;   // the recording it was found in
    std::vector<std::string> evidence;
};

// One added measurement the diagnosis proposes (DecisiveTestPlanner), simulated with the two
// competing fitted models: how differently they predict it, relative to the measured noise.
struct ProposedTestEvidence {
    std::string code;          // "cooldown", "standstill_phases", "feed_high", "feed_low", "dense_runs", "screw_pt100_free_end", ...
    std::string description;   // the programme in words
    std::string observable;    // "interferometer" or "screw temperature"
    double duration_h = 0.0;   // added recording time
    int runs = 0;              // interferometer runs (or temperature samples) scored
    int points = 0;
    double noise = 0.0;        // per point, in `unit` (the better model's held-out RMS, at least the floor)
    std::string unit;          // "um" or "K"
    double rmsDifference = 0.0;  // RMS of model A - model B over the scored points
    double maxDifference = 0.0;  // largest |A - B|
    double expectedChi2 = 0.0;   // sum over runs of (run RMS of A - B / noise)^2: each run one sample
    double expectedZ = 0.0;      // sqrt(expectedChi2)
    double expectedHeldoutGain = 0.0; // 1 - noise / sqrt(noise^2 + rmsDifference^2)
};

// Which added measurement would decide between two explanations (issue 36 item 5).
struct DecisiveTestAdvice {
    bool given = false;
    std::string trigger;       // why advice is given (the rule that fired)
    std::string modelA, modelB; // the two explanations, e.g. "baseline" and "baseline + holding_heat"
    std::vector<ProposedTestEvidence> tests; // ranked, most decisive first
    std::string summary;       // in words
};

// The switches a diagnosis ran with (DiagnosisOptions), recorded with its answer so that a
// stored result says how it was reached ("options" of DiagnosisResultJson).
struct DiagnosisSwitches {
    bool priors = false;
    bool checkMeasurementChain = false;
    bool tryTriples = false;
    bool housingContact = false;
    bool fitScrewTemperatures = false;
    double dt_s = 0.0;                // implicit time step of the fits
    std::vector<std::string> effects; // the candidate codes asked for; empty: all
};

struct DiagnosisReport {
    // Accepted effect codes joined by '+' in the order of acceptance, "none" when none was,
    // "unexplained" for a located discrepancy no candidate explains.
    std::string effect = "none";
    std::vector<DiagnosisStep> steps;   // the accepted effects, in order (an "unexplained" one last)
    DiagnosisDiscrepancy discrepancy;
    std::string explanation;
    ResidualLocation location;          // of the baseline on the training recording
    ResidualLocation correctedLocation; // of the corrected model on the training recording
    ModelEvaluation baseline;
    ModelEvaluation corrected;          // the final model (== baseline when the answer is "none")
    std::vector<CandidateOutcome> candidates; // against the baseline, sorted by score, best first
    // Every round of the forward selection: its candidates against the model of that round.
    std::vector<std::vector<CandidateOutcome>> rounds;
    std::vector<DiagnosisPrediction> predictions;
    // Notes on the input in words (e.g. interferometer points left out: outside the drive).
    std::vector<std::string> notes;
    // Sensors found at fault (corrected before the selection, never charged to the machine).
    std::vector<SensorFinding> measurementChain;
    // The added measurement that would separate the two closest explanations (when the answer
    // is `none` with a located residual, or the best two are close).
    DecisiveTestAdvice advice;
    // The grammar of effects searched (EffectGrammar, issue 36 item 2): members offered to this
    // diagnosis (after --effects) and how many were refitted against the baseline (applicable:
    // their inputs exist), the count the first round's false-discovery threshold takes.
    int grammarMembers = 0;
    int candidatesSearched = 0;
    DiagnosisSwitches switches;
    double wallTime_s = 0.0;
    bool cancelled = false;
};

} // namespace driftlab

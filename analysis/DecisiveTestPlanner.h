#pragma once
// "Which test would decide" (issue 36 item 5): given two competing fitted models of one machine
// (the baseline and a candidate that fell short, or two candidates that came out close), builds
// the added measurements a lab could make after the training recording — a longer cool-down,
// standstill phases, another feed (higher / lower than any recorded), the same programme with
// interferometer runs every 10 min, a surface PT100 at a named place on the screw — simulates
// both models on each, and ranks them by the expected evidence: the expected chi-square of the
// difference of the two predictions against the measured noise, each interferometer run (or
// temperature sample) counted as one sample as the prediction test counts runs.
//
// The auxiliary temperatures a proposed programme would record (motor, housings, structure,
// coolant) are extrapolated by a per-channel driver model fitted on the training recording:
// rise over ambient = c + g * (feed through a first-order lag tau), tau in {10, 30, 60, 120}
// min, the best least-squares fit kept, continuous at the end of the recording. Ambient is held
// at its last value. Interferometer runs do not move the axis in the proposed drives (their
// own heat is small against a programme's). No Qt.

#include "DiagnosisTypes.h"
#include "ResidualLocator.h"
#include "ScrewModelIdentifier.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

class DecisiveTestPlanner {
public:
    // One model's predictions on a recording: its interferometer thermal errors (relative to
    // each point's reference run) and its screw temperatures, in the order of the recording.
    using Predictor = std::function<FitStatistics(const DiagnosisRecording &)>;

    struct Settings {
        double extension_s = 3.0 * 3600.0;  // added programmes after the recording
        double runInterval_s = 1200.0;       // interferometer runs in the added programmes
        double denseInterval_s = 600.0;      // "runs every N minutes" over the recorded programme
        double dwell_s = 15.0;               // per target within a run
        double temperatureInterval_s = 600.0; // surface PT100 samples counted as independent
        double highFeedFactor = 1.5;         // another feed: this times the highest recorded
        double lowFeedFactor = 0.5;          // and this times the lowest moving one
        double phase_s = 2400.0;             // standstill phases: motion / standstill blocks
    };

    struct Proposal {
        std::string code;
        std::string description;
        std::string observable; // "interferometer" or "screw temperature"
        double duration_h = 0.0;
        DiagnosisRecording recording;
        std::vector<int> runOf; // per scored observation (interferometer points or temperatures, in order)
    };

    // The two explanations to separate, by the rule (issue 36 item 5):
    //  - the answer is `none` and the baseline's residual is located (not white, or following
    //    a driver): the baseline against the applicable library candidate of round 1 with the
    //    largest held-out gain;
    //  - a library step was named, and in its round the runner-up is close: its score within
    //    `scoreMargin` of the winner's, or its held-out RMS within `heldoutRatio` of the
    //    winner's: the model with the winner against the model with the runner-up, both on
    //    top of the steps before.
    struct Rivals {
        bool any = false;
        std::string trigger;
        int stepsBefore = 0;  // the first stepsBefore accepted steps are in both models
        std::string a;        // empty: the model of those steps alone (the baseline when 0)
        std::string b;
    };
    static Rivals rivals(const DiagnosisReport &report, double scoreMargin, double heldoutRatio);

    explicit DecisiveTestPlanner(double screwLength_m) : m_length_m(screwLength_m) {}
    DecisiveTestPlanner(double screwLength_m, const Settings &settings) : m_length_m(screwLength_m), m_settings(settings) {}

    std::vector<Proposal> propose(const DiagnosisRecording &train) const;

    // The proposals' evidence, most decisive first (expected chi-square; the shorter test first
    // on a tie). noise_um / noise_K: the noise per interferometer point / temperature sample.
    std::vector<ProposedTestEvidence> rank(const std::vector<Proposal> &proposals, const Predictor &a, const Predictor &b,
                                           double noise_um, double noise_K) const;

    // The channel's rise over `ambient` as c + g * lag_tau(feed in m/min) fitted on the
    // recording, continued over `drive` (which starts with the recording's own drive).
    static TimeSeries extendChannel(const TimeSeries &channel, const ScrewDrive &recorded, const ScrewDrive &drive);

    // The advice in words from ranked evidence.
    static std::string summarise(const std::string &modelA, const std::string &modelB, const std::vector<ProposedTestEvidence> &tests);

private:
    double m_length_m;
    Settings m_settings;
};

} // namespace driftlab

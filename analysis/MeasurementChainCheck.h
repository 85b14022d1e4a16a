#pragma once
// The measurement chain as a suspect (issue 36 item 3). The observables are checked against
// each other before anything is charged to the machine:
//  * interferometer vs air: an interferometer whose air compensation is off reads an error
//    proportional to the beam length and the air temperature change (about 1 um/m/K); the
//    screw-end probe sees none of it. Found when the interferometer's residual follows
//    dT_air x position with a coefficient of 0.3-3 um/m/K, the air explains it better than any
//    other temperature channel, the probe does not follow the air, and the validation
//    recording shows the same law.
//  * probe vs interferometer: the probe's disagreement with a model fitted to the
//    interferometer alone follows a temperature channel or time (a holder that moves), while
//    the interferometer's own residual does not; confirmed on the validation recording.
//  * PT100s: a level step in one channel (lines fitted on either side of a moment disagree at
//    it) that no other channel shows: a loose contact or a recalibration, not heat (heat gives
//    a kink, never a jump).
// A finding names the sensor and its law; DiagnosisEngine corrects the reading (or leaves the
// sensor out) and does not charge it to the machine. No Qt.

#include "CandidateEffect.h"
#include "DiagnosisTypes.h"
#include "ScrewModelIdentifier.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

class MeasurementChainCheck {
public:
    // Fresh components of the machine the diagnosis judges (DiagnosisEngine::assemble: with
    // housingContactBaseline the as-built housing contacts), added to every refit of the check
    // so that the sensors are judged against that machine, not the bare seed-000 model. Empty
    // (or returning no components): the seed-000 model alone.
    using Machine = std::function<CandidateModel()>;

    struct Options {
        double minT = 5.0;                  // |coefficient| / SE (SE scaled by the effective n)
        double confirmT = 3.0;              // the same law on the validation recording
        double airJointMinT = 4.0;          // airByJointFit's |c1| / SE (othersim: clean 1.7-1.8, 0.93 um/m/K at 0.5 K/h: 4.4)
        double airLow_um_mK = 0.3, airHigh_um_mK = 3.0;
        double minProbeDrift_um = 1.0;      // the fitted drift's range over the recording
        double minProbeR2 = 0.5;
        double maxInterferometerShare = 0.1; // interferometer's coefficient / the probe's (same driver)
        double minStep_K = 0.2;
        double stepNoiseFactor = 12.0;      // step >= factor x robust spread of the step statistic
        double stepWindow_s = 300.0;
    };

    // Residuals are measured - predicted, um.
    //  trainFit: the baseline (interferometer and probe) on the training recording;
    //  trainInterferometerOnly / validateInterferometerOnly: a baseline fitted to the
    //  interferometer alone, its predictions of both recordings' probes and interferometers
    //  (empty when there is no probe); validateFit: the baseline's predictions of the
    //  validation recording.
    static std::vector<SensorFinding> check(const DiagnosisRecording &train, const DiagnosisRecording &validate,
                                            const std::vector<ObservationFit> &trainFit,
                                            const std::vector<ObservationFit> &validateFit,
                                            const std::vector<ObservationFit> &trainInterferometerOnly,
                                            const std::vector<ObservationFit> &validateInterferometerOnly,
                                            const Options &options);
    static std::vector<SensorFinding> check(const DiagnosisRecording &train, const DiagnosisRecording &validate,
                                            const std::vector<ObservationFit> &trainFit,
                                            const std::vector<ObservationFit> &validateFit,
                                            const std::vector<ObservationFit> &trainInterferometerOnly,
                                            const std::vector<ObservationFit> &validateInterferometerOnly)
    {
        return check(train, validate, trainFit, validateFit, trainInterferometerOnly, validateInterferometerOnly, Options{});
    }

    // Interferometer vs air by a joint refit: the baseline plus (c1 P_x + c0)(T_air - T_air(t_ref))
    // on the interferometer only, the probe anchoring the screw (the baseline alone absorbs part of
    // the law). Named when c1 is in the air range at |t| >= airJointMinT, the validation recording refitted
    // on its own gives the same sign at |t| >= confirmT, and the training fit with the law predicts
    // the validation interferometer better than the baseline (validateFit). Needs a probe.
    static std::vector<SensorFinding> airByJointFit(const DiagnosisRecording &train, const DiagnosisRecording &validate,
                                                    const ScrewGeometry &geometry, const IdentificationOptions &options,
                                                    const std::vector<ObservationFit> &validateFit, const Options &chainOptions,
                                                    const Machine &machine = {});

    // Level steps in one recording's temperature channels (see above).
    static std::vector<SensorFinding> steps(const DiagnosisRecording &r, const Options &options);

    // Applies a finding to a recording: removes the interferometer's air law, leaves out the
    // probe, or takes the step out of the PT100 channel (and the drive's ambient for the
    // ambient role). Steps apply only to the recording they were found in (by name).
    static void correct(DiagnosisRecording &r, const SensorFinding &finding);

    // The whole check as the diagnosis runs it: fits a baseline to the interferometer alone
    // when there is a probe, runs check() and corrects both recordings by every finding. Every
    // refit (the interferometer-only baseline, the air law's joint fits) carries `machine`.
    static std::vector<SensorFinding> examine(DiagnosisRecording &train, DiagnosisRecording &validate,
                                              const ScrewGeometry &geometry, const IdentificationOptions &options,
                                              const std::vector<ObservationFit> &trainFit,
                                              const std::vector<ObservationFit> &validateFit, const Machine &machine = {});
    // steps() on a recording, each corrected; the findings.
    static std::vector<SensorFinding> correctSteps(DiagnosisRecording &r);

    // Reference time of an interferometer point (its own, the recording's, or the drive start).
    static double referenceTime(const ScrewRecording &r, const PositioningErrorPoint &p);
};

} // namespace driftlab

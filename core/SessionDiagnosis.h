#pragma once
// The mismatch diagnosis of two stored sessions as one use case, run the same way by
// `driftlab-cli diagnose` and the GUI's Diagnosis workspace: reads the training and the
// validation recording (SessionAnalysis::diagnosisRecording), runs DiagnosisEngine with the
// one set of settings below (fit step 20 s, drive sampled every second, 60 iterations), and
// stores the answer with the training session (DiagnosisResultJson::storedResult, kind
// AnalysisResultKind::diagnosis()): the same record whichever face ran it, read by the
// test report.
//
// Construction reads both recordings on the calling thread (a SessionStore belongs to the
// thread that opened it) and throws std::invalid_argument naming the recording for input the
// diagnosis cannot use; run() touches no store and may run on a worker thread; store() on
// the thread of the store it writes.

#include "DiagnosisEngine.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"

#include <QString>

#include <string>
#include <vector>

namespace driftlab {

class SessionStore;

struct DiagnosisRequest {
    qint64 train = 0;
    qint64 validate = 0;
    // How the user named the recordings (messages; "validate" of the stored record). Empty:
    // the session ids.
    QString trainLabel, validateLabel;
    std::vector<std::string> effects; // candidate codes to try; empty: all
    bool fitScrewTemperatures = false;
    double dt_s = 20.0;               // implicit time step of the fits, (0, 600] s
    bool priors = false;              // lambda and P_f anchored by steel and the drawing (issue 36)
    bool checkMeasurementChain = false; // sensors checked against each other before the selection (opt-in)
    bool tryTriples = false;          // triples when no single and no pair passes (opt-in, issue 36 item 4)
    bool housingContact = false;      // the housings' contact with the screw in the baseline (opt-in, issue 36)
};

class SessionDiagnosis {
public:
    using Progress = DiagnosisEngine::Progress; // return false to cancel

    // Train from trainStore, validate from validateStore (a bundle imported elsewhere).
    SessionDiagnosis(const SessionStore &trainStore, const DiagnosisRequest &request, const SessionStore &validateStore);
    SessionDiagnosis(const SessionStore &store, const DiagnosisRequest &request);

    // The checks of a request that need no store (time step, effect codes); throws
    // std::invalid_argument naming the option. The constructor runs them too.
    static void check(const DiagnosisRequest &request);

    // What was read of each recording ("..., auxiliary roles: ...").
    QString trainNote() const { return m_trainNote; }
    QString validateNote() const { return m_validateNote; }
    const DiagnosisOptions &options() const { return m_options; }

    // The diagnosis; report.cancelled when progress returned false.
    DiagnosisReport run(const Progress &progress = {}) const;

    // Throws std::invalid_argument when `store` cannot keep the answer (read-only): check
    // before running.
    static void checkWritable(const SessionStore &store);
    // Stores a (not cancelled) report with the training session; returns the result id.
    qint64 store(SessionStore &store, const DiagnosisReport &report) const;

private:
    DiagnosisRequest m_request;
    DiagnosisRecording m_train, m_validate;
    ScrewGeometry m_geometry;
    DiagnosisOptions m_options;
    QString m_trainNote, m_validateNote;
};

} // namespace driftlab

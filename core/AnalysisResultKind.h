#pragma once
// The one list of the kinds of analysis result stored with a session
// (SessionStore::addAnalysisResult / latestAnalysisResult). Writers (CLI, GUI) and readers
// (the test report, the Analysis workspace) name a kind only through this class.

#include <QString>

namespace driftlab {

class AnalysisResultKind {
public:
    // The mismatch diagnosis (DiagnosisResultJson's stored record), kept with the training session.
    static QString diagnosis() { return QStringLiteral("diagnosis"); }
    // A sensitive-point selection (DataDrivenFit::selectionJson plus "session").
    static QString sensitivePoints() { return QStringLiteral("sensitive-points"); }
    // A compensation loop's before/after summary (`compensate --db`).
    static QString compensation() { return QStringLiteral("compensation"); }
    // The ISO 230 evaluation of the session's interferometer runs (Iso230Report::toJson, written
    // by SessionIso230::store from `iso230` and the ISO 230 view).
    static QString iso230() { return QStringLiteral("iso230"); }
    // `analyse`: the seed-000 model run against the screw-end probe.
    static QString fdmElongationCheck() { return QStringLiteral("fdm-elongation-check"); }
};

} // namespace driftlab

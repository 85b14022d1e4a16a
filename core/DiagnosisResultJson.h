#pragma once
// The one owner of the mismatch diagnosis's JSON: the file `diagnose --json` writes and the
// record stored with the training session (AnalysisResultKind::diagnosis(), read by the
// test report). Schema version 1: "schema_version": 1 (records written before 2026-11 have
// no "schema_version" and the same fields).

#include "DiagnosisTypes.h"

#include <QJsonObject>
#include <QString>

namespace driftlab {

class DiagnosisResultJson {
public:
    static constexpr int kSchemaVersion = 1;

    // The whole answer: effect(s), explanation, location, candidates, selection rounds,
    // baseline and corrected models, wall time, and "options": the switches it ran with
    // (priors, measurement_chain, triples, housing_contact, fit_screw_temperatures, dt_s,
    // effects; added 2026-11-28, absent from older records: readers take them as unknown).
    static QJsonObject document(const DiagnosisReport &report);
    // The stored record: document() without the wall time (the same bytes whichever face ran
    // the diagnosis) plus "validate", the validation recording as the user named it.
    static QJsonObject storedResult(const DiagnosisReport &report, const QString &validate);
    // The switches of a document() or storedResult() ("options"); false (and `out` untouched)
    // for a record written before they were recorded.
    static bool switches(const QJsonObject &document, DiagnosisSwitches &out);
};

} // namespace driftlab

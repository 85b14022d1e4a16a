#pragma once
// The result of an ISO 230 evaluation (SessionIso230): ISO 230-2 positioning values of each
// test of a session's interferometer runs and the ISO 230-3-style drift summary, with the
// request it answers, as JSON and as a short text for the CLI and the GUI.
//
// The one owner of the ISO 230 JSON: the file `iso230 --json` writes and the record stored
// with the session (AnalysisResultKind::iso230(), read by the test report) are toJson(), and
// fromJson() reads it back. Schema version 1: "schema_version": 1.

#include "Iso230Drift.h"
#include "Iso230Positioning.h"
#include "Iso230Request.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <vector>

namespace driftlab {

class Iso230Report {
public:
    static constexpr int kSchemaVersion = 1;

    // leftOut: notes on runs left out (a partial last run).
    Iso230Report(const Iso230Request &request, const QString &sessionName, int referenceRun, std::vector<Iso230Test> tests,
                 Iso230DriftSummary drift, QStringList leftOut);
    // Reads a toJson() document back (the per-approach times of the targets are not in it);
    // throws std::invalid_argument naming the field for anything else.
    static Iso230Report fromJson(const QJsonObject &json);

    const Iso230Request &request() const { return m_request; }
    const QString &sessionName() const { return m_name; }
    const std::vector<Iso230Test> &tests() const { return m_tests; }
    const Iso230DriftSummary &drift() const { return m_drift; }
    int referenceRun() const { return m_referenceRun; }
    // Index into tests() of the test holding the reference run (0 when none does).
    int referenceTest() const;
    const QStringList &leftOut() const { return m_leftOut; }
    QJsonObject toJson() const;
    // A few lines: the reference test's axis values, their range over the tests, the
    // largest drift and, with a temperature, its slope.
    QString text() const;

private:
    Iso230Request m_request;
    QString m_name;
    int m_referenceRun = 0;
    std::vector<Iso230Test> m_tests;
    Iso230DriftSummary m_drift;
    QStringList m_leftOut;
};

} // namespace driftlab

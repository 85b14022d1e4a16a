#pragma once
// The ISO 230 section of a test report: the ISO 230-2 axis values per interferometer test,
// the reference test per target and direction with the ISO 230 view's positioning and drift
// figures, and the ISO 230-3 drift summary. Reads the result `iso230` stored with the session
// (SessionIso230::stored) or, without one, evaluates the default request; the numbers are the
// same Iso230Report the ISO 230 view and `driftlab-cli iso230 --json` show.
// Needs a QApplication (the figures are drawn by Iso230View's plots); no display.

#include <QtGlobal>

namespace driftlab {

class ReportDocument;
class ReportTemplate;
class SessionStore;

class ReportIso230Section {
public:
    static void write(ReportDocument &doc, const SessionStore &store, qint64 session, const ReportTemplate &look);
};

} // namespace driftlab

#pragma once
// The report step of the mismatch diagnosis (DiagnosisEngine): turns the forward selection's
// accepted effects into the report's steps, answer and explanation text, tries the empirical
// discrepancy term on the final model's residual (DiscrepancyTerm), explains a `none`, orders
// the candidates and lists B's predictions (baseline and corrected).

#include "CandidateFit.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"
#include "ForwardSelection.h"

#include <string>
#include <vector>

namespace driftlab {

class DiagnosisReportAssembler {
public:
    DiagnosisReportAssembler(double screwLength_m, const DiagnosisOptions &options);

    // Fills the report from the selection (`base`: the baseline's fit, the corrected model
    // when nothing was accepted).
    void assemble(DiagnosisReport &report, const ForwardSelection::Result &selection, const CandidateFit &base,
                  const DiagnosisRecording &train, const DiagnosisRecording &validate) const;

private:
    // Tries the empirical discrepancy term on the final model's residual; when it passes, the
    // answer gains "unexplained" and the corrected predictions include it. Returns the term's
    // value at B's interferometer points (empty when not accepted).
    std::vector<double> explainRest(DiagnosisReport &report, const CandidateFit &final, const DiagnosisRecording &train,
                                    const DiagnosisRecording &validate) const;
    // The explanation of `none`: the driver terms that could not be placed, or a residual that
    // is not plain noise, or noise (ResidualLocator::isLocated on the baseline's residual).
    static std::string noneExplanation(const DiagnosisReport &report, const std::vector<CandidateOutcome> &empiricalRound);

    double m_screwLength_m;
    DiagnosisOptions m_options;
};

} // namespace driftlab

#pragma once
// The diagnosis's switches in user words: the one place that names them for a person. The
// Diagnosis dock's check boxes and its answer, and the test report's diagnosis section, use
// these labels (the JSON keys are DiagnosisResultJson's, the CLI options DiagnoseCommand's).

#include "DiagnosisTypes.h"

#include <QString>

namespace driftlab {

class DiagnosisSwitchLabels {
public:
    static QString priors();
    static QString measurementChain();
    static QString triples();
    static QString housingContact();
    static QString screwTemperatures(); // no check box: `diagnose --fit-screw-temperatures`

    // "Priors on, Measurement chain off, Triples off, Housing contact on, Screw temperatures
    // fitted off": every switch with its state, in the dock's order.
    static QString summary(const DiagnosisSwitches &switches);
};

} // namespace driftlab

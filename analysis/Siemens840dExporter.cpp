#include "Siemens840dExporter.h"

#include "CompensationLaw.h"
#include "CompensationTable.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

std::string Siemens840dExporter::description() const
{
    return "SINUMERIK 840D temperature compensation: MD32750/MD32760, SD43900/SD43910/SD43920 as a "
           "synchronized action of R-parameter temperatures, and a setting-data table over temperature";
}

std::string Siemens840dExporter::reference() const
{
    return "SINUMERIK 840D sl Function Manual Extended Functions, K3 Compensations, 4.2 Temperature compensation; "
           "machine data MD32750, MD32760; setting data SD43900, SD43910, SD43920";
}

ExportResult Siemens840dExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const DataDrivenModel &m = law.model();
    const int first = o.firstVariable >= 0 ? o.firstVariable : 100;
    FormulaSyntax syntax;
    for (std::size_t i = 0; i < m.inputs.size(); ++i)
        syntax.inputs.push_back("$R[" + std::to_string(first + static_cast<int>(i)) + "]");
    const std::string &ax = o.axis;

    // K3: MD32760 limits the compensation travel per IPO cycle to factor * MD32000 * IPO cycle
    // (more is spread over several cycles, no alarm) and with it the gradient of the error line.
    // The notes give the model's largest gradient and that travel for the user to check.
    const double velocityFactor = 0.01; // MD32760 default
    double maxSlope = 0.0;
    const std::vector<double> temps = o.temperatures.values();
    std::vector<double> u(m.inputs.size());
    for (double T : temps) {
        std::fill(u.begin(), u.end(), T);
        maxSlope = std::max(maxSlope, std::fabs(law.slope_um_per_mm(u.data()) * 1e-3));
    }

    ExportResult r;
    std::ostringstream mpf;
    mpf << "; DriftLab thermal compensation, axis " << ax << ", model " << m.kind << " from " << model.source << "\n"
        << "; dK = SD43900 + SD43910 * (P - SD43920) = -E(P, T) / 1000 (mm); E = model thermal error in um\n"
        << "; machine data (set once, POWER ON):\n"
        << "; $MA_TEMP_COMP_TYPE[" << ax << "]=3\n"
        << "; $MA_COMP_ADD_VELO_FACTOR[" << ax << "]=" << CompensationLaw::number(velocityFactor, 6) << "\n"
        << "; inputs written by the PLC (degC):\n";
    for (std::size_t i = 0; i < m.inputs.size(); ++i)
        mpf << ";   " << syntax.inputs[i] << " = " << m.inputs[i].id << " (" << m.inputs[i].unit << ")\n";
    mpf << "$SA_TEMP_COMP_REF_POSITION[" << ax << "]=" << CompensationLaw::plain(law.referencePosition_mm(), 12) << "\n"
        << "IDS=1 WHENEVER TRUE DO $SA_TEMP_COMP_ABS_VALUE[" << ax << "]=" << law.compensationOffsetFormula(syntax)
        << " $SA_TEMP_COMP_SLOPE[" << ax << "]=" << law.compensationSlopeFormula(syntax) << "\n"
        << "M30\n";
    r.files.push_back({o.baseName + ".mpf", mpf.str()});
    r.notes.push_back("inputs are R parameters " + syntax.inputs.front() + ".. filled by the PLC in \u00b0C");
    r.notes.push_back("largest |SD43910| on " + CompensationLaw::number(o.temperatures.from, 6) + ".." +
                      CompensationLaw::number(o.temperatures.to, 6) + " \u00b0C: " + CompensationLaw::number(maxSlope, 6) +
                      " (MD32760 limits the gradient; default factor " + CompensationLaw::number(velocityFactor, 3) + ")");
    r.notes.push_back("MD32760 = " + CompensationLaw::number(velocityFactor, 3) + " with MD32000 = " +
                      CompensationLaw::number(o.maxAxisVelocity_mm_min, 6) + " mm/min and an IPO cycle of " +
                      CompensationLaw::number(o.ipoCycle_s * 1e3, 4) + " ms lets the compensation move " +
                      CompensationLaw::number(velocityFactor * o.maxAxisVelocity_mm_min / 60.0 * o.ipoCycle_s * 1e3, 4) +
                      " \u00b5m per IPO cycle");

    if (law.scalarTemperature()) {
        const CompensationTable t = CompensationTable::build(law, o, name());
        std::ostringstream table;
        table << "; SD43900/SD43910/SD43920 for axis " << ax << " against temperature (linear interpolation between rows: max "
              << CompensationLaw::number(t.interpolationError_um, 4) << " um)\n"
              << "T_degC;SD43900_mm;SD43910;SD43920_mm\n";
        for (double T : t.temperatures_C) {
            const std::vector<double> ut = law.inputsAt(T);
            table << CompensationLaw::number(T, 12) << ';' << CompensationLaw::number(-1e-3 * law.offset_um(ut.data()), 12)
                  << ';' << CompensationLaw::number(-1e-3 * law.slope_um_per_mm(ut.data()), 12) << ';'
                  << CompensationLaw::plain(law.referencePosition_mm(), 12) << '\n';
        }
        r.files.push_back({o.baseName + "_sd_table.csv", table.str()});
        r.approximationError_um = t.interpolationError_um;
    } else {
        r.notes.push_back("no setting-data table: the model takes " + std::to_string(m.inputs.size()) +
                          " inputs (the synchronized action is exact)");
    }
    return r;
}

} // namespace driftlab

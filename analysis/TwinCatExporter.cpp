#include "TwinCatExporter.h"

#include "CompensationLaw.h"
#include "CompensationTable.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

std::string TwinCatExporter::description() const
{
    return "Beckhoff TwinCAT CNC temperature compensation: P-AXIS-00271..00274 at one temperature and a "
           "TEMPC::offset_0 / coefficient table over temperature";
}

std::string TwinCatExporter::reference() const
{
    return "Beckhoff TF5200 TwinCAT CNC Axis Compensation, Temperature compensation; Axis parameters P-AXIS-00271 "
           "temp_comp, P-AXIS-00272 temp_comp_position_0, P-AXIS-00273 temp_comp_offset_0, P-AXIS-00274 "
           "temp_comp_coefficient";
}

ExportResult TwinCatExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const CompensationTable table = CompensationTable::build(law, o, name());
    const double T = CompensationTable::singleTemperature(o);
    const std::vector<double> u = law.inputsAt(T);
    // compensation = offset_0 + coefficient (P - position_0) = -E
    const long position0 = std::lround(law.referencePosition_mm() * 1e4);         // 0.1 um
    const long offset0 = std::lround(-law.offset_um(u.data()) * 10.0);            // 0.1 um
    const long coefficient = std::lround(-law.slope_um_per_mm(u.data()) * 1e3);   // um/m
    std::ostringstream lis;
    lis << "# DriftLab thermal compensation, axis " << o.axis << ", model " << law.model().kind << " at "
        << CompensationLaw::number(T, 6) << " degC\n"
        << "lr_param.temp_comp                  1\n"
        << "lr_param.temp_comp_position_0       " << position0 << "\n"
        << "lr_param.temp_comp_offset_0         " << offset0 << "\n"
        << "lr_param.temp_comp_coefficient      " << coefficient << "\n";
    double rounding = 0.0;
    for (double p : table.positions_mm) {
        const double stored = 0.1 * static_cast<double>(offset0) +
                              static_cast<double>(coefficient) * 1e-3 * (p - static_cast<double>(position0) * 1e-4);
        rounding = std::max(rounding, std::fabs(stored + law.error_um(p, u.data())));
    }
    std::ostringstream csv;
    csv << "T_degC,offset_0_0.1um,coefficient_um_per_m,position_0_0.1um\n";
    for (double t : table.temperatures_C) {
        const std::vector<double> ut = law.inputsAt(t);
        csv << CompensationLaw::number(t, 12) << ',' << CompensationLaw::number(-law.offset_um(ut.data()) * 10.0, 12) << ','
            << CompensationLaw::number(-law.slope_um_per_mm(ut.data()) * 1e3, 12) << ',' << position0 << '\n';
    }
    ExportResult r;
    r.files.push_back({o.baseName + "_axis.lis", lis.str()});
    r.files.push_back({o.baseName + "_tempc.csv", csv.str()});
    r.approximationError_um = std::max(rounding, table.interpolationError_um);
    r.notes.push_back("axis parameters at " + CompensationLaw::number(T, 6) + " \u00b0C, rounded to 0.1 \u00b5m and 1 \u00b5m/m: up to " +
                      CompensationLaw::number(rounding, 4) + " \u00b5m; the PLC table interpolated linearly in temperature: up to " +
                      CompensationLaw::number(table.interpolationError_um, 4) + " \u00b5m");
    return r;
}

} // namespace driftlab

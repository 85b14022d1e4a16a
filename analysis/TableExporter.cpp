#include "TableExporter.h"

#include "CompensationLaw.h"
#include "CompensationTable.h"

#include <sstream>

namespace driftlab {

std::string TableExporter::description() const
{
    return m_json ? "JSON table: thermal error and compensation over positions x temperatures"
                  : "CSV table: thermal error and compensation per temperature and position";
}

std::string TableExporter::reference() const
{
    return "DriftLab docs/export.md (generic table; RFC 4180 CSV, RFC 8259 JSON)";
}

ExportResult TableExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const CompensationTable t = CompensationTable::build(law, o, name());
    std::ostringstream out;
    auto list = [&](const std::vector<double> &v) {
        out << '[';
        for (std::size_t i = 0; i < v.size(); ++i)
            out << (i ? ", " : "") << CompensationLaw::number(v[i], 17);
        out << ']';
    };
    if (m_json) {
        out << "{\n \"format\": \"driftlab-compensation-table\", \"version\": 1,\n \"model\": \"" << law.model().kind
            << "\", \"axis\": \"" << o.axis << "\",\n \"sign\": \"compensation_um = -error_um\",\n \"positions_mm\": ";
        list(t.positions_mm);
        out << ",\n \"temperatures_C\": ";
        list(t.temperatures_C);
        out << ",\n \"error_um\": [";
        for (std::size_t j = 0; j < t.error_um.size(); ++j) {
            out << (j ? ",\n  " : "\n  ");
            list(t.error_um[j]);
        }
        out << "\n ],\n \"interpolation_error_um\": " << CompensationLaw::number(t.interpolationError_um, 17) << "\n}\n";
    } else {
        out << "temperature_C,position_mm,error_um,compensation_um\n";
        for (std::size_t j = 0; j < t.temperatures_C.size(); ++j)
            for (std::size_t i = 0; i < t.positions_mm.size(); ++i)
                out << CompensationLaw::number(t.temperatures_C[j], 17) << ',' << CompensationLaw::number(t.positions_mm[i], 17)
                    << ',' << CompensationLaw::number(t.error_um[j][i], 17) << ','
                    << CompensationLaw::number(-t.error_um[j][i], 17) << '\n';
    }
    ExportResult r;
    r.files.push_back({o.baseName + (m_json ? ".json" : ".csv"), out.str()});
    r.approximationError_um = t.interpolationError_um;
    r.notes.push_back("linear interpolation between the stored temperatures: up to " +
                      CompensationLaw::number(t.interpolationError_um, 4) + " \u00b5m");
    return r;
}

} // namespace driftlab

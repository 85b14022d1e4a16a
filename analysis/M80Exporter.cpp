#include "M80Exporter.h"

#include "CompensationLaw.h"
#include "CompensationTable.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

std::string M80Exporter::description() const
{
    return "Mitsubishi M80 register map (R5700.. pairs, 1 \u00b5m, low word first) and the register values over "
           "temperature and position";
}

std::string M80Exporter::reference() const
{
    return "Seed 003 (thermal error compensation on a Mitsubishi M80 through R registers in 1 \u00b5m steps); "
           "Mitsubishi M800/M80 Series PLC Interface Manual, R register device (16-bit words)";
}

int M80Exporter::lowRegister(const std::string &axis)
{
    if (axis == "X")
        return 5700;
    if (axis == "Y")
        return 5702;
    if (axis == "Z")
        return 5704;
    throw ExportRefused("m80: the seed-003 register map has X, Y and Z only, not '" + axis + "'");
}

void M80Exporter::split(std::int32_t value, std::uint16_t &low, std::uint16_t &high)
{
    const std::uint32_t bits = static_cast<std::uint32_t>(value);
    low = static_cast<std::uint16_t>(bits & 0xFFFFu);
    high = static_cast<std::uint16_t>(bits >> 16);
}

ExportResult M80Exporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const CompensationTable table = CompensationTable::build(law, o, name());
    const int low = lowRegister(o.axis);
    std::ostringstream map;
    map << "{\n \"format\": \"driftlab-register-map\", \"version\": 1, \"preset\": \"m80-seed003\",\n"
        << " \"unit_um\": 1, \"sign\": -1, \"word_order\": \"low-first\", \"signed\": true,\n \"axes\": {\n"
        << "  \"X\": [5700, 5701], \"Y\": [5702, 5703], \"Z\": [5704, 5705]\n },\n"
        << " \"axis\": \"" << o.axis << "\", \"model\": \"" << law.model().kind << "\"\n}\n";
    std::ostringstream csv;
    csv << "T_degC,position_mm,compensation_um,R" << low << ",R" << low + 1 << "\n";
    double rounding = 0.0;
    for (std::size_t j = 0; j < table.temperatures_C.size(); ++j)
        for (std::size_t i = 0; i < table.positions_mm.size(); ++i) {
            const double comp = -table.error_um[j][i];
            const std::int32_t v = static_cast<std::int32_t>(std::lround(comp));
            rounding = std::max(rounding, std::fabs(static_cast<double>(v) - comp));
            std::uint16_t lo, hi;
            split(v, lo, hi);
            csv << CompensationLaw::number(table.temperatures_C[j], 12) << ','
                << CompensationLaw::number(table.positions_mm[i], 12) << ',' << v << ',' << lo << ',' << hi << '\n';
        }
    ExportResult r;
    r.files.push_back({o.baseName + "_m80_map.json", map.str()});
    r.files.push_back({o.baseName + "_m80_registers.csv", csv.str()});
    r.approximationError_um = rounding;
    r.notes.push_back("register values are the compensation -E rounded to 1 \u00b5m (up to " + CompensationLaw::number(rounding, 3) +
                      " \u00b5m); a 32-bit two's-complement value, low word in R" + std::to_string(low));
    return r;
}

} // namespace driftlab

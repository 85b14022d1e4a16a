#include "CompensationTable.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

std::vector<double> CompensationTable::positions(const CompensationLaw &law, const ExportOptions &o)
{
    const bool unset = o.positions.from == 0.0 && o.positions.to == 0.0;
    return (unset ? law.defaultPositions() : o.positions).values();
}

double CompensationTable::singleTemperature(const ExportOptions &o)
{
    return std::isfinite(o.temperature) ? o.temperature : 0.5 * (o.temperatures.from + o.temperatures.to);
}

CompensationTable CompensationTable::build(const CompensationLaw &law, const ExportOptions &o, const std::string &target)
{
    if (!law.scalarTemperature())
        throw ExportRefused(target + ": a table over one temperature cannot hold a model of " +
                            std::to_string(law.inputCount()) +
                            " inputs; use a formula target (840d, fanuc, heidenhain), c, or the live loop");
    CompensationTable t;
    t.positions_mm = positions(law, o);
    t.temperatures_C = o.temperatures.values();
    for (double T : t.temperatures_C) {
        const std::vector<double> u = law.inputsAt(T);
        std::vector<double> row;
        for (double p : t.positions_mm)
            row.push_back(law.error_um(p, u.data()));
        t.error_um.push_back(row);
    }
    for (std::size_t j = 0; j + 1 < t.temperatures_C.size(); ++j) {
        const std::vector<double> u = law.inputsAt(0.5 * (t.temperatures_C[j] + t.temperatures_C[j + 1]));
        for (std::size_t i = 0; i < t.positions_mm.size(); ++i) {
            const double interpolated = 0.5 * (t.error_um[j][i] + t.error_um[j + 1][i]);
            t.interpolationError_um =
                std::max(t.interpolationError_um, std::fabs(interpolated - law.error_um(t.positions_mm[i], u.data())));
        }
    }
    return t;
}

} // namespace driftlab

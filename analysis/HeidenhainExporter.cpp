#include "HeidenhainExporter.h"

#include "CompensationLaw.h"
#include "CompensationTable.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

std::string HeidenhainExporter::description() const
{
    return "HEIDENHAIN TNC: TEMPCOMP formula on PLC temperature words (position-independent models) and "
           "*.COM compensation tables per temperature with a *.CMA selection file";
}

std::string HeidenhainExporter::reference() const
{
    return "HEIDENHAIN TNC 426/430 Technical Manual, 6.5.3 Temperature compensation (TEMPCOMP column); "
           "nonlinear axis-error compensation *.COM / *.CMA tables (PLC module 9095 selects the active line)";
}

ExportResult HeidenhainExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const DataDrivenModel &m = law.model();
    ExportResult r;
    if (m.kind != "synthetic") {
        const int first = o.firstVariable >= 0 ? o.firstVariable : 486;
        FormulaSyntax s;
        for (std::size_t i = 0; i < m.inputs.size(); ++i)
            s.inputs.push_back("W" + std::to_string(first + 2 * static_cast<int>(i)));
        std::ostringstream f;
        f << "; DriftLab TEMPCOMP for axis " << o.axis << ", model " << m.kind << " from " << model.source
          << ": compensation in mm = -E / 1000\n";
        for (std::size_t i = 0; i < m.inputs.size(); ++i)
            f << "; " << s.inputs[i] << " = " << m.inputs[i].id << " (degC)\n";
        f << "TEMPCOMP = " << law.compensationOffsetFormula(s) << "\n";
        r.files.push_back({o.baseName + "_tempcomp.txt", f.str()});
        r.notes.push_back("TEMPCOMP formula on PLC words " + s.inputs.front() + ".. (every other word), exact");
        if (!law.scalarTemperature())
            return r;
    }
    const CompensationTable t = CompensationTable::build(law, o, name());
    std::ostringstream cma;
    cma << "BEGIN " << o.baseName << ".CMA\nNR " << o.axis << "\n";
    for (std::size_t j = 0; j < t.temperatures_C.size(); ++j) {
        const std::string file = o.baseName + "_" + std::to_string(j) + ".COM";
        std::ostringstream com;
        com << "BEGIN " << file << " MM\n; temperature " << CompensationLaw::number(t.temperatures_C[j], 10)
            << " degC, compensation = -E / 1000 mm\nNR AXISPOS " << o.axis << "\n";
        for (std::size_t i = 0; i < t.positions_mm.size(); ++i)
            com << i << ' ' << CompensationLaw::number(t.positions_mm[i], 10) << ' '
                << CompensationLaw::number(-1e-3 * t.error_um[j][i], 10) << "\n";
        com << "[END]\n";
        r.files.push_back({file, com.str()});
        cma << j << ' ' << file << " ; " << CompensationLaw::number(t.temperatures_C[j], 10) << " degC\n";
    }
    cma << "[END]\n";
    r.files.push_back({o.baseName + ".CMA", cma.str()});
    // Nearest-line selection: the worst case is half a step away from a stored temperature.
    double worst = 0.0;
    for (std::size_t j = 0; j + 1 < t.temperatures_C.size(); ++j) {
        const std::vector<double> u = law.inputsAt(0.5 * (t.temperatures_C[j] + t.temperatures_C[j + 1]));
        for (std::size_t i = 0; i < t.positions_mm.size(); ++i) {
            const double e = law.error_um(t.positions_mm[i], u.data());
            worst = std::max({worst, std::fabs(e - t.error_um[j][i]), std::fabs(e - t.error_um[j + 1][i])});
        }
    }
    r.approximationError_um = std::max(r.approximationError_um, worst);
    r.notes.push_back("the PLC selects the .CMA line of the nearest temperature: up to " +
                      CompensationLaw::number(worst, 4) + " \u00b5m between the stored temperatures");
    return r;
}

} // namespace driftlab

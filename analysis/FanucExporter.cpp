#include "FanucExporter.h"

#include "CompensationLaw.h"

#include <sstream>

namespace driftlab {

std::string FanucExporter::description() const
{
    return "Fanuc custom macro B program: compensation from macro variables, written with G10 L2 P0 "
           "(external workpiece zero-point offset)";
}

std::string FanucExporter::reference() const
{
    return "FANUC Series 0i-MODEL F / 30i Operator's Manual: Custom macro (variables, arithmetic, EXP), "
           "system variables #5021.. (machine coordinates), G10 L2 P0 external workpiece zero point offset";
}

int FanucExporter::machinePositionVariable(const std::string &axis)
{
    static const std::string order = "XYZABC";
    const std::size_t k = axis.size() == 1 ? order.find(axis[0]) : std::string::npos;
    if (k == std::string::npos)
        throw ExportRefused("fanuc: axis '" + axis + "' is not one of X, Y, Z, A, B, C");
    return 5021 + static_cast<int>(k);
}

ExportResult FanucExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const DataDrivenModel &m = law.model();
    const int first = o.firstVariable >= 0 ? o.firstVariable : 500;
    FormulaSyntax s;
    s.open = '[';
    s.close = ']';
    s.digits = 8; // a longer constant raises alarm PS0003 (too many digits)
    for (std::size_t i = 0; i < m.inputs.size(); ++i)
        s.inputs.push_back("#" + std::to_string(first + static_cast<int>(i)));
    std::ostringstream p;
    p << "%\nO9100 (DRIFTLAB THERMAL COMP " << o.axis << ")\n"
      << "(MODEL " << m.kind << ", E = THERMAL ERROR UM, OFFSET = -E/1000 MM)\n";
    for (std::size_t i = 0; i < m.inputs.size(); ++i)
        p << "(" << s.inputs[i] << " = INPUT " << i << ", DEGC, SET BY PMC)\n";
    p << "#1=#" << machinePositionVariable(o.axis) << "\n"
      << "#2=" << law.compensationOffsetFormula(s) << "\n"
      << "#3=" << law.compensationSlopeFormula(s) << "\n"
      << "#4=#2+#3*[#1" << CompensationLaw::signedTerm(-law.referencePosition_mm(), s.digits) << "]\n"
      << "G10 L2 P0 " << o.axis << "#4\n"
      << "M99\n%\n";
    ExportResult r;
    r.files.push_back({o.baseName + ".nc", p.str()});
    r.notes.push_back("inputs are macro variables " + s.inputs.front() + ".. (\u00b0C) the PMC keeps current; call O9100 "
                      "periodically: the external offset is exact for the model at that moment");
    r.notes.push_back("constants written with 8 significant digits (the macro limit)");
    return r;
}

} // namespace driftlab

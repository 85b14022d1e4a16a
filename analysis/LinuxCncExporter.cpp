#include "LinuxCncExporter.h"

#include "CompensationLaw.h"
#include "CompensationTable.h"

#include <cctype>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

namespace {
constexpr std::size_t kMaxPoints = 256; // motion's compensation table size (LinuxCNC 2.9)
} // namespace

std::string LinuxCncExporter::description() const
{
    return "LinuxCNC COMP_FILE (types 0 and 1) at one temperature, INI and HAL settings for external offsets";
}

std::string LinuxCncExporter::reference() const
{
    return "LinuxCNC documentation: INI configuration, [JOINT_n] COMP_FILE / COMP_FILE_TYPE (screw compensation); "
           "External axis offsets (eoffset pins, [AXIS_L] OFFSET_AV_RATIO)";
}

ExportResult LinuxCncExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const CompensationLaw law = CompensationLaw::from(model);
    const CompensationTable table = CompensationTable::build(law, o, name());
    if (table.positions_mm.size() > kMaxPoints)
        throw ExportRefused("linuxcnc: a COMP_FILE holds at most " + std::to_string(kMaxPoints) + " points, the position grid has " +
                            std::to_string(table.positions_mm.size()) + " (use a larger --positions step)");
    const double T = CompensationTable::singleTemperature(o);
    const std::vector<double> u = law.inputsAt(T);
    static const std::string order = "XYZABC";
    const std::size_t joint = o.axis.size() == 1 ? order.find(o.axis[0]) : std::string::npos;
    if (joint == std::string::npos)
        throw ExportRefused("linuxcnc: axis '" + o.axis + "' is not one of X, Y, Z, A, B, C");
    std::string lower = o.axis;
    lower[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(lower[0])));

    std::ostringstream type0, type1;
    double drift = 0.0;
    for (std::size_t i = 0; i < table.positions_mm.size(); ++i) {
        const double p = table.positions_mm[i];
        const double e = law.error_um(p, u.data());
        const std::string trim = CompensationLaw::number(-1e-3 * e, 12);
        const std::string reached = CompensationLaw::number(p + 1e-3 * e, 12);
        type1 << CompensationLaw::number(p, 12) << ' ' << trim << ' ' << trim << '\n';
        type0 << CompensationLaw::number(p, 12) << ' ' << reached << ' ' << reached << '\n';
        for (const std::vector<double> &row : table.error_um)
            drift = std::max(drift, std::fabs(row[i] - e));
    }
    const std::string base = o.baseName;
    std::ostringstream ini, hal;
    ini << "# DriftLab thermal compensation, axis " << o.axis << ", model " << law.model().kind << " at "
        << CompensationLaw::number(T, 6) << " degC\n"
        << "[JOINT_" << joint << "]\nCOMP_FILE = " << base << "_type1.comp\nCOMP_FILE_TYPE = 1\n"
        << "# or: COMP_FILE = " << base << "_type0.comp / COMP_FILE_TYPE = 0\n\n"
        << "[AXIS_" << o.axis << "]\n# external offsets take this fraction of the axis' velocity and acceleration\n"
        << "OFFSET_AV_RATIO = 0.1\n";
    hal << "# external offsets for the live thermal loop: eoffset = counts * scale (1 count = 1 um)\n"
        << "net dl-eoffset-enable => axis." << lower << ".eoffset-enable\n"
        << "setp axis." << lower << ".eoffset-scale 0.001\n"
        << "net dl-eoffset-counts => axis." << lower << ".eoffset-counts\n"
        << "sets dl-eoffset-enable 1\n";
    ExportResult r;
    r.files.push_back({base + "_type1.comp", type1.str()});
    r.files.push_back({base + "_type0.comp", type0.str()});
    r.files.push_back({base + ".ini", ini.str()});
    r.files.push_back({base + ".hal", hal.str()});
    r.approximationError_um = drift;
    r.notes.push_back("COMP_FILE holds the model at " + CompensationLaw::number(T, 6) + " \u00b0C; over " +
                      CompensationLaw::number(o.temperatures.from, 6) + ".." + CompensationLaw::number(o.temperatures.to, 6) +
                      " \u00b0C the model moves up to " + CompensationLaw::number(drift, 4) +
                      " \u00b5m from it: drive that part through the external offsets (.hal)");
    return r;
}

} // namespace driftlab

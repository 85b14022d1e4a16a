#pragma once
// One controller export format (docs/export.md). Exporters are stateless; the registry
// (ModelExporterRegistry) lists them. export_() returns every file it would write, the notes
// a user must read (units, sign, what drives the inputs) and the approximation error where
// the target cannot express the model exactly; a model the target cannot express at all is
// refused with ExportRefused(reason). Nothing here touches the file system.
//
// Sign and units everywhere: the model predicts the thermal error E (um, actual minus nominal
// position, the interferometer convention); controllers are given the compensation -E in their
// own unit (mm unless stated).

#include "ExportableModel.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace driftlab {

class ExportRefused : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ExportRange {
    double from = 0.0, to = 0.0, step = 1.0;
    std::vector<double> values() const; // from, from + step, ..., to (to always included)
};

struct ExportOptions {
    std::string axis = "X";
    std::string baseName = "driftlab_comp"; // file names and identifiers (C target: a C identifier)
    // Table targets: positions (mm) and the characteristic temperature (degC). A position range
    // with from == to == 0 means "the model's own range" (synthetic: P0 .. P_ref, else 0 .. 1000).
    ExportRange positions{0.0, 0.0, 0.0};
    ExportRange temperatures{15.0, 40.0, 1.0};
    // Single-temperature targets (LinuxCNC COMP_FILE, Heidenhain .COM): NaN = middle of temperatures.
    double temperature = std::numeric_limits<double>::quiet_NaN();
    int firstVariable = -1;               // first controller variable of the inputs (-1: target default)
    double maxAxisVelocity_mm_min = 10000.0; // 840D MD32000, for the MD32760 check
    double ipoCycle_s = 0.004;               // 840D IPO cycle, for the MD32760 check
};

struct ExportFile {
    std::string name;    // relative to the output (the first file is the main one)
    std::string content;
};

struct ExportResult {
    std::vector<ExportFile> files;
    std::vector<std::string> notes;
    // Largest |exported - model| (um) over the table grid, 0 when exact (up to number format).
    double approximationError_um = 0.0;
};

class ModelExporter {
public:
    virtual ~ModelExporter() = default;
    virtual std::string name() const = 0;        // CLI target, e.g. "840d"
    virtual std::string description() const = 0;
    virtual std::string reference() const = 0;   // the manual section the format follows
    // Throws ExportRefused when the model cannot be expressed by this target.
    virtual ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const = 0;
};

} // namespace driftlab

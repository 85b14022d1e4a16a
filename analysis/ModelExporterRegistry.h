#pragma once
// Every controller export format, by CLI target name (840d, fanuc, heidenhain, linuxcnc,
// twincat, m80, c, csv, json). Owns its exporters; no global state.

#include "ModelExporter.h"

#include <memory>
#include <string>
#include <vector>

namespace driftlab {

class ModelExporterRegistry {
public:
    ModelExporterRegistry();
    const std::vector<std::unique_ptr<ModelExporter>> &exporters() const { return m_exporters; }
    // nullptr when unknown.
    const ModelExporter *find(const std::string &name) const;
    std::string names(const std::string &separator = "|") const;

private:
    std::vector<std::unique_ptr<ModelExporter>> m_exporters;
};

} // namespace driftlab

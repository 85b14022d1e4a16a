#pragma once
// Generic tables of the thermal error E (um) and the compensation -E against position and
// temperature, as CSV (one row per temperature and position) or JSON (a matrix), with the
// model, the units and the error of interpolating linearly between the stored temperatures.

#include "ModelExporter.h"

namespace driftlab {

class TableExporter : public ModelExporter {
public:
    explicit TableExporter(bool json) : m_json(json) {}
    std::string name() const override { return m_json ? "json" : "csv"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;

private:
    bool m_json;
};

} // namespace driftlab

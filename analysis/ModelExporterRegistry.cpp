#include "ModelExporterRegistry.h"

#include "CCodeExporter.h"
#include "FanucExporter.h"
#include "HeidenhainExporter.h"
#include "LinuxCncExporter.h"
#include "M80Exporter.h"
#include "Siemens840dExporter.h"
#include "TableExporter.h"
#include "TwinCatExporter.h"

namespace driftlab {

ModelExporterRegistry::ModelExporterRegistry()
{
    m_exporters.push_back(std::make_unique<Siemens840dExporter>());
    m_exporters.push_back(std::make_unique<FanucExporter>());
    m_exporters.push_back(std::make_unique<HeidenhainExporter>());
    m_exporters.push_back(std::make_unique<LinuxCncExporter>());
    m_exporters.push_back(std::make_unique<TwinCatExporter>());
    m_exporters.push_back(std::make_unique<M80Exporter>());
    m_exporters.push_back(std::make_unique<CCodeExporter>());
    m_exporters.push_back(std::make_unique<TableExporter>(false));
    m_exporters.push_back(std::make_unique<TableExporter>(true));
}

const ModelExporter *ModelExporterRegistry::find(const std::string &name) const
{
    for (const auto &e : m_exporters)
        if (e->name() == name)
            return e.get();
    return nullptr;
}

std::string ModelExporterRegistry::names(const std::string &separator) const
{
    std::string out;
    for (const auto &e : m_exporters)
        out += (out.empty() ? "" : separator) + e->name();
    return out;
}

} // namespace driftlab

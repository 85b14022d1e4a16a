#include "ImporterRegistry.h"

#include "BundleSessionImporter.h"
#include "CsvSessionImporter.h"
#include "RtlSessionImporter.h"
#include "SqliteSessionImporter.h"

namespace driftlab {

ImporterRegistry::ImporterRegistry()
{
    m_importers.push_back(std::make_unique<BundleSessionImporter>());
    m_importers.push_back(std::make_unique<SqliteSessionImporter>());
    m_importers.push_back(std::make_unique<RtlSessionImporter>());
    m_importers.push_back(std::make_unique<CsvSessionImporter>());
}

ImporterRegistry::~ImporterRegistry() = default;

const SessionImporter *ImporterRegistry::find(const QString &path) const
{
    for (const auto &i : m_importers)
        if (i->canImport(path))
            return i.get();
    return nullptr;
}

const SessionImporter *ImporterRegistry::byName(const QString &name) const
{
    for (const auto &i : m_importers)
        if (i->name() == name)
            return i.get();
    return nullptr;
}

} // namespace driftlab

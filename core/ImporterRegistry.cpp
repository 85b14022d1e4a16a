#include "ImporterRegistry.h"

#include "SessionImporters.h"

namespace driftlab {

ImporterRegistry::ImporterRegistry()
{
    for (SessionImporter (*make)() : {bundleSessionImporter, sqliteSessionImporter, rtlSessionImporter, csvSessionImporter})
        m_importers.push_back(std::make_unique<SessionImporter>(make()));
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

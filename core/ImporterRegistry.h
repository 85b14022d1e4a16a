#pragma once
// The importers DriftLab knows (SessionImporter), in the order they are asked: a bundle
// (folder with manifest.json, or .zip), an SQLite session database (.sqlite, .db: its sessions
// copied), an interferometer .rtl file (added to a session), a CSV table (with a column map).

#include "SessionImporter.h"

#include <memory>
#include <vector>

namespace driftlab {

class ImporterRegistry {
public:
    ImporterRegistry();
    ~ImporterRegistry();
    const std::vector<std::unique_ptr<SessionImporter>> &importers() const { return m_importers; }
    const SessionImporter *find(const QString &path) const; // nullptr: nothing imports it
    const SessionImporter *byName(const QString &name) const;

private:
    std::vector<std::unique_ptr<SessionImporter>> m_importers;
};

} // namespace driftlab

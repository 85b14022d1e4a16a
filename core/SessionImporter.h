#pragma once
// One kind of file DriftLab imports into a session database (in the manner of PlotJuggler's
// DataLoader): whether it takes a path, and the import itself. ImporterRegistry holds one of
// each (bundle, SQLite database, .rtl interferometer file, CSV table); the GUI's drag and drop
// and `driftlab-cli import` find the importer of a path there.

#include <QList>
#include <QString>

#include <functional>
#include <utility>

namespace driftlab {

class SessionStore;

class SessionImporter {
public:
    using Progress = std::function<bool(double fraction)>; // 0..1; return false to cancel
    struct Options {
        bool allowDuplicate = false; // import a second copy of a recording the store holds
        qint64 session = 0;          // importers that add to an existing session (.rtl)
        QString columnMap;           // a CSV table's column map file (CsvColumnMap)
        Progress progress;
    };

    using CanImport = std::function<bool(const QString &path)>;
    using Import = std::function<QList<qint64>(const QString &path, SessionStore &store, const Options &options)>;

    // An importer is a record: its name and description, and its two functions
    // (SessionImporters.h lists the importers there are).
    SessionImporter(QString name, QString description, CanImport canImport, Import import, bool needsColumnMap = false)
        : m_name(std::move(name)), m_description(std::move(description)), m_canImport(std::move(canImport)),
          m_import(std::move(import)), m_needsColumnMap(needsColumnMap)
    {
    }
    QString name() const { return m_name; }               // "bundle", "sqlite", "rtl", "csv"
    QString description() const { return m_description; } // for menus and --help
    // From the path alone (its suffix, or a bundle folder's manifest.json); reads nothing else.
    bool canImport(const QString &path) const { return m_canImport(path); }
    // Whether import() needs Options::columnMap (the GUI then asks with its CSV dialog).
    bool needsColumnMap() const { return m_needsColumnMap; }
    // Imports into store (a bundle, a table or an .rtl file all or nothing; a database session by
    // session, each verified); returns the ids of the sessions created or added to.
    // Throws: std::invalid_argument for a request that cannot run (a missing option), the
    // format's own error naming file and field, DuplicateSessionError, StorageError; a
    // cancelled import throws std::runtime_error (StorageError for a database copy).
    QList<qint64> import(const QString &path, SessionStore &store, const Options &options) const
    {
        return m_import(path, store, options);
    }

private:
    QString m_name, m_description;
    CanImport m_canImport;
    Import m_import;
    bool m_needsColumnMap = false;
};

} // namespace driftlab

#pragma once
// One kind of file DriftLab imports into a session database (in the manner of PlotJuggler's
// DataLoader): whether it takes a path, and the import itself. ImporterRegistry holds one of
// each (bundle, SQLite database, .rtl interferometer file, CSV table); the GUI's drag and drop
// and `driftlab-cli import` find the importer of a path there.

#include <QList>
#include <QString>

#include <functional>

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

    virtual ~SessionImporter() = default;
    virtual QString name() const = 0;        // "bundle", "sqlite", "rtl", "csv"
    virtual QString description() const = 0; // for menus and --help
    // From the path alone (its suffix, or a bundle folder's manifest.json); reads nothing else.
    virtual bool canImport(const QString &path) const = 0;
    // Whether import() needs Options::columnMap (the GUI then asks with its CSV dialog).
    virtual bool needsColumnMap() const { return false; }
    // Imports into store (a bundle, a table or an .rtl file all or nothing; a database session by
    // session, each verified); returns the ids of the sessions created or added to.
    // Throws: std::invalid_argument for a request that cannot run (a missing option), the
    // format's own error naming file and field, DuplicateSessionError, StorageError; a
    // cancelled import throws std::runtime_error (StorageError for a database copy).
    virtual QList<qint64> import(const QString &path, SessionStore &store, const Options &options) const = 0;
};

} // namespace driftlab

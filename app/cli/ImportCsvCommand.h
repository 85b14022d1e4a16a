#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli import-csv FILE --map MAP.json [--db DB] [--name NAME] [--started ISO] [--json FILE]:
// turns one CSV table (a data logger's export) into a session through a column map;
// import-csv FILE --guess-map MAP.json writes a starting map guessed from the file instead.
class ImportCsvCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("import-csv"); }
    QString summary() const override;
    int run(const QStringList &args) override;

private:
    static int writeGuess(const QStringList &files, const QString &target, bool force);
};

} // namespace driftlab

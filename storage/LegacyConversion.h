#pragma once
// The data conversions of the schema steps that rewrite rows (SchemaMigrator runs the DDL and
// calls these inside the same transaction): version 1 -> 2 moves the narrow samples table into
// blocks and mipmap levels, 2 -> 3 gives every session a UUID.

#include <QSqlDatabase>
#include <QString>

namespace driftlab {

class SampleChannels;

class LegacyConversion {
public:
    static void samplesToBlocks(const QSqlDatabase &db, const QString &path, SampleChannels &samples);
    static void assignMissingUuids(const QSqlDatabase &db, const QString &path);
};

} // namespace driftlab

#pragma once
// Where SampleChannels' blocks and mipmap rows go: one interface, two back ends chosen by the
// connection (make()): QtSqlSampleBackend (SQLite, or a QPSQL connection without a usable
// libpq handle) and PgSampleBackend (a central store: bytea parameters and results travel
// binary through libpq, PgBinaryStatement). The SQL is written once, in SampleChannels, with
// '?' placeholders; a back end only runs it.

#include <QByteArray>
#include <QSqlDatabase>
#include <QString>
#include <QVariant>
#include <QVector>

#include <functional>
#include <memory>

namespace driftlab {

class SampleBackend {
public:
    // One result row; columns by index.
    class Row {
    public:
        virtual ~Row() = default;
        virtual qint64 integer(int column) const = 0;
        virtual double real(int column) const = 0;
        virtual QByteArray bytes(int column) const = 0; // valid for the length of the call
    };
    using RowVisitor = std::function<void(const Row &)>;

    static std::unique_ptr<SampleBackend> make(const QSqlDatabase &db, const QString &path);
    virtual ~SampleBackend() = default;

    // Runs a write statement (sql is a string literal: back ends may cache by its address).
    // Throws StorageError naming the store and `what`.
    virtual void exec(const char *sql, const QVector<QVariant> &params, const QString &what) = 0;
    // Runs a query and calls row() for each result row, in order.
    virtual void query(const char *sql, const QVector<QVariant> &params, const QString &what, const RowVisitor &row) const = 0;
};

} // namespace driftlab

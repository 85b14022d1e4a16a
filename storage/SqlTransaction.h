#pragma once
// One transaction on a raw QSqlDatabase for the length of a block (RAII), for the code that runs
// before a SessionStore exists (SchemaMigrator, CentralSchema: they set up the schema the store
// opens), where StoreTransaction cannot be used. Begins on construction, rolls back when the
// block is left without commit(); failures throw StorageError "<database>: <what>: <reason>".

#include <QSqlDatabase>
#include <QString>

namespace driftlab {

class SqlTransaction {
public:
    SqlTransaction(QSqlDatabase &db, const QString &whatIfNotBegun); // e.g. "cannot begin migration"
    ~SqlTransaction();                                              // rollback unless committed
    SqlTransaction(const SqlTransaction &) = delete;
    SqlTransaction &operator=(const SqlTransaction &) = delete;

    void commit(const QString &whatIfNotCommitted); // a failed commit is rolled back and throws

private:
    QSqlDatabase &m_db;
    bool m_open = true;
};

} // namespace driftlab

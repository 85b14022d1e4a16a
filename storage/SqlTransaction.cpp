#include "SqlTransaction.h"

#include "StorageError.h"

#include <QSqlError>

namespace driftlab {

namespace {
[[noreturn]] void fail(const QSqlDatabase &db, const QString &what, const QSqlError &error)
{
    throw StorageError(QStringLiteral("%1: %2: %3").arg(db.databaseName(), what, error.text()).toStdString());
}
} // namespace

SqlTransaction::SqlTransaction(QSqlDatabase &db, const QString &whatIfNotBegun) : m_db(db)
{
    if (!m_db.transaction())
        fail(m_db, whatIfNotBegun, m_db.lastError());
}

SqlTransaction::~SqlTransaction()
{
    if (m_open)
        m_db.rollback();
}

void SqlTransaction::commit(const QString &whatIfNotCommitted)
{
    m_open = false;
    if (!m_db.commit()) {
        const QSqlError error = m_db.lastError();
        m_db.rollback();
        fail(m_db, whatIfNotCommitted, error);
    }
}

} // namespace driftlab

#include "QtSqlSampleBackend.h"

#include "SqlSupport.h"

namespace driftlab {

namespace {
class QueryRow : public SampleBackend::Row {
public:
    explicit QueryRow(const QSqlQuery &q) : m_q(q) {}
    qint64 integer(int column) const override { return m_q.value(column).toLongLong(); }
    double real(int column) const override { return m_q.value(column).toDouble(); }
    QByteArray bytes(int column) const override { return m_q.value(column).toByteArray(); }

private:
    const QSqlQuery &m_q;
};
} // namespace

QtSqlSampleBackend::QtSqlSampleBackend(const QSqlDatabase &db, const QString &path) : m_db(db), m_path(path) {}

void QtSqlSampleBackend::exec(const char *sql, const QVector<QVariant> &params, const QString &what)
{
    auto it = m_writes.find(sql);
    if (it == m_writes.end())
        it = m_writes.insert(sql, SqlSupport::prepared(m_db, m_path, QString::fromLatin1(sql)));
    QSqlQuery &q = it.value();
    for (int i = 0; i < params.size(); ++i)
        q.bindValue(i, params[i]);
    SqlSupport::run(q, m_path, what);
}

void QtSqlSampleBackend::query(const char *sql, const QVector<QVariant> &params, const QString &what, const RowVisitor &row) const
{
    QSqlQuery q = SqlSupport::select(m_db, m_path, QString::fromLatin1(sql), QVariantList(params.cbegin(), params.cend()), what);
    const QueryRow current(q);
    while (q.next())
        row(current);
}

} // namespace driftlab

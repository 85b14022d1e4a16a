#include "PgSampleBackend.h"

#include "PgBinaryStatement.h"

namespace driftlab {

namespace {
class BinaryRow : public SampleBackend::Row {
public:
    explicit BinaryRow(const QVector<QByteArray> &values) : m_values(values) {}
    qint64 integer(int column) const override { return PgBinaryStatement::int64(m_values[column]); }
    double real(int column) const override { return PgBinaryStatement::float64(m_values[column]); }
    QByteArray bytes(int column) const override { return m_values[column]; }

private:
    const QVector<QByteArray> &m_values;
};
} // namespace

PgSampleBackend::PgSampleBackend(const QSqlDatabase &db, const QString &path) : m_db(db), m_path(path) {}

QByteArray PgSampleBackend::numbered(const char *sql)
{
    QByteArray out;
    int n = 0;
    for (const char *c = sql; *c; ++c) {
        if (*c == '?')
            out += '$' + QByteArray::number(++n);
        else
            out += *c;
    }
    return out;
}

void PgSampleBackend::exec(const char *sql, const QVector<QVariant> &params, const QString &what)
{
    PgBinaryStatement::exec(m_db, m_path, numbered(sql).constData(), params, what);
}

void PgSampleBackend::query(const char *sql, const QVector<QVariant> &params, const QString &what, const RowVisitor &row) const
{
    PgBinaryStatement::query(m_db, m_path, numbered(sql).constData(), params, what,
                             [&](const QVector<QByteArray> &values) { row(BinaryRow(values)); });
}

} // namespace driftlab

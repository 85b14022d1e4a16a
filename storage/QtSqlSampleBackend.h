#pragma once
// SampleBackend through QtSql: prepared statements (write statements kept and reused), values
// as QVariants.

#include "SampleBackend.h"

#include <QHash>
#include <QSqlQuery>

namespace driftlab {

class QtSqlSampleBackend : public SampleBackend {
public:
    QtSqlSampleBackend(const QSqlDatabase &db, const QString &path);
    void exec(const char *sql, const QVector<QVariant> &params, const QString &what) override;
    void query(const char *sql, const QVector<QVariant> &params, const QString &what, const RowVisitor &row) const override;

private:
    QSqlDatabase m_db;
    QString m_path;
    QHash<const char *, QSqlQuery> m_writes; // prepared write statements, reused
};

} // namespace driftlab

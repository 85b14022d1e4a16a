#pragma once
// SampleBackend on a central store through libpq (PgBinaryStatement): byte arrays go to the
// server as binary bytea parameters and come back as binary results, on the connection of the
// store's QPSQL database and so inside its transaction. '?' placeholders become $1, $2, ...

#include "SampleBackend.h"

namespace driftlab {

class PgSampleBackend : public SampleBackend {
public:
    PgSampleBackend(const QSqlDatabase &db, const QString &path);
    void exec(const char *sql, const QVector<QVariant> &params, const QString &what) override;
    void query(const char *sql, const QVector<QVariant> &params, const QString &what, const RowVisitor &row) const override;
    // sql with its '?' placeholders numbered as PostgreSQL's $1, $2, ... (no '?' in literals).
    static QByteArray numbered(const char *sql);

private:
    QSqlDatabase m_db;
    QString m_path;
};

} // namespace driftlab

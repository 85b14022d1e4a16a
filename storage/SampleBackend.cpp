#include "SampleBackend.h"

#include "PgBinaryStatement.h"
#include "PgSampleBackend.h"
#include "QtSqlSampleBackend.h"

namespace driftlab {

std::unique_ptr<SampleBackend> SampleBackend::make(const QSqlDatabase &db, const QString &path)
{
    if (PgBinaryStatement::usable(db))
        return std::make_unique<PgSampleBackend>(db, path);
    return std::make_unique<QtSqlSampleBackend>(db, path);
}

} // namespace driftlab

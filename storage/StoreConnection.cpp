#include "StoreConnection.h"

#include "CentralConnection.h"
#include "SchemaMigrator.h"
#include "SqlSupport.h"
#include "StorageError.h"

#include <QAtomicInteger>
#include <QFile>
#include <QFileInfo>
#include <QSqlError>
#include <QSqlQuery>
#include <QUrl>

#include <cerrno>
#include <cstring>

#include <unistd.h>

namespace driftlab {

namespace {
QAtomicInteger<quint64> g_connectionCounter;
} // namespace

bool StoreConnection::isCentral(const QString &path)
{
    return path.startsWith(QLatin1String("postgresql://")) || path.startsWith(QLatin1String("postgres://"));
}

QString StoreConnection::displayPath(const QString &path)
{
    if (!isCentral(path))
        return path;
    QUrl url(path);
    url.setPassword(QString());
    return url.toString();
}

StoreConnection::StoreConnection(const QString &path)
    : m_path(displayPath(path)), m_name(QStringLiteral("driftlab-store-%1").arg(++g_connectionCounter))
{
    try {
        if (isCentral(path))
            openCentral(path);
        else
            openSqlite(path);
    } catch (...) {
        m_db.close();
        m_link.reset();
        m_db = QSqlDatabase();
        QSqlDatabase::removeDatabase(m_name);
        throw;
    }
}

StoreConnection::~StoreConnection()
{
    m_db.close();
    m_link.reset(); // after the close: its watchdog also guards the last rollback
    m_db = QSqlDatabase();
    QSqlDatabase::removeDatabase(m_name);
}

void StoreConnection::openSqlite(const QString &path)
{
    m_db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), m_name);
    const QFileInfo file(path);
    const QFileInfo dir(file.absolutePath());
    if (!dir.isDir())
        throw StorageError(QStringLiteral("%1: folder %2 does not exist").arg(path, dir.filePath()).toStdString());
    // Read-only media (a write-protected share, a DVD, a read-only mount): a database whose
    // folder cannot be written cannot get its -wal and -shm files, so it is opened read-only
    // (immutable unless a WAL file is there to be read); every write is then refused with
    // SQLITE_READONLY, reported as read-only by SqlSupport. A new database there is refused.
    const QByteArray native = QFile::encodeName(dir.absoluteFilePath());
    const bool folderWritable = ::access(native.constData(), W_OK) == 0;
    const int folderErrno = folderWritable ? 0 : errno;
    if (!file.exists() && !folderWritable)
        throw StorageError(QStringLiteral("%1: cannot create the database: folder %2 is read-only (%3)")
                               .arg(path, dir.absoluteFilePath(), QString::fromLocal8Bit(std::strerror(folderErrno)))
                               .toStdString());
    m_readOnly = !folderWritable || (file.exists() && ::access(QFile::encodeName(file.absoluteFilePath()).constData(), W_OK) != 0);
    if (m_readOnly) {
        const QFileInfo wal(file.absoluteFilePath() + QStringLiteral("-wal"));
        QUrl uri = QUrl::fromLocalFile(file.absoluteFilePath());
        uri.setScheme(QStringLiteral("file"));
        uri.setQuery(wal.exists() && wal.size() > 0 ? QStringLiteral("mode=ro") : QStringLiteral("immutable=1"));
        m_db.setDatabaseName(uri.toString(QUrl::FullyEncoded));
        m_db.setConnectOptions(QStringLiteral("QSQLITE_OPEN_URI;QSQLITE_OPEN_READONLY;QSQLITE_BUSY_TIMEOUT=5000"));
    } else {
        m_db.setDatabaseName(path);
        m_db.setConnectOptions(QStringLiteral("QSQLITE_BUSY_TIMEOUT=5000"));
    }
    if (!m_db.open())
        SqlSupport::fail(path, QStringLiteral("cannot open database"), m_db.lastError());
    QSqlQuery pragma(m_db);
    if (m_readOnly) {
        if (!pragma.exec(QStringLiteral("PRAGMA schema_version")))
            SqlSupport::fail(path, QStringLiteral("cannot read (not an SQLite database?)"), pragma.lastError());
        pragma.exec(QStringLiteral("PRAGMA foreign_keys=ON"));
        if (SchemaMigrator::version(m_db) < SchemaMigrator::currentVersion())
            throw StorageError(QStringLiteral("%1: read-only: its schema version %2 needs an upgrade to %3, which writes; "
                                              "copy the file to writable storage to open it")
                                   .arg(path)
                                   .arg(SchemaMigrator::version(m_db))
                                   .arg(SchemaMigrator::currentVersion())
                                   .toStdString());
    } else {
        // WAL: readers see committed data while a recording writes.
        if (!pragma.exec(QStringLiteral("PRAGMA journal_mode=WAL")))
            SqlSupport::fail(path, QStringLiteral("cannot enable WAL (not an SQLite database?)"), pragma.lastError());
        pragma.exec(QStringLiteral("PRAGMA foreign_keys=ON"));
        pragma.exec(QStringLiteral("PRAGMA synchronous=NORMAL"));
    }
}

void StoreConnection::openCentral(const QString &url)
{
    if (!QSqlDatabase::isDriverAvailable(QStringLiteral("QPSQL")))
        throw StorageError(QStringLiteral("%1: Qt's PostgreSQL driver (QPSQL) is not installed (Debian package libqt5sql5-psql)")
                               .arg(m_path)
                               .toStdString());
    m_central = true;
    m_db = QSqlDatabase::addDatabase(QStringLiteral("QPSQL"), m_name);
    m_link = std::make_unique<CentralConnection>(m_db, url, m_path); // address, time limits, stall watchdog
}

} // namespace driftlab

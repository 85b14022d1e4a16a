#include "CentralConnection.h"

#include "SqlSupport.h"
#include "StorageError.h"

#include <QHash>
#include <QSqlDriver>
#include <QSqlError>
#include <QSqlQuery>
#include <QUrl>
#include <QVariant>

#include <libpq-fe.h>

#include <algorithm>
#include <chrono>

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

namespace driftlab {

namespace {

std::mutex g_notesMutex;
QHash<QString, QString> g_notes; // store address -> what the watchdog did

int socketOf(const QSqlDatabase &db)
{
    if (!db.driver())
        return -1;
    const QVariant h = db.driver()->handle();
    if (!h.isValid() || qstrcmp(h.typeName(), "PGconn*") != 0)
        return -1;
    PGconn *conn = *static_cast<PGconn *const *>(h.constData());
    return conn ? PQsocket(conn) : -1;
}

} // namespace

int CentralConnection::timeout_s()
{
    const QByteArray env = qgetenv("DRIFTLAB_PG_TIMEOUT_S");
    if (env.isEmpty())
        return kDefaultTimeout_s;
    bool ok = false;
    const int s = env.trimmed().toInt(&ok);
    if (!ok || s < 1 || s > 86400)
        throw StorageError(QStringLiteral("DRIFTLAB_PG_TIMEOUT_S='%1': expected a whole number of seconds from 1 to 86400")
                               .arg(QString::fromLocal8Bit(env))
                               .toStdString());
    return s;
}

CentralConnection::CentralConnection(QSqlDatabase &db, const QString &url, const QString &path) : m_path(path), m_limit_s(timeout_s())
{
    // postgresql://[user[:password]@]host[:port]/database: libpq finds a password the URL
    // lacks in PGPASSWORD or ~/.pgpass (PGPASSFILE), so none needs to be written in a file of ours.
    const QUrl u(url);
    if (!u.isValid() || u.host().isEmpty() || u.path().size() < 2)
        throw StorageError(QStringLiteral("%1: expected postgresql://[USER@]HOST[:PORT]/DATABASE").arg(m_path).toStdString());
    db.setHostName(u.host());
    db.setPort(u.port(5432));
    db.setDatabaseName(u.path().mid(1));
    if (!u.userName().isEmpty())
        db.setUserName(u.userName());
    if (!u.password().isEmpty())
        db.setPassword(u.password());
    // Keepalive probes start after a third of the limit of silence and give up after three
    // unanswered ones; unacknowledged data is dropped after the limit (tcp_user_timeout).
    const int idle = std::max(1, m_limit_s / 3);
    const int interval = std::max(1, (m_limit_s - idle) / 3);
    QString options = QStringLiteral("connect_timeout=5;application_name=driftlab;keepalives=1;keepalives_idle=%1;"
                                     "keepalives_interval=%2;keepalives_count=3;tcp_user_timeout=%3")
                          .arg(idle)
                          .arg(interval)
                          .arg(1000 * m_limit_s);
    if (u.hasQuery())
        options += QLatin1Char(';') + u.query().replace(QLatin1Char('&'), QLatin1Char(';'));
    db.setConnectOptions(options);
    if (!db.open())
        SqlSupport::fail(m_path, QStringLiteral("cannot connect to the central store"), db.lastError());
    QSqlQuery q(db);
    if (!q.exec(QStringLiteral("SET statement_timeout = '%1s'").arg(m_limit_s)))
        SqlSupport::fail(m_path, QStringLiteral("cannot set the statement time limit"), q.lastError());
    // A duplicate of libpq's socket: the watchdog never touches a number the process may have
    // given to another file after libpq closed its own (the socket lives until both are closed).
    const int fd = socketOf(db);
    m_socket = fd >= 0 ? ::fcntl(fd, F_DUPFD_CLOEXEC, 0) : -1;
    if (m_socket >= 0)
        m_watchdog = std::thread([this] { watch(); });
}

CentralConnection::~CentralConnection()
{
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    if (m_watchdog.joinable())
        m_watchdog.join();
    if (m_socket >= 0)
        ::close(m_socket);
    std::lock_guard<std::mutex> lock(g_notesMutex);
    g_notes.remove(m_path);
}

QString CentralConnection::stallNote(const QString &path)
{
    std::lock_guard<std::mutex> lock(g_notesMutex);
    return g_notes.value(path);
}

// Every quarter second: has DriftLab sent data more recently than it received any (a request
// waiting for its answer), and has that request waited for the limit? Then the server is stalled:
// shutting the socket down makes libpq's blocked wait return with a lost connection (the
// server rolls the open transaction back when it notices). An idle connection (the last data
// was the server's answer) is never touched.
void CentralConnection::watch()
{
    const quint32 limit_ms = static_cast<quint32>(m_limit_s) * 1000u;
    std::unique_lock<std::mutex> lock(m_mutex);
    while (!m_wake.wait_for(lock, std::chrono::milliseconds(250), [this] { return m_stop; })) {
        tcp_info info{};
        socklen_t size = sizeof info;
        if (::getsockopt(m_socket, IPPROTO_TCP, TCP_INFO, &info, &size) != 0)
            return;
        // Sent more recently than received: a request waits for its answer, since the last send
        // (a long upload keeps sending, so only a request that has been waiting counts).
        const bool waiting = info.tcpi_last_data_sent < info.tcpi_last_data_recv;
        if (!waiting || info.tcpi_last_data_sent < limit_ms)
            continue;
        {
            std::lock_guard<std::mutex> notes(g_notesMutex);
            g_notes.insert(m_path, QStringLiteral("the server did not answer for %1 s (time limit DRIFTLAB_PG_TIMEOUT_S = %2 s); DriftLab "
                                                  "closed the connection, and the server rolls back what was not committed")
                                       .arg(info.tcpi_last_data_sent / 1000)
                                       .arg(m_limit_s));
        }
        ::shutdown(m_socket, SHUT_RDWR);
        return;
    }
}

} // namespace driftlab

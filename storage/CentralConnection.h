#pragma once
// The connection to a central store (PostgreSQL through Qt's QPSQL driver), in one place for
// every command and the GUI: the address, the time limits and the stall watchdog.
//
// Time limits (docs/storage.md, "Time limits"): connecting has connect_timeout; after that the
// server gets `statement_timeout` = the limit (it cancels a statement that runs longer), TCP
// keepalive and tcp_user_timeout tell the kernel to drop a peer that no longer answers, and a
// watchdog thread closes the socket when DriftLab has sent a request and heard nothing for
// the limit (a stalled server, e.g. a stopped backend, whose kernel still acknowledges
// keepalives). The limit is DRIFTLAB_PG_TIMEOUT_S seconds (default 30).

#include <QSqlDatabase>
#include <QString>

#include <condition_variable>
#include <mutex>
#include <thread>

namespace driftlab {

class CentralConnection {
public:
    static constexpr int kDefaultTimeout_s = 30;
    // DRIFTLAB_PG_TIMEOUT_S, or the default; throws StorageError naming the variable when it
    // is not a whole number of seconds from 1 to 86400.
    static int timeout_s();

    // Opens db (a QPSQL connection added by the caller) to the address url; path is the address
    // without a password, for messages. Throws StorageError.
    CentralConnection(QSqlDatabase &db, const QString &url, const QString &path);
    ~CentralConnection();
    CentralConnection(const CentralConnection &) = delete;
    CentralConnection &operator=(const CentralConnection &) = delete;

    int limit_s() const { return m_limit_s; }
    // What the watchdog did to the connection of the store at path (empty if nothing): added to
    // the message of an error that lost the connection.
    static QString stallNote(const QString &path);

private:
    void watch();

    QString m_path;
    int m_limit_s = kDefaultTimeout_s;
    int m_socket = -1;
    std::mutex m_mutex;
    std::condition_variable m_wake;
    bool m_stop = false;
    std::thread m_watchdog;
};

} // namespace driftlab

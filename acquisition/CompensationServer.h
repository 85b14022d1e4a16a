#pragma once
// The controller side of a live compensation loop, for the simulated rig: a Modbus TCP server
// (Qt SerialBus QModbusTcpServer, on its own thread) holding the register pairs of an
// OffsetRegisterMap. Every accepted write is decoded with the map (sign, word order,
// resolution) and the sink gets every entry's offset in um, as a CNC applies an external
// machine-coordinate offset (or interpolates a live compensation table's support points,
// OffsetRegisterMap::offsetAt). A client writes both words of a pair in one request
// (CompensationLoop does), so the sink never sees half a value; a write of one word alone is
// decoded with the other word as it stands.

#include "OffsetRegisterMap.h"

#include <QString>
#include <QVector>

#include <atomic>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

class QEventLoop;

namespace driftlab {

class CompensationServer {
public:
    // Called on the server's thread after each write: the offset of every map entry, in um.
    using Sink = std::function<void(const QVector<double> &entryOffsets_um)>;

    CompensationServer(const QString &host, int port, const OffsetRegisterMap &map, Sink sink);
    ~CompensationServer(); // stops the server
    CompensationServer(const CompensationServer &) = delete;
    CompensationServer &operator=(const CompensationServer &) = delete;

    // Starts listening; throws std::runtime_error naming the address when it cannot.
    void start();
    void stop();
    bool listening() const { return m_listening; }
    QString address() const;               // "HOST:PORT"
    QVector<double> offsets_um() const;    // per map axis, what the registers hold now
    long long writes() const { return m_writes; }

private:
    void run(std::promise<QString> *ready);

    QString m_host;
    int m_port;
    OffsetRegisterMap m_map;
    Sink m_sink;
    std::thread m_thread;
    std::atomic<bool> m_listening{false};
    std::atomic<long long> m_writes{0};
    mutable std::mutex m_mutex; // guards m_loop, m_offsets
    QEventLoop *m_loop = nullptr;
    bool m_stopRequested = false;
    QVector<double> m_offsets;
};

} // namespace driftlab

#pragma once
// Independent protocol peers for the device tests, started and stopped inside the tests:
// the libmodbus server (tests/tools/modbus_peer), socat pseudo-terminal pairs, and the
// MTConnect agent (tests/tools/mtconnect_agent.py, Python's http.server). None of them uses
// DriftLab's protocol code. Free ports are chosen by the peers (port 0) and read back.

#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QProcess>
#include <QStandardPaths>
#include <QString>
#include <QStringList>
#include <QThread>

#include <functional>
#include <memory>

namespace testpeers {

inline bool waitFor(const std::function<bool()> &condition, int timeout_ms)
{
    QElapsedTimer t;
    t.start();
    while (!condition()) {
        if (t.elapsed() > timeout_ms)
            return false;
        QThread::msleep(10);
    }
    return true;
}

// A child process that prints "ready ..." when it serves and acknowledges commands with "ok".
class Peer {
public:
    ~Peer() { kill(); }
    bool start(const QString &program, const QStringList &args, int timeout_ms = 10000)
    {
        kill();
        m_program = program;
        m_args = args;
        m_out.clear();
        m_all.clear();
        m_process = std::make_unique<QProcess>();
        m_process->setProcessChannelMode(QProcess::SeparateChannels);
        m_process->start(program, args);
        if (!m_process->waitForStarted(timeout_ms))
            return false;
        if (!readUntil("ready", timeout_ms) || !readUntil("\n", timeout_ms))
            return false;
        const int i = m_out.indexOf("ready ");
        m_ready = i < 0 ? QString() : QString::fromLatin1(m_out.mid(i + 6, m_out.indexOf('\n', i) - i - 6)).trimmed();
        return true;
    }
    bool restart(int timeout_ms = 10000) { return start(m_program, m_args, timeout_ms); }
    // The word after "ready" (the port).
    QString ready() const { return m_ready; }
    bool command(const QByteArray &line, int timeout_ms = 5000)
    {
        if (!m_process)
            return false;
        m_out.clear();
        m_process->write(line + '\n');
        m_process->waitForBytesWritten(timeout_ms);
        return readUntil("ok " + line, timeout_ms);
    }
    void kill()
    {
        if (m_process) {
            m_process->kill();
            m_process->waitForFinished(5000);
            m_process.reset();
        }
    }
    bool running() const { return m_process && m_process->state() == QProcess::Running; }
    // Everything the peer printed since start() (reads what is pending first).
    QByteArray output()
    {
        if (m_process) {
            m_process->waitForReadyRead(20); // the pipe is read only when asked to
            const QByteArray more = m_process->readAllStandardOutput();
            m_out += more;
            m_all += more;
        }
        return m_all;
    }
    QByteArray errors() const { return m_process ? m_process->readAllStandardError() : QByteArray(); }

private:
    bool readUntil(const QByteArray &marker, int timeout_ms)
    {
        QElapsedTimer t;
        t.start();
        while (!m_out.contains(marker)) {
            if (t.elapsed() > timeout_ms || m_process->state() != QProcess::Running)
                return false;
            m_process->waitForReadyRead(50);
            const QByteArray more = m_process->readAllStandardOutput();
            m_out += more;
            m_all += more;
        }
        return true;
    }
    std::unique_ptr<QProcess> m_process;
    QString m_program;
    QStringList m_args;
    QByteArray m_out;
    QByteArray m_all;
    QString m_ready;
};

// socat joining two pseudo-terminals, reachable as dir/a and dir/b.
class PtyPair {
public:
    ~PtyPair() { stop(); }
    static QString socat() { return QStandardPaths::findExecutable(QStringLiteral("socat")); }
    bool start(const QString &dir)
    {
        stop();
        m_a = QDir(dir).filePath(QStringLiteral("pty-a"));
        m_b = QDir(dir).filePath(QStringLiteral("pty-b"));
        m_process = std::make_unique<QProcess>();
        m_process->start(socat(), {QStringLiteral("pty,raw,echo=0,link=%1").arg(m_a), QStringLiteral("pty,raw,echo=0,link=%1").arg(m_b)});
        if (!m_process->waitForStarted(5000))
            return false;
        return waitFor([this] { return QFileInfo::exists(m_a) && QFileInfo::exists(m_b); }, 5000);
    }
    void stop()
    {
        if (m_process) {
            m_process->terminate();
            if (!m_process->waitForFinished(2000)) {
                m_process->kill();
                m_process->waitForFinished(2000);
            }
            m_process.reset();
        }
    }
    QString a() const { return m_a; }
    QString b() const { return m_b; }

private:
    std::unique_ptr<QProcess> m_process;
    QString m_a, m_b;
};

} // namespace testpeers

#pragma once
// A session writer on its own thread: it owns its own SessionStore connection, takes sample
// blocks, events and frames through a bounded queue (push blocks while the queue is full)
// and commits them in batched transactions at least every maxCommitInterval_s (default 0.5 s),
// so a crash loses at most the last second. Readers open their own SessionStore on the same
// file and read committed data while the writer runs (WAL).
//
// A write failure (disk full, ...) rolls the open batch back, stops the writer and is
// rethrown as StorageError by every later call; the database stays intact.

#include "StorageTypes.h"

#include <QString>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

namespace driftlab {

class SessionStore;

class SessionWriter {
public:
    struct Options {
        int queueCapacity = 256;          // queued items before push() blocks
        double maxCommitInterval_s = 0.5; // longest time a written item stays uncommitted (< 1 s)
        qint64 sizeLimit_bytes = 0;       // 0 = none; else PRAGMA max_page_count (quota, tests)
    };

    // Opens (creating/migrating) the database on the writer thread. Throws StorageError.
    explicit SessionWriter(const QString &path);
    SessionWriter(const QString &path, const Options &options);
    // Commits what is queued and stops (errors are swallowed here: call finish() to see them).
    ~SessionWriter();
    SessionWriter(const SessionWriter &) = delete;
    SessionWriter &operator=(const SessionWriter &) = delete;

    // Synchronous: run on the writer thread inside the current batch, result returned.
    qint64 createSession(const SessionInfo &info);
    qint64 addChannel(qint64 sessionId, const ChannelInfo &channel);
    void setComplete(qint64 sessionId, bool complete);

    // Asynchronous: queued, committed within maxCommitInterval_s.
    void appendSamples(qint64 channelId, const QVector<double> &t, const QVector<double> &v);
    void addEvent(qint64 sessionId, const EventRecord &event);
    void addIrFrame(qint64 sessionId, const IrFrame &frame);

    // Waits until everything queued so far is committed. Throws StorageError after a failure.
    void flush();
    // flush() and stop the thread; later calls throw.
    void finish();

    qint64 commits() const;

private:
    using Task = std::function<void(SessionStore &)>;
    void push(Task task);
    template <class R> R call(std::function<R(SessionStore &)> fn);
    void loop(const QString &path, std::promise<void> &opened);
    void throwIfFailed() const;

    Options m_options;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake;     // writer waits for work
    std::condition_variable m_progress; // producers wait for room / flushes
    std::deque<Task> m_queue;
    bool m_stop = false;
    bool m_flushRequested = false;
    quint64 m_pushed = 0;
    quint64 m_committed = 0;  // tasks committed (in push order)
    qint64 m_commits = 0;
    std::string m_error;
    std::thread m_thread;
};

} // namespace driftlab

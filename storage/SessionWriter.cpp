#include "SessionWriter.h"

#include "IrFrameCodec.h"
#include "SessionStore.h"
#include "StoreTransaction.h"
#include "StorageError.h"

#include <optional>

namespace driftlab {

SessionWriter::SessionWriter(const QString &path) : SessionWriter(path, Options{}) {}

SessionWriter::SessionWriter(const QString &path, const Options &options) : m_options(options)
{
    std::promise<void> opened;
    std::future<void> ready = opened.get_future();
    m_thread = std::thread([this, path, &opened] { loop(path, opened); });
    try {
        ready.get();
    } catch (...) {
        m_thread.join();
        throw;
    }
}

SessionWriter::~SessionWriter()
{
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    if (m_thread.joinable())
        m_thread.join();
}

void SessionWriter::loop(const QString &path, std::promise<void> &opened)
{
    std::unique_ptr<SessionStore> store;
    try {
        store = std::make_unique<SessionStore>(path);
        if (m_options.sizeLimit_bytes > 0)
            store->setSizeLimit(m_options.sizeLimit_bytes);
    } catch (...) {
        opened.set_exception(std::current_exception());
        return;
    }
    opened.set_value();
    const auto interval = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(m_options.maxCommitInterval_s));
    std::optional<StoreTransaction> tx; // open between commits (RAII: rolled back if left open)
    quint64 done = 0; // tasks run in this process, committed or not
    auto txStart = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        if (tx) {
            m_wake.wait_until(lock, txStart + interval,
                              [&] { return m_stop || m_flushRequested || !m_queue.empty(); });
        } else {
            m_wake.wait(lock, [&] { return m_stop || m_flushRequested || !m_queue.empty(); });
        }
        std::deque<Task> batch;
        batch.swap(m_queue);
        const bool stop = m_stop;
        const bool flush = m_flushRequested;
        lock.unlock();
        m_progress.notify_all(); // room in the queue
        std::string error;
        try {
            for (Task &task : batch) {
                if (!tx) {
                    tx.emplace(*store);
                    txStart = std::chrono::steady_clock::now();
                }
                task(*store);
                ++done;
            }
            if (tx && (stop || flush || std::chrono::steady_clock::now() - txStart >= interval)) {
                tx->commit(); // a failed commit is rolled back by SessionStore
                tx.reset();
                lock.lock();
                m_committed = done;
                ++m_commits;
                lock.unlock();
            }
        } catch (const std::exception &e) {
            error = e.what();
            tx.reset(); // rolls back an open transaction
        }
        lock.lock();
        if (flush)
            m_flushRequested = false;
        if (!error.empty()) {
            m_error = error;
            m_queue.clear();
        }
        m_progress.notify_all();
        if (stop || !m_error.empty()) {
            m_stop = true;
            break;
        }
    }
    lock.unlock();
    tx.reset();
    store.reset();
}

void SessionWriter::throwIfFailed() const
{
    if (!m_error.empty())
        throw StorageError("session writer stopped: " + m_error);
    if (m_stop)
        throw StorageError("session writer stopped");
}

void SessionWriter::push(Task task)
{
    std::unique_lock<std::mutex> lock(m_mutex);
    m_progress.wait(lock, [&] {
        return !m_error.empty() || m_stop || static_cast<int>(m_queue.size()) < m_options.queueCapacity;
    });
    throwIfFailed();
    m_queue.push_back(std::move(task));
    ++m_pushed;
    lock.unlock();
    m_wake.notify_one();
}

template <class R> R SessionWriter::call(std::function<R(SessionStore &)> fn)
{
    auto promise = std::make_shared<std::promise<R>>();
    std::future<R> result = promise->get_future();
    push([fn, promise](SessionStore &s) {
        try {
            promise->set_value(fn(s));
        } catch (...) {
            promise->set_exception(std::current_exception());
            throw;
        }
    });
    // Wait for the result, or for the writer to fail before running it.
    for (;;) {
        if (result.wait_for(std::chrono::milliseconds(20)) == std::future_status::ready)
            return result.get();
        std::lock_guard<std::mutex> lock(m_mutex);
        if (!m_error.empty() && result.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
            throwIfFailed();
    }
}

qint64 SessionWriter::createSession(const SessionInfo &info)
{
    return call<qint64>([info](SessionStore &s) { return s.createSession(info); });
}

qint64 SessionWriter::addChannel(qint64 sessionId, const ChannelInfo &channel)
{
    return call<qint64>([sessionId, channel](SessionStore &s) { return s.addChannel(sessionId, channel); });
}

void SessionWriter::setComplete(qint64 sessionId, bool complete)
{
    call<int>([sessionId, complete](SessionStore &s) {
        s.setComplete(sessionId, complete);
        return 0;
    });
    flush();
}

void SessionWriter::appendSamples(qint64 channelId, const QVector<double> &t, const QVector<double> &v)
{
    push([channelId, t, v](SessionStore &s) { s.appendSamples(channelId, t, v); });
}

void SessionWriter::addEvent(qint64 sessionId, const EventRecord &event)
{
    push([sessionId, event](SessionStore &s) { s.addEvent(sessionId, event); });
}

void SessionWriter::addIrFrame(qint64 sessionId, const IrFrame &frame)
{
    if (frame.width <= 0 || frame.height <= 0 || frame.pixels.size() != frame.width * frame.height)
        throw StorageError(QStringLiteral("infrared frame at %1 s: %2 pixels for %3 x %4")
                               .arg(frame.t).arg(frame.pixels.size()).arg(frame.width).arg(frame.height).toStdString());
    // Compressed here, in the producer's thread, in parallel with the writer.
    const QByteArray blob = IrFrameCodec::compress(frame.pixels, frame.width, frame.height);
    IrFrame meta = frame;
    meta.pixels.clear();
    push([sessionId, meta, blob](SessionStore &s) { s.addCompressedIrFrame(sessionId, meta, blob); });
}

void SessionWriter::flush()
{
    std::unique_lock<std::mutex> lock(m_mutex);
    throwIfFailed();
    const quint64 target = m_pushed;
    m_flushRequested = true;
    m_wake.notify_one();
    m_progress.wait(lock, [&] { return !m_error.empty() || m_stop || m_committed >= target; });
    if (m_committed < target)
        throwIfFailed();
}

void SessionWriter::finish()
{
    flush();
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    if (m_thread.joinable())
        m_thread.join();
}

qint64 SessionWriter::commits() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_commits;
}

} // namespace driftlab

#pragma once
// One cancellable background job of a panel (model fit, diagnosis, selection, ...): a
// thread, a cancel flag the work polls, and a join before the next start and on
// destruction. The work hands its result back to the GUI thread (QMetaObject::invokeMethod)
// and the panel calls finish() there, which joins the thread and ends running().

#include <atomic>
#include <functional>
#include <thread>

namespace driftlab {

class BackgroundJob {
public:
    BackgroundJob() = default;
    BackgroundJob(const BackgroundJob &) = delete;
    BackgroundJob &operator=(const BackgroundJob &) = delete;
    // Cancels a running job and waits for it: the work must poll cancelled().
    ~BackgroundJob();

    // Starts `work` on its own thread; false (nothing started) while a job is running.
    bool start(std::function<void()> work);
    // Asks the work to stop at its next poll; the job still ends through finish().
    void cancel() { m_cancel = true; }
    bool cancelled() const { return m_cancel.load(); }
    // Started and not yet finished.
    bool running() const { return m_thread.joinable() && !m_finished; }
    // On the GUI thread, once the work's result has arrived: joins the thread.
    void finish();

private:
    void join();

    std::thread m_thread;
    std::atomic<bool> m_cancel{false};
    bool m_finished = true;
};

} // namespace driftlab

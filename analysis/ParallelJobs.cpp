#include "ParallelJobs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace driftlab {

ParallelJobs::ParallelJobs(int threads) : m_threads(threads) {}

bool ParallelJobs::run(size_t n, const std::function<void(size_t)> &job, const std::function<std::string(size_t)> &label,
                       const std::function<bool(double, const std::string &)> &tick) const
{
    std::atomic<size_t> next{0};
    std::atomic<bool> stop{false};
    std::atomic<int> finished{0};
    int threads = m_threads > 0 ? m_threads : static_cast<int>(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, std::max(1, static_cast<int>(n)));
    if (threads == 1) {
        // Serial: progress between jobs from this thread.
        for (size_t k = 0; k < n; ++k) {
            if (!tick(static_cast<double>(k) / static_cast<double>(std::max<size_t>(1, n)), label(k)))
                return false;
            job(k);
        }
        return true;
    }
    std::mutex mutex;
    std::condition_variable changed; // a job finished
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (;;) {
                const size_t k = next++;
                if (k >= n || stop)
                    return;
                job(k);
                {
                    const std::lock_guard<std::mutex> lock(mutex);
                    ++finished;
                }
                changed.notify_one();
            }
        });
    // This thread reports progress and honours cancel.
    int reported = -1, polls = 0;
    while (finished < static_cast<int>(n) && !stop) {
        if (finished != reported || ++polls % 10 == 0) {
            reported = finished;
            const size_t running = std::min(next.load(), n - 1);
            if (!tick(static_cast<double>(reported) / static_cast<double>(n),
                      std::to_string(reported) + " of " + std::to_string(n) + " refitted, now " + label(running)))
                stop = true;
        }
        // Woken when a job finishes (the last one ends the wait at once, not up to 50 ms
        // later: several such waits per diagnosis), else every 50 ms to poll for cancel.
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished != reported; });
    }
    for (std::thread &t : pool)
        t.join();
    return !stop;
}

} // namespace driftlab

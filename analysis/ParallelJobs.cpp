#include "ParallelJobs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
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
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (;;) {
                const size_t k = next++;
                if (k >= n || stop)
                    return;
                job(k);
                ++finished;
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
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    for (std::thread &t : pool)
        t.join();
    return !stop;
}

} // namespace driftlab

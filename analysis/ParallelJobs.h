#pragma once
// Runs n independent jobs (the candidate refits of a diagnosis round) on a pool of threads,
// reporting progress and honouring cancel from the calling thread; serial with one thread.

#include <cstddef>
#include <functional>
#include <string>

namespace driftlab {

class ParallelJobs {
public:
    // threads <= 0: one per core.
    explicit ParallelJobs(int threads);

    // Runs job(0..n-1); label(k) names job k for progress (fraction in [0, 1]; false from
    // tick cancels: no further job starts). False when cancelled.
    bool run(size_t n, const std::function<void(size_t)> &job, const std::function<std::string(size_t)> &label,
             const std::function<bool(double, const std::string &)> &tick) const;

private:
    int m_threads;
};

} // namespace driftlab

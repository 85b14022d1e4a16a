// Acquisition benchmarks, each against a simple reference run in the same process:
//  1. BlockQueue with blocks of 500 samples vs a mutex/condvar queue of single samples
//     (why devices hand over blocks, never one item per sample);
//  2. the truth model's step (Thomas + 5-node Schur complement) vs a dense Gaussian
//     elimination of the same linear system (tridiagonal screw block embedded densely).
#include "BlockQueue.h"
#include "ScrewTruthModel.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

using namespace driftlab;
using Clock = std::chrono::steady_clock;

static double seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

int main()
{
    const long long total = 4000000;
    // 1a. Blocks.
    {
        BlockQueue q(64);
        auto t0 = Clock::now();
        std::thread producer([&] {
            for (long long i = 0; i < total; i += 500) {
                DeviceBlock b;
                b.channels.resize(1);
                b.channels[0].t.resize(500);
                b.channels[0].v.resize(500);
                for (int k = 0; k < 500; ++k) {
                    b.channels[0].t[k] = static_cast<double>(i + k);
                    b.channels[0].v[k] = 1.0;
                }
                q.push(std::move(b), 10.0);
            }
        });
        long long got = 0;
        QVector<DeviceBlock> out;
        while (got < total) {
            out.clear();
            q.drain(out);
            for (const DeviceBlock &b : out)
                got += b.channels[0].t.size();
            if (out.isEmpty())
                std::this_thread::yield();
        }
        producer.join();
        const double blocks = seconds(t0);
        // 1b. Reference: one queue item per sample.
        std::mutex m;
        std::condition_variable cv;
        std::deque<std::pair<double, double>> dq;
        t0 = Clock::now();
        std::thread p2([&] {
            for (long long i = 0; i < total; ++i) {
                std::unique_lock<std::mutex> l(m);
                cv.wait(l, [&] { return dq.size() < 64 * 500; });
                dq.emplace_back(static_cast<double>(i), 1.0);
            }
        });
        long long got2 = 0;
        while (got2 < total) {
            std::lock_guard<std::mutex> l(m);
            if (!dq.empty()) {
                dq.pop_front();
                ++got2;
                cv.notify_one();
            }
        }
        p2.join();
        const double single = seconds(t0);
        std::printf("queue: %lld samples, blocks of 500 %.3f s (%.1f M samples/s), per-sample queue %.3f s; ratio %.1fx\n",
                    total, blocks, total / blocks / 1e6, single, single / blocks);
    }
    // 2. Truth model step vs dense solve of the same system size.
    {
        RigScrew screw;
        ScrewTruthModel model(screw, RigThermal{}, RigEffects{});
        const int steps = 20000;
        auto t0 = Clock::now();
        for (int i = 0; i < steps; ++i)
            model.step(0.5, {0.2 + 0.4 * std::fabs(std::sin(i * 0.01))}, 6000.0, 20.0, 20.0);
        const double fast = seconds(t0) / steps;
        const int n = screw.cells + ScrewTruthModel::NodeCount;
        std::vector<double> a(static_cast<size_t>(n) * n), b(n);
        const int denseSteps = 200;
        t0 = Clock::now();
        double sink = 0;
        for (int s = 0; s < denseSteps; ++s) {
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j)
                    a[static_cast<size_t>(i) * n + j] = (i == j) ? 4.0 : (std::abs(i - j) == 1 || j >= n - 5 || i >= n - 5) ? -0.1 : 0.0;
                b[i] = 1.0 + s;
            }
            for (int c = 0; c < n; ++c)
                for (int r = c + 1; r < n; ++r) {
                    const double f = a[static_cast<size_t>(r) * n + c] / a[static_cast<size_t>(c) * n + c];
                    if (f == 0.0)
                        continue;
                    for (int k = c; k < n; ++k)
                        a[static_cast<size_t>(r) * n + k] -= f * a[static_cast<size_t>(c) * n + k];
                    b[r] -= f * b[c];
                }
            for (int c = n - 1; c >= 0; --c) {
                double v = b[c];
                for (int k = c + 1; k < n; ++k)
                    v -= a[static_cast<size_t>(c) * n + k] * b[k];
                b[c] = v / a[static_cast<size_t>(c) * n + c];
            }
            sink += b[0];
        }
        const double dense = seconds(t0) / denseSteps;
        std::printf("truth model: %d cells + %d nodes, step %.2f us (10 h at dt 0.5 s: %.2f s), dense solve %.1f us; ratio %.0fx (%g)\n",
                    screw.cells, static_cast<int>(ScrewTruthModel::NodeCount), fast * 1e6, fast * 72000, dense * 1e6,
                    dense / fast, sink > 0 ? 1.0 : 0.0);
    }
    return 0;
}

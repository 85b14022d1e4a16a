#pragma once
// Reads a device directly (no engine) for a while and collects its samples and events,
// for the device tests.

#include "Device.h"

#include <QElapsedTimer>

#include <functional>

namespace testpeers {

struct Recording {
    QVector<driftlab::SampleBlock> channels;
    QVector<driftlab::EventRecord> events;
};

// Reads for wall_s seconds (each read waits up to readTimeout_s); `each` runs before every
// read (a peer writing lines, ...). Device errors propagate.
inline void readFor(driftlab::Device &d, double wall_s, Recording &r, double readTimeout_s = 0.1, const std::function<void()> &each = {})
{
    QElapsedTimer t;
    t.start();
    while (t.elapsed() < wall_s * 1000.0) {
        if (each)
            each();
        const driftlab::DeviceBlock b = d.read(readTimeout_s);
        r.channels.resize(std::max(r.channels.size(), b.channels.size()));
        for (int i = 0; i < b.channels.size(); ++i) {
            r.channels[i].t += b.channels[i].t;
            r.channels[i].v += b.channels[i].v;
        }
        r.events += b.events;
    }
}

} // namespace testpeers

#pragma once
// Bounded single-producer / single-consumer queue of device blocks: one device worker
// pushes, the recorder drains. A full queue makes push() wait up to a timeout and then
// drop the block (counted): a stalled recorder never blocks a device forever and memory
// stays bounded.

#include "DeviceBlock.h"

#include <condition_variable>
#include <deque>
#include <mutex>

namespace driftlab {

class BlockQueue {
public:
    explicit BlockQueue(int capacity = 64) : m_capacity(capacity) {}

    // Returns false if the block was dropped because the queue stayed full.
    bool push(DeviceBlock &&block, double timeout_s);
    // Moves every queued block to out (appending); returns how many.
    int drain(QVector<DeviceBlock> &out);
    int size() const;
    int capacity() const { return m_capacity; }
    int highWater() const;
    long long dropped() const;

private:
    int m_capacity;
    mutable std::mutex m_mutex;
    std::condition_variable m_notFull;
    std::deque<DeviceBlock> m_blocks;
    int m_highWater = 0;
    long long m_dropped = 0;
};

} // namespace driftlab

#include "BlockQueue.h"

#include <chrono>

namespace driftlab {

bool BlockQueue::push(DeviceBlock &&block, double timeout_s)
{
    std::unique_lock<std::mutex> lock(m_mutex);
    const bool room = m_notFull.wait_for(lock, std::chrono::duration<double>(timeout_s),
                                         [this] { return static_cast<int>(m_blocks.size()) < m_capacity; });
    if (!room) {
        ++m_dropped;
        return false;
    }
    m_blocks.push_back(std::move(block));
    m_highWater = std::max(m_highWater, static_cast<int>(m_blocks.size()));
    return true;
}

int BlockQueue::drain(QVector<DeviceBlock> &out)
{
    std::deque<DeviceBlock> taken;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        taken.swap(m_blocks);
    }
    m_notFull.notify_all();
    for (DeviceBlock &b : taken)
        out.push_back(std::move(b));
    return static_cast<int>(taken.size());
}

int BlockQueue::size() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return static_cast<int>(m_blocks.size());
}

int BlockQueue::highWater() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_highWater;
}

long long BlockQueue::dropped() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_dropped;
}

} // namespace driftlab

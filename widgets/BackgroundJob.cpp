#include "BackgroundJob.h"

namespace driftlab {

BackgroundJob::~BackgroundJob()
{
    m_cancel = true;
    join();
}

bool BackgroundJob::start(std::function<void()> work)
{
    if (running())
        return false;
    join(); // a finished job's thread
    m_cancel = false;
    m_finished = false;
    m_thread = std::thread(std::move(work));
    return true;
}

void BackgroundJob::finish()
{
    join();
    m_finished = true;
}

void BackgroundJob::join()
{
    if (m_thread.joinable())
        m_thread.join();
}

} // namespace driftlab

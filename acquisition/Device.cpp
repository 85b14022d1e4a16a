#include "Device.h"

namespace driftlab {

QString DeviceHealth::stateName(State s)
{
    switch (s) {
    case State::Closed: return QStringLiteral("closed");
    case State::Running: return QStringLiteral("running");
    case State::Reconnecting: return QStringLiteral("reconnecting");
    case State::Stopped: return QStringLiteral("stopped");
    case State::Failed: return QStringLiteral("failed");
    }
    return QString();
}

} // namespace driftlab

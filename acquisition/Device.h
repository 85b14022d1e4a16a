#pragma once
// An acquisition device (PT100 module, eddy-current probe amplifier, CNC link, laser
// interferometer, infrared camera, or a simulated one). A DeviceWorker drives it on its
// own thread: open -> configure -> start -> read()... -> stop -> close. read() blocks
// until samples are available (or the timeout passes) and returns them as one block.
//
// Time stamps: a device either stamps its samples itself on the session clock
// (deviceStamped() == true, e.g. a simulation or an instrument with a synchronised
// clock), or leaves that to the worker, which stamps the newest sample of a block
// with (receipt time - declaredLatency_s()) and the earlier ones by their spacing.

#include "DeviceBlock.h"

#include <QJsonObject>
#include <QString>
#include <QVector>

#include <stdexcept>

namespace driftlab {

class SessionClock;

// A device that does not answer or answers garbage. The worker marks a gap and reconnects.
class DeviceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct DeviceHealth {
    enum class State { Closed, Running, Reconnecting, Stopped, Failed };
    State state = State::Closed;
    QString message;         // last error, if any
    long long samples = 0;   // scalar samples delivered
    long long blocks = 0;
    double lastSample_s = -1.0;
    double rate_Hz = 0.0;    // samples per session second over the last few seconds
    int gaps = 0;
    int reconnects = 0;
    long long droppedBlocks = 0; // queue overflow (recorder too slow)
    static QString stateName(State s);
};

class Device {
public:
    virtual ~Device() = default;
    virtual QString id() const = 0;   // unique within a recording, e.g. "pt100"
    virtual QString type() const = 0; // registry type name, e.g. "sim-pt100"

    virtual void open() = 0; // throws DeviceError if the device cannot be reached
    virtual void configure(const QJsonObject &settings) { Q_UNUSED(settings); }
    virtual void start(const SessionClock &clock) = 0;
    virtual void stop() = 0;
    virtual void close() = 0;

    virtual QVector<ChannelInfo> channels() const = 0;
    virtual double declaredLatency_s() const = 0;
    virtual bool deviceStamped() const { return false; }
    // Blocks up to timeout (wall seconds). Samples of each channel in channel order; with
    // deviceStamped() false their t are acquisition times on the device's own scale and
    // only their spacing is used. Throws DeviceError when the device stops answering.
    virtual DeviceBlock read(double timeoutWall_s) = 0;
};

} // namespace driftlab

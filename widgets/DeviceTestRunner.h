#pragma once
// Runs one configured device on a thread of its own for the rig setup dialog's "Test
// connection": open, start on a private session clock, read blocks until stopped, and
// report the latest value of each channel, the frames and the device's events back to the
// GUI thread (queued signals, at most ~10 per second). Nothing is stored.

#include "RigConfig.h"

#include <QObject>
#include <QStringList>

#include <atomic>
#include <thread>

namespace driftlab {

class DeviceTestRunner : public QObject {
    Q_OBJECT
public:
    explicit DeviceTestRunner(QObject *parent = nullptr);
    ~DeviceTestRunner() override;

    // Starts testing (stops a running test first). The base rig is used by simulated types.
    void start(const DeviceConfig &device, const RigConfig &baseRig);
    void stop();

signals:
    // channels: one "value unit" text per channel ("-" before the first value); state: the
    // device's state ("connecting", "running", "no answer: ...", "stopped").
    void update(const QStringList &channelIds, const QStringList &values, const QString &state);
    void message(const QString &text);

private:
    void run(DeviceConfig device, RigConfig baseRig);

    std::thread m_thread;
    std::atomic<bool> m_stop{false};
};

} // namespace driftlab

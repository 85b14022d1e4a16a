#pragma once
// A UVC thermal core (e.g. a radiometric module behind a USB UVC bridge) streaming 16-bit
// frames, read through OpenCV's V4L2 capture with RGB conversion off and the Y16 pixel
// format requested; one frame is kept every interval_s and converted with the camera's
// calibration (InfraredFrameConverter). A camera that cannot be opened or stops delivering
// frames throws DeviceError (gap, event, reopen with backoff). Frames are stamped when
// grabbed, minus the declared latency (the core's own pipeline delay).
// Settings: camera (index or /dev/videoN), width, height, fourcc (default "Y16 "), fps,
// interval_s, latency_s, calibration {...}.
// No camera is attached on the CI machine: the conversion path and the configuration are
// tested, and opening a missing camera is a DeviceError; streaming from a real core is not.

#include "Device.h"
#include "InfraredCalibration.h"

#include <memory>

namespace cv {
class VideoCapture;
}

namespace driftlab {

class UvcCameraDevice : public Device {
public:
    struct Config {
        QString camera = QStringLiteral("0"); // index or device path
        int width = 0, height = 0;            // 0: the camera's default
        QString fourcc = QStringLiteral("Y16 ");
        double fps = 0.0;
        double interval_s = 1.0;
        double latency_s = 0.0;
        InfraredCalibration calibration;
        static Config fromJson(const QJsonObject &settings, const QString &path);
    };

    UvcCameraDevice(const QString &id, const Config &config);
    ~UvcCameraDevice() override;

    QString id() const override { return m_id; }
    QString type() const override { return QStringLiteral("ir-uvc"); }
    void open() override;
    void start(const SessionClock &clock) override;
    void stop() override {}
    void close() override;
    QVector<ChannelInfo> channels() const override { return {}; }
    double declaredLatency_s() const override { return m_config.latency_s; }
    bool deviceStamped() const override { return true; }
    DeviceBlock read(double timeoutWall_s) override;

    const Config &config() const { return m_config; }

private:
    QString m_id;
    Config m_config;
    std::unique_ptr<cv::VideoCapture> m_capture;
    const SessionClock *m_clock = nullptr;
    double m_next_s = 0.0;
};

} // namespace driftlab

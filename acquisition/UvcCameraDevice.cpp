#include "UvcCameraDevice.h"

#include "InfraredFrameConverter.h"
#include "SessionClock.h"

#include <opencv2/videoio.hpp>

#include <cmath>

namespace driftlab {

UvcCameraDevice::Config UvcCameraDevice::Config::fromJson(const QJsonObject &settings, const QString &path)
{
    JsonFields f(settings, path);
    Config c;
    const QJsonValue cam = settings.value(QStringLiteral("camera"));
    f.markKnown(QStringLiteral("camera"));
    if (cam.isDouble() && cam.toDouble() >= 0 && cam.toDouble() == std::floor(cam.toDouble()) && cam.toDouble() < 64)
        c.camera = QString::number(cam.toInt());
    else if (cam.isString() && cam.toString().startsWith(QLatin1String("/dev/")))
        c.camera = cam.toString();
    else if (!cam.isUndefined())
        f.fail(QStringLiteral("camera"), QStringLiteral("expected a camera index (0, 1, ...) or a device path (/dev/video2), got %1").arg(JsonFields::shown(cam)));
    c.width = f.integer(QStringLiteral("width"), 0, 0, 8192);
    c.height = f.integer(QStringLiteral("height"), 0, 0, 8192);
    c.fourcc = f.string(QStringLiteral("fourcc"), c.fourcc);
    if (c.fourcc.size() != 4)
        f.fail(QStringLiteral("fourcc"), QStringLiteral("expected four characters, e.g. \"Y16 \", got \"%1\"").arg(c.fourcc));
    c.fps = f.number(QStringLiteral("fps"), 0.0, 0.0, 1000.0);
    c.interval_s = f.number(QStringLiteral("interval_s"), 1.0, 0.01, 86400.0);
    c.latency_s = f.number(QStringLiteral("latency_s"), 0.0, 0.0, 60.0);
    c.calibration = InfraredCalibration::fromDevice(f);
    f.finish();
    return c;
}

UvcCameraDevice::UvcCameraDevice(const QString &id, const Config &config) : m_id(id), m_config(config) {}

UvcCameraDevice::~UvcCameraDevice() = default;

void UvcCameraDevice::open()
{
    close();
    m_capture = std::make_unique<cv::VideoCapture>();
    bool isIndex = false;
    const int index = m_config.camera.toInt(&isIndex);
    const bool opened = isIndex ? m_capture->open(index, cv::CAP_V4L2) : m_capture->open(m_config.camera.toStdString(), cv::CAP_V4L2);
    if (!opened || !m_capture->isOpened()) {
        m_capture.reset();
        throw DeviceError(QStringLiteral("%1: cannot open camera %2 (V4L2)").arg(m_id, m_config.camera).toStdString());
    }
    const QByteArray cc = m_config.fourcc.toLatin1();
    m_capture->set(cv::CAP_PROP_FOURCC, cv::VideoWriter::fourcc(cc[0], cc[1], cc[2], cc[3]));
    if (m_config.width > 0)
        m_capture->set(cv::CAP_PROP_FRAME_WIDTH, m_config.width);
    if (m_config.height > 0)
        m_capture->set(cv::CAP_PROP_FRAME_HEIGHT, m_config.height);
    if (m_config.fps > 0.0)
        m_capture->set(cv::CAP_PROP_FPS, m_config.fps);
    m_capture->set(cv::CAP_PROP_CONVERT_RGB, 0); // keep the 16-bit counts
}

void UvcCameraDevice::start(const SessionClock &clock)
{
    m_clock = &clock;
    m_next_s = clock.now_s();
}

void UvcCameraDevice::close()
{
    if (m_capture) {
        m_capture->release();
        m_capture.reset();
    }
}

DeviceBlock UvcCameraDevice::read(double timeoutWall_s)
{
    if (!m_capture || !m_clock)
        throw DeviceError(QStringLiteral("%1: read on a closed camera").arg(m_id).toStdString());
    // Keep the stream flowing (a UVC camera queues frames), keep one per interval.
    if (!m_capture->grab())
        throw DeviceError(QStringLiteral("%1: camera %2 stopped delivering frames").arg(m_id, m_config.camera).toStdString());
    const double t = m_clock->now_s();
    DeviceBlock b;
    if (t < m_next_s) {
        Q_UNUSED(timeoutWall_s);
        return b;
    }
    m_next_s = std::max(m_next_s + m_config.interval_s, t);
    cv::Mat image;
    if (!m_capture->retrieve(image))
        throw DeviceError(QStringLiteral("%1: camera %2 delivered no frame").arg(m_id, m_config.camera).toStdString());
    const int w = static_cast<int>(m_capture->get(cv::CAP_PROP_FRAME_WIDTH));
    const int h = static_cast<int>(m_capture->get(cv::CAP_PROP_FRAME_HEIGHT));
    try {
        IrFrame f = InfraredFrameConverter::toFrame(image, m_config.calibration, QStringLiteral("camera %1").arg(m_config.camera), w, h);
        f.t = t - m_config.latency_s;
        b.frames.push_back(f);
    } catch (const std::invalid_argument &e) {
        // An 8-bit stream is a configuration error: stop instead of recording pictures.
        throw std::runtime_error(e.what());
    }
    return b;
}

} // namespace driftlab

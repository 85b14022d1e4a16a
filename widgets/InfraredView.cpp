#include "InfraredView.h"

#include <QLinearGradient>
#include <QMouseEvent>
#include <QPainter>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>

namespace driftlab {

namespace {
constexpr int kBarWidth = 18;
constexpr int kBarMargin = 70;

QColor mapColour(double f)
{
    // The same inferno-like map as the image (OpenCV's COLORMAP_INFERNO), sampled.
    cv::Mat one(1, 1, CV_8UC1, cv::Scalar(std::lround(255.0 * std::clamp(f, 0.0, 1.0))));
    cv::Mat bgr;
    cv::applyColorMap(one, bgr, cv::COLORMAP_INFERNO);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
    return QColor(c[2], c[1], c[0]);
}
} // namespace

InfraredView::InfraredView(QWidget *parent) : QWidget(parent)
{
    setMouseTracking(true);
    setMinimumSize(240, 140);
}

void InfraredView::setFrame(const cv::Mat &temperature, const InfraredCalibration &calibration)
{
    m_temperature = temperature.clone();
    m_calibration = calibration;
    if (!m_fixedRange && !m_temperature.empty()) {
        double lo = 0.0, hi = 0.0;
        cv::minMaxLoc(m_temperature, &lo, &hi);
        m_low = lo;
        m_high = hi > lo ? hi : lo + 1.0;
    }
    rebuildImage();
}

void InfraredView::setFixedRange(double low_C, double high_C)
{
    m_fixedRange = true;
    m_low = low_C;
    m_high = high_C > low_C ? high_C : low_C + 1.0;
    rebuildImage();
}

void InfraredView::rebuildImage()
{
    if (m_temperature.empty()) {
        m_image = QImage();
        update();
        return;
    }
    cv::Mat norm8, bgr, rgb;
    m_temperature.convertTo(norm8, CV_8U, 255.0 / (m_high - m_low), -255.0 * m_low / (m_high - m_low));
    cv::applyColorMap(norm8, bgr, cv::COLORMAP_INFERNO);
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    m_image = QImage(rgb.data, rgb.cols, rgb.rows, static_cast<int>(rgb.step), QImage::Format_RGB888).copy();
    update();
}

double InfraredView::temperatureAt(int x, int y) const
{
    if (m_temperature.empty() || x < 0 || y < 0 || x >= m_temperature.cols || y >= m_temperature.rows)
        return std::numeric_limits<double>::quiet_NaN();
    return m_temperature.at<float>(y, x);
}

QRectF InfraredView::imageRect() const
{
    if (m_image.isNull())
        return {};
    const QRectF area(0, 0, width() - kBarMargin, height());
    const double s = std::min(area.width() / m_image.width(), area.height() / m_image.height());
    const QSizeF size(m_image.width() * s, m_image.height() * s);
    return QRectF(QPointF((area.width() - size.width()) / 2, (area.height() - size.height()) / 2), size);
}

void InfraredView::paintEvent(QPaintEvent *)
{
    QPainter p(this);
    p.fillRect(rect(), palette().window());
    if (m_image.isNull()) {
        p.drawText(rect(), Qt::AlignCenter, tr("No infrared frame"));
        return;
    }
    const QRectF r = imageRect();
    p.drawImage(r, m_image);
    // Screw axis and band.
    const double s = r.width() / m_image.width();
    const QPointF a(r.left() + (m_calibration.lineX0_px + 0.5) * s, r.top() + (m_calibration.lineY0_px + 0.5) * s);
    const QPointF b(r.left() + (m_calibration.lineX1_px + 0.5) * s, r.top() + (m_calibration.lineY1_px + 0.5) * s);
    p.setRenderHint(QPainter::Antialiasing);
    p.setPen(QPen(QColor(0, 255, 255), 1.0, Qt::DashLine));
    p.drawLine(a, b);
    const QPointF d = b - a;
    const double len = std::hypot(d.x(), d.y());
    if (len > 0) {
        const QPointF n(-d.y() / len * m_calibration.screwWidth_px / 2 * s, d.x() / len * m_calibration.screwWidth_px / 2 * s);
        p.setPen(QPen(QColor(0, 255, 255, 160), 1.0));
        p.drawLine(a + n, b + n);
        p.drawLine(a - n, b - n);
    }
    // Scale bar.
    const QRectF bar(width() - kBarMargin + 8, 20, kBarWidth, height() - 40);
    QLinearGradient g(bar.bottomLeft(), bar.topLeft());
    for (int i = 0; i <= 10; ++i)
        g.setColorAt(i / 10.0, mapColour(i / 10.0));
    p.fillRect(bar, g);
    p.setPen(palette().text().color());
    p.drawRect(bar);
    p.drawText(QPointF(bar.right() + 3, bar.top() + 10), QString::number(m_high, 'f', 1));
    p.drawText(QPointF(bar.right() + 3, bar.bottom()), QString::number(m_low, 'f', 1));
    p.drawText(QPointF(bar.left(), bar.top() - 6), tr("°C"));
}

void InfraredView::mouseMoveEvent(QMouseEvent *event)
{
    const QRectF r = imageRect();
    if (r.isEmpty() || !r.contains(event->pos()))
        return;
    const double s = r.width() / m_image.width();
    const int x = static_cast<int>((event->pos().x() - r.left()) / s);
    const int y = static_cast<int>((event->pos().y() - r.top()) / s);
    const double t = temperatureAt(x, y);
    if (!std::isnan(t))
        emit readout(tr("pixel (%1, %2): %3 °C").arg(x).arg(y).arg(t, 0, 'f', 2));
}

} // namespace driftlab

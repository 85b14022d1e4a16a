#include "InfraredView.h"

#include "PlotExporter.h"
#include "PlotInteraction.h"

#include <QContextMenuEvent>
#include <QKeyEvent>
#include <QLinearGradient>
#include <QMenu>
#include <QMouseEvent>
#include <QPainter>
#include <QTextStream>

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
    setFocusPolicy(Qt::ClickFocus); // Shift+Esc clears the cursors
    setMinimumSize(240, 140);
}

void InfraredView::setFrame(const cv::Mat &temperature, const InfraredCalibration &calibration)
{
    if (temperature.size() != m_temperature.size())
        clearCursors(); // the same pixels on the next frame of a session, else none
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
    paintCursors(p);
}

std::optional<QPoint> InfraredView::pixelAt(QPoint widgetPos) const
{
    const QRectF r = imageRect();
    if (r.isEmpty() || !r.contains(widgetPos))
        return std::nullopt;
    const double s = r.width() / m_image.width();
    const QPoint pixel(static_cast<int>((widgetPos.x() - r.left()) / s), static_cast<int>((widgetPos.y() - r.top()) / s));
    if (pixel.x() < 0 || pixel.y() < 0 || pixel.x() >= m_image.width() || pixel.y() >= m_image.height())
        return std::nullopt;
    return pixel;
}

QPointF InfraredView::widgetPos(QPoint pixel) const
{
    const QRectF r = imageRect();
    const double s = m_image.isNull() ? 1.0 : r.width() / m_image.width();
    return {r.left() + (pixel.x() + 0.5) * s, r.top() + (pixel.y() + 0.5) * s};
}

std::optional<double> InfraredView::axialPosition_mm(QPoint pixel) const
{
    const InfraredCalibration &c = m_calibration;
    const double dx = c.lineX1_px - c.lineX0_px, dy = c.lineY1_px - c.lineY0_px;
    const double length2 = dx * dx + dy * dy;
    if (length2 < 4.0)
        return std::nullopt;
    const double f = ((pixel.x() - c.lineX0_px) * dx + (pixel.y() - c.lineY0_px) * dy) / length2;
    return 1000.0 * (c.line0_m + f * (c.line1_m - c.line0_m));
}

void InfraredView::setCursorPixel(Which which, QPoint pixel)
{
    m_cursor[which] = pixel;
    update();
}

void InfraredView::clearCursors()
{
    m_cursor[A].reset();
    m_cursor[B].reset();
    m_dragging = -1;
    update();
}

QString InfraredView::cursorText() const
{
    QStringList lines;
    double t[2] = {NAN, NAN};
    std::optional<double> x[2];
    for (int w : {A, B}) {
        if (!m_cursor[w])
            continue;
        const QPoint c = *m_cursor[w];
        t[w] = temperatureAt(c.x(), c.y());
        x[w] = axialPosition_mm(c);
        QString line = tr("%1 (%2, %3)  %4 °C").arg(w == A ? QStringLiteral("A") : QStringLiteral("B")).arg(c.x()).arg(c.y()).arg(t[w], 0, 'f', 2);
        if (x[w])
            line += tr("  at %1 mm").arg(*x[w], 0, 'f', 1);
        lines << line;
    }
    if (m_cursor[A] && m_cursor[B]) {
        const double dT = t[B] - t[A];
        QString line = tr("ΔT %1 °C").arg(dT, 0, 'f', 2);
        if (x[A] && x[B]) {
            const double dx = *x[B] - *x[A];
            line += tr("   Δx %1 mm along the screw").arg(dx, 0, 'f', 1);
            if (std::fabs(dx) > 1e-9) {
                const double g = dT / dx;
                // Four significant digits: 0.01910 °C/mm, 1.250 °C/mm.
                const int decimals = g == 0.0 ? 4 : std::clamp(3 - static_cast<int>(std::floor(std::log10(std::fabs(g)))), 0, 8);
                line += tr("   ΔT/Δx %1 °C/mm").arg(g, 0, 'f', decimals);
            }
        } else {
            line += tr("   (no screw axis calibrated: no distance)");
        }
        lines << line;
    }
    return lines.join(QLatin1Char('\n'));
}

void InfraredView::paintCursors(QPainter &p) const
{
    // Green and pink: apart from the colour map (black, purple, orange, pale yellow) and the
    // cyan screw axis.
    const QColor colours[2] = {QColor(80, 255, 80), QColor(255, 80, 220)};
    for (int w : {A, B}) {
        if (!m_cursor[w])
            continue;
        const QPointF c = widgetPos(*m_cursor[w]);
        for (const auto &pen : {QPen(QColor(0, 0, 0, 200), 3.5), QPen(colours[w], 1.5)}) {
            p.setPen(pen);
            p.drawEllipse(c, 6.0, 6.0);
            p.drawLine(c - QPointF(10, 0), c - QPointF(6, 0));
            p.drawLine(c + QPointF(6, 0), c + QPointF(10, 0));
        }
        const QString name = w == A ? QStringLiteral("A") : QStringLiteral("B");
        const QRectF label(c + QPointF(8, -8 - fontMetrics().ascent()), QSizeF(fontMetrics().horizontalAdvance(name) + 4, fontMetrics().height()));
        p.fillRect(label, QColor(0, 0, 0, 170));
        p.setPen(colours[w]);
        p.drawText(label, Qt::AlignCenter, name);
    }
    const QString text = cursorText();
    if (text.isEmpty())
        return;
    const QStringList lines = text.split(QLatin1Char('\n'));
    const QFontMetrics fm(font());
    int width = 0;
    for (const QString &line : lines)
        width = std::max(width, fm.horizontalAdvance(line));
    const QRectF box(imageRect().left() + 6, imageRect().top() + 6, width + 12, lines.size() * fm.lineSpacing() + 8);
    p.setPen(QColor(160, 160, 160));
    p.setBrush(QColor(255, 255, 255, 215));
    p.drawRect(box);
    p.setPen(Qt::black);
    p.drawText(box.adjusted(6, 4, -6, -4), Qt::AlignLeft | Qt::AlignTop, text);
}

void InfraredView::mouseMoveEvent(QMouseEvent *event)
{
    if (m_dragging >= 0 && (event->buttons() & Qt::LeftButton)) {
        if (const auto pixel = pixelAt(event->pos()))
            setCursorPixel(static_cast<Which>(m_dragging), *pixel);
        return;
    }
    const auto pixel = pixelAt(event->pos());
    if (!pixel)
        return;
    const double t = temperatureAt(pixel->x(), pixel->y());
    if (!std::isnan(t))
        emit readout(tr("pixel (%1, %2): %3 °C").arg(pixel->x()).arg(pixel->y()).arg(t, 0, 'f', 2));
}

void InfraredView::mousePressEvent(QMouseEvent *event)
{
    if (event->button() == Qt::LeftButton && event->modifiers() == Qt::NoModifier) {
        // A press within 4 px of a placed cursor grabs it.
        for (int w : {B, A}) {
            if (m_cursor[w] && QLineF(widgetPos(*m_cursor[w]), event->pos()).length() <= 4.0 + 0.5 * imageRect().width() / std::max(1, m_image.width())) {
                m_dragging = w;
                return;
            }
        }
    }
    if (event->modifiers() & Qt::ShiftModifier) {
        if (event->button() == Qt::RightButton) {
            clearCursors();
            return;
        }
        const auto pixel = pixelAt(event->pos());
        if (event->button() == Qt::LeftButton && pixel) {
            if (m_cursor[A] && !m_cursor[B]) {
                setCursorPixel(B, *pixel);
            } else {
                m_cursor[B].reset();
                setCursorPixel(A, *pixel);
            }
            return;
        }
    }
    QWidget::mousePressEvent(event);
}

void InfraredView::mouseReleaseEvent(QMouseEvent *event)
{
    if (m_dragging >= 0 && event->button() == Qt::LeftButton) {
        if (const auto pixel = pixelAt(event->pos()))
            setCursorPixel(static_cast<Which>(m_dragging), *pixel);
        m_dragging = -1;
        return;
    }
    QWidget::mouseReleaseEvent(event);
}

void InfraredView::keyPressEvent(QKeyEvent *event)
{
    if (event->key() == Qt::Key_Escape && (event->modifiers() & Qt::ShiftModifier)) {
        clearCursors();
        return;
    }
    QWidget::keyPressEvent(event);
}

void InfraredView::contextMenuEvent(QContextMenuEvent *event)
{
    if (event->modifiers() & Qt::ShiftModifier)
        return; // Shift+right click cleared the cursors
    QMenu *menu = createMenu(this);
    menu->setAttribute(Qt::WA_DeleteOnClose);
    menu->popup(event->globalPos());
}

QMenu *InfraredView::createMenu(QWidget *parent)
{
    auto *menu = new QMenu(parent);
    PlotInteraction::ExportActions actions;
    actions.image = [this] { return grab(); };
    actions.save = [this](const QString &path) { PlotExporter::exportWidget(*this, path); };
    actions.csvTitle = tr("Export frame temperatures as CSV...");
    if (!m_temperature.empty())
        actions.csv = [this](QTextStream &out) { return writeCsv(out); };
    PlotInteraction::addExportActions(menu, this, actions);
    return menu;
}

int InfraredView::writeCsv(QTextStream &out) const
{
    out << "x_px,y_px,axial_position_mm,temperature_C\n";
    int n = 0;
    for (int y = 0; y < m_temperature.rows; ++y) {
        for (int x = 0; x < m_temperature.cols; ++x) {
            const auto along = axialPosition_mm(QPoint(x, y));
            out << x << ',' << y << ',' << (along ? QString::number(*along, 'f', 3) : QString()) << ','
                << QString::number(m_temperature.at<float>(y, x), 'f', 3) << '\n';
            ++n;
        }
    }
    return n;
}

bool InfraredView::exportCsv(const QString &path, QString *error, int *rows) const
{
    return PlotInteraction::writeCsv(path, [this](QTextStream &out) { return writeCsv(out); }, error, rows);
}

} // namespace driftlab

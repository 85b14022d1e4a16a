#include "PlotCursors.h"

#include "ElapsedTimeAxis.h"
#include "PlotReadout.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPen>

#include <qwt_plot.h>
#include <qwt_plot_canvas.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_textlabel.h>
#include <qwt_scale_map.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <cmath>

namespace driftlab {

PlotCursors *PlotCursors::install(QwtPlot *plot)
{
    return new PlotCursors(plot, FieldValue(), QwtPlot::yLeft);
}

PlotCursors *PlotCursors::installPoints(QwtPlot *plot, FieldValue value, int valueAxis)
{
    return new PlotCursors(plot, std::move(value), valueAxis);
}

PlotCursors *PlotCursors::of(const QwtPlot *plot)
{
    return plot->findChild<PlotCursors *>(QString(), Qt::FindDirectChildrenOnly);
}

PlotCursors::PlotCursors(QwtPlot *plot, FieldValue field, int valueAxis)
    : QObject(plot), m_plot(plot), m_canvas(plot->canvas()), m_label(new QwtPlotTextLabel()), m_field(std::move(field)),
      m_valueAxis(valueAxis)
{
    const QColor colours[2] = {QColor(200, 0, 120), QColor(0, 120, 200)};
    for (int i = 0; i < 2; ++i) {
        m_marker[i] = new QwtPlotMarker(i == A ? QStringLiteral("cursor A") : QStringLiteral("cursor B"));
        m_marker[i]->setLineStyle(m_field ? QwtPlotMarker::NoLine : QwtPlotMarker::VLine);
        m_marker[i]->setLinePen(colours[i], 1.0, Qt::SolidLine);
        if (m_field) // a ring: the field under it stays visible
            m_marker[i]->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, Qt::NoBrush, QPen(colours[i], 2.0), QSize(11, 11)));
        QwtText label(i == A ? QStringLiteral("A") : QStringLiteral("B"));
        label.setColor(colours[i]);
        m_marker[i]->setLabel(label);
        m_marker[i]->setLabelAlignment(Qt::AlignRight | Qt::AlignBottom);
        m_marker[i]->setItemAttribute(QwtPlotItem::Legend, false);
        m_marker[i]->setItemAttribute(QwtPlotItem::AutoScale, false);
    }
    m_label->setZ(100);
    // The plot owns the markers and the label from here on (it deletes its attached items):
    // they stay attached and are shown or hidden, so none is left without an owner.
    for (QwtPlotMarker *marker : m_marker) {
        marker->setVisible(false);
        marker->attach(m_plot);
    }
    m_label->setVisible(false);
    m_label->attach(m_plot);

    m_canvas->installEventFilter(this);
}

void PlotCursors::setCursor(Which which, double x)
{
    setPoint(which, x, m_y[which]);
}

void PlotCursors::setPoint(Which which, double x, double y)
{
    m_x[which] = x;
    m_y[which] = y;
    m_marker[which]->setValue(x, y);
    m_marker[which]->setVisible(true);
    update();
}

void PlotCursors::clear()
{
    for (int i = 0; i < 2; ++i) {
        m_x[i].reset();
        m_marker[i]->setVisible(false);
    }
    update();
}

std::optional<double> PlotCursors::position(Which which) const
{
    return m_x[which];
}

std::optional<QPointF> PlotCursors::point(Which which) const
{
    if (!m_x[which])
        return std::nullopt;
    return QPointF(*m_x[which], m_y[which]);
}

double PlotCursors::valueAt(const QwtPlotCurve &curve, double x)
{
    const size_t n = curve.dataSize();
    for (size_t i = 1; i < n; ++i) {
        const QPointF a = curve.sample(i - 1), b = curve.sample(i);
        if ((a.x() <= x && x <= b.x()) || (b.x() <= x && x <= a.x()))
            return a.x() == b.x() ? a.y() : a.y() + (b.y() - a.y()) * (x - a.x()) / (b.x() - a.x());
    }
    return n == 1 && curve.sample(0).x() == x ? curve.sample(0).y() : NAN;
}

QString PlotCursors::deltaText(int axis, double d) const
{
    if (ElapsedTimeAxis::installed(m_plot, axis))
        return ElapsedTimeAxis::format(d); // signed: "-0:30:00"
    return PlotReadout::valueText(m_plot, axis, d);
}

QString PlotCursors::fieldText() const
{
    const int axes[3] = {QwtPlot::xBottom, QwtPlot::yLeft, m_valueAxis};
    double v[2][3] = {};
    QStringList lines;
    for (int w : {A, B}) {
        if (!m_x[w])
            continue;
        v[w][0] = *m_x[w];
        v[w][1] = m_y[w];
        v[w][2] = m_field(*m_x[w], m_y[w]);
        QStringList parts;
        for (int k = 0; k < 3; ++k)
            parts << (std::isfinite(v[w][k]) ? PlotReadout::valueText(m_plot, axes[k], v[w][k]) : QStringLiteral("-"));
        lines << (w == A ? QStringLiteral("A  ") : QStringLiteral("B  ")) + parts.join(QStringLiteral("   "));
    }
    if (m_x[A] && m_x[B]) {
        QStringList parts;
        for (int k = 0; k < 3; ++k) {
            // The quantity's name: the axis title without its unit ("thermal error (µm)").
            QString name = m_plot->axisTitle(axes[k]).text();
            name = name.left(name.lastIndexOf(QLatin1Char('('))).trimmed();
            const double d = v[B][k] - v[A][k];
            parts << QStringLiteral("Δ %1 %2").arg(name, std::isfinite(d) ? deltaText(axes[k], d) : QStringLiteral("-"));
        }
        lines << parts.join(QStringLiteral("   "));
    }
    return lines.join(QLatin1Char('\n'));
}

QString PlotCursors::text() const
{
    if (!m_x[A] && !m_x[B])
        return QString();
    if (m_field)
        return fieldText();
    const int xAxis = QwtPlot::xBottom;
    const bool time = ElapsedTimeAxis::installed(m_plot, xAxis);
    QStringList lines;
    QString head;
    if (m_x[A])
        head += QStringLiteral("A %1").arg(PlotReadout::valueText(m_plot, xAxis, *m_x[A]));
    if (m_x[B])
        head += QStringLiteral("%1B %2").arg(head.isEmpty() ? QString() : QStringLiteral("   "),
                                             PlotReadout::valueText(m_plot, xAxis, *m_x[B]));
    if (m_x[A] && m_x[B]) {
        const double dx = *m_x[B] - *m_x[A];
        head += QStringLiteral("   Δ%1 %2").arg(time ? QStringLiteral("t") : QStringLiteral("x"), deltaText(xAxis, dx));
    }
    lines << head;
    for (const QwtPlotItem *item : m_plot->itemList(QwtPlotItem::Rtti_PlotCurve)) {
        const auto *curve = static_cast<const QwtPlotCurve *>(item);
        if (!curve->isVisible())
            continue;
        const int axis = curve->yAxis();
        QString line = curve->title().text() + QStringLiteral("  ");
        const double va = m_x[A] ? valueAt(*curve, *m_x[A]) : NAN;
        const double vb = m_x[B] ? valueAt(*curve, *m_x[B]) : NAN;
        const auto show = [this, axis](double v) { return std::isfinite(v) ? PlotReadout::valueText(m_plot, axis, v) : QStringLiteral("-"); };
        if (m_x[A] && m_x[B]) {
            line += QStringLiteral("%1 → %2").arg(show(va), show(vb));
            if (std::isfinite(va) && std::isfinite(vb))
                line += QStringLiteral("  Δ %1").arg(show(vb - va));
        } else {
            line += show(m_x[A] ? va : vb);
        }
        lines << line;
    }
    return lines.join(QLatin1Char('\n'));
}

void PlotCursors::update()
{
    const QString t = text();
    if (t.isEmpty()) {
        m_label->setVisible(false);
    } else {
        QwtText label(t);
        label.setRenderFlags(Qt::AlignLeft | Qt::AlignTop);
        label.setBackgroundBrush(QColor(255, 255, 255, 215));
        label.setBorderPen(QPen(QColor(160, 160, 160)));
        m_label->setText(label);
        m_label->setVisible(true);
    }
    m_plot->replot();
}

void PlotCursors::place(Which which, const QPoint &pixel)
{
    const double x = m_plot->canvasMap(QwtPlot::xBottom).invTransform(pixel.x());
    setPoint(which, x, m_field ? m_plot->canvasMap(QwtPlot::yLeft).invTransform(pixel.y()) : m_y[which]);
}

bool PlotCursors::eventFilter(QObject *watched, QEvent *event)
{
    if (watched == m_canvas && m_dragging >= 0 &&
        (event->type() == QEvent::MouseMove || event->type() == QEvent::MouseButtonRelease)) {
        // Dragging a placed cursor: it follows the pointer (not a zoom rectangle).
        const auto *mouse = static_cast<QMouseEvent *>(event);
        place(static_cast<Which>(m_dragging), mouse->pos());
        if (event->type() == QEvent::MouseButtonRelease)
            m_dragging = -1;
        return true;
    }
    if (watched == m_canvas && event->type() == QEvent::MouseButtonPress) {
        const auto *mouse = static_cast<QMouseEvent *>(event);
        if (mouse->button() == Qt::LeftButton && mouse->modifiers() == Qt::NoModifier) {
            // A press within 4 px of a placed cursor grabs it.
            for (int w : {B, A}) {
                const double dy = m_field ? m_plot->canvasMap(QwtPlot::yLeft).transform(m_y[w]) - mouse->pos().y() : 0.0;
                if (m_x[w] && std::abs(m_plot->canvasMap(QwtPlot::xBottom).transform(*m_x[w]) - mouse->pos().x()) <= 4.0 &&
                    std::abs(dy) <= 4.0) {
                    m_dragging = w;
                    return true;
                }
            }
        }
        if (mouse->modifiers() & Qt::ShiftModifier) {
            if (mouse->button() == Qt::RightButton) {
                clear();
                return true;
            }
            if (mouse->button() == Qt::LeftButton) {
                if (m_x[A] && !m_x[B]) {
                    place(B, mouse->pos());
                } else {
                    m_x[B].reset();
                    m_marker[B]->setVisible(false);
                    place(A, mouse->pos());
                }
                return true; // not a zoom rectangle
            }
        }
    } else if (watched == m_canvas && event->type() == QEvent::KeyPress) {
        const auto *key = static_cast<QKeyEvent *>(event);
        if (key->key() == Qt::Key_Escape && (key->modifiers() & Qt::ShiftModifier)) {
            clear();
            return true;
        }
    }
    return QObject::eventFilter(watched, event);
}

} // namespace driftlab

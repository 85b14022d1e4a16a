#include "PlotInteraction.h"

#include "PlotExporter.h"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_zoomer.h>
#include <qwt_scale_div.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>

#include <QApplication>
#include <QClipboard>
#include <QContextMenuEvent>
#include <QFileDialog>
#include <QMenu>
#include <QMessageBox>
#include <QSaveFile>
#include <QTextStream>
#include <QWheelEvent>

#include <cmath>

namespace driftlab {

namespace {
QString csvField(QString text)
{
    if (text.contains(QLatin1Char(',')) || text.contains(QLatin1Char('"')))
        text = QLatin1Char('"') + text.replace(QLatin1Char('"'), QStringLiteral("\"\"")) + QLatin1Char('"');
    return text;
}
} // namespace

PlotInteraction::PlotInteraction(QwtPlot *plot, QwtPlotZoomer *zoomer) : QObject(plot), m_plot(plot), m_zoomer(zoomer)
{
    setObjectName(QStringLiteral("PlotInteraction"));
}

PlotInteraction *PlotInteraction::install(QwtPlot *plot, QwtPlotZoomer *zoomer)
{
    auto *p = new PlotInteraction(plot, zoomer);
    if (zoomer) {
        // Right button: the menu. Zoom out one step: Ctrl+right button (or the menu).
        zoomer->setMousePattern(QwtEventPattern::MouseSelect2, Qt::RightButton, Qt::ControlModifier | Qt::ShiftModifier);
        zoomer->setMousePattern(QwtEventPattern::MouseSelect3, Qt::RightButton, Qt::ControlModifier);
    }
    plot->canvas()->installEventFilter(p);
    for (int axis = 0; axis < QwtPlot::axisCnt; ++axis)
        if (QwtScaleWidget *w = plot->axisWidget(axis))
            w->installEventFilter(p);
    return p;
}

bool PlotInteraction::eventFilter(QObject *watched, QEvent *event)
{
    if (event->type() == QEvent::ContextMenu && watched == m_plot->canvas()) {
        auto *e = static_cast<QContextMenuEvent *>(event);
        QMenu *menu = createMenu(m_plot);
        menu->setAttribute(Qt::WA_DeleteOnClose);
        menu->popup(e->globalPos());
        return true;
    }
    if (event->type() == QEvent::Wheel) {
        for (int axis = 0; axis < QwtPlot::axisCnt; ++axis) {
            if (watched != m_plot->axisWidget(axis) || !m_plot->axisEnabled(axis))
                continue;
            auto *e = static_cast<QWheelEvent *>(event);
            const int delta = e->angleDelta().y() != 0 ? e->angleDelta().y() : e->angleDelta().x();
            if (delta == 0)
                return false;
            const QPoint at = m_plot->canvas()->mapFrom(m_plot->axisWidget(axis), e->position().toPoint());
            const bool horizontal = axis == QwtPlot::xBottom || axis == QwtPlot::xTop;
            const double centre = m_plot->canvasMap(axis).invTransform(horizontal ? at.x() : at.y());
            zoomAxis(*m_plot, axis, std::pow(0.9, delta / 120.0), centre);
            return true;
        }
    }
    return QObject::eventFilter(watched, event);
}

void PlotInteraction::zoomAxis(QwtPlot &plot, int axis, double factor, double centre)
{
    const QwtScaleDiv &div = plot.axisScaleDiv(axis);
    const double lo = centre + (div.lowerBound() - centre) * factor;
    const double hi = centre + (div.upperBound() - centre) * factor;
    plot.setAxisScale(axis, lo, hi);
    plot.replot();
}

QMenu *PlotInteraction::createMenu(QWidget *parent)
{
    auto *menu = new QMenu(parent);
    if (m_zoomer) {
        QAction *undo = menu->addAction(tr("Undo zoom"), this, [this] { m_zoomer->zoom(-1); });
        undo->setEnabled(m_zoomer->zoomRectIndex() > 0);
        menu->addAction(tr("Reset zoom"), this, [this] { m_zoomer->zoom(0); });
        menu->addSeparator();
    }
    menu->addAction(tr("Copy image"), this, [this] { QApplication::clipboard()->setPixmap(m_plot->grab()); });
    menu->addAction(tr("Save image (PNG, SVG, PDF)..."), this, [this] {
        const QString out = QFileDialog::getSaveFileName(m_plot, tr("Save image"), QStringLiteral("plot.png"),
                                                         tr("PNG (*.png);;SVG (*.svg);;PDF (*.pdf)"));
        if (out.isEmpty())
            return;
        try {
            PlotExporter::exportPlot(*m_plot, out);
        } catch (const std::exception &e) {
            QMessageBox::warning(m_plot, tr("Save image"), QString::fromUtf8(e.what()));
        }
    });
    QAction *csv = menu->addAction(tr("Export visible data as CSV..."), this, [this] {
        const QString out = QFileDialog::getSaveFileName(m_plot, tr("Export visible data"), QStringLiteral("plot.csv"),
                                                         tr("CSV (*.csv)"));
        QString error;
        if (!out.isEmpty() && !exportVisibleData(*m_plot, out, &error))
            QMessageBox::warning(m_plot, tr("Export visible data"), error);
    });
    csv->setEnabled(!m_plot->itemList(QwtPlotItem::Rtti_PlotCurve).isEmpty());
    return menu;
}

bool PlotInteraction::exportVisibleData(const QwtPlot &plot, const QString &path, QString *error, int *rows)
{
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) {
        if (error)
            *error = tr("%1: cannot write: %2").arg(path, file.errorString());
        return false;
    }
    QTextStream out(&file);
    out.setCodec("UTF-8");
    auto title = [&plot](int axis) {
        const QString t = plot.axisTitle(axis).text();
        return t.isEmpty() ? (axis == QwtPlot::xBottom ? QStringLiteral("x") : QStringLiteral("y")) : t;
    };
    out << "curve," << csvField(title(QwtPlot::xBottom)) << ",value,axis\n";
    const QwtScaleDiv &x = plot.axisScaleDiv(QwtPlot::xBottom);
    const double x0 = std::min(x.lowerBound(), x.upperBound()), x1 = std::max(x.lowerBound(), x.upperBound());
    int n = 0;
    for (const QwtPlotItem *item : plot.itemList(QwtPlotItem::Rtti_PlotCurve)) {
        const auto *curve = static_cast<const QwtPlotCurve *>(item);
        if (!curve->isVisible())
            continue;
        const QString name = csvField(curve->title().text());
        const QString axis = csvField(title(curve->yAxis()));
        for (size_t i = 0; i < curve->dataSize(); ++i) {
            const QPointF p = curve->sample(i);
            if (p.x() < x0 || p.x() > x1)
                continue;
            out << name << ',' << QString::number(p.x(), 'g', 12) << ',' << QString::number(p.y(), 'g', 10) << ',' << axis << '\n';
            ++n;
        }
    }
    out.flush();
    if (!file.commit()) {
        if (error)
            *error = tr("%1: cannot write: %2").arg(path, file.errorString());
        return false;
    }
    if (rows)
        *rows = n;
    return true;
}

} // namespace driftlab

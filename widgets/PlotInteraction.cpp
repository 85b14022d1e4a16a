#include "PlotInteraction.h"

#include "ElapsedTimeAxis.h"
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
#include <QMouseEvent>
#include <QSaveFile>
#include <QShortcut>
#include <QTextStream>
#include <QWheelEvent>

#include <cmath>

namespace driftlab {

QString PlotInteraction::csvField(QString text)
{
    if (text.contains(QLatin1Char(',')) || text.contains(QLatin1Char('"')))
        text = QLatin1Char('"') + text.replace(QLatin1Char('"'), QStringLiteral("\"\"")) + QLatin1Char('"');
    return text;
}

namespace {
// The curves' points inside the visible x range: curve, x, value, and the value's axis title.
int curveRows(const QwtPlot &plot, QTextStream &out)
{
    auto title = [&plot](int axis) {
        const QString t = plot.axisTitle(axis).text();
        return t.isEmpty() ? (axis == QwtPlot::xBottom ? QStringLiteral("x") : QStringLiteral("y")) : t;
    };
    // A time axis shows h:mm:ss but the rows hold seconds: the column says so (time_s, as the
    // CLI's CSVs and the surface exports name it), not the axis's "(h:mm:ss)".
    const QString xName = ElapsedTimeAxis::installed(&plot, QwtPlot::xBottom) ? QStringLiteral("time_s") : title(QwtPlot::xBottom);
    out << "curve," << PlotInteraction::csvField(xName) << ",value,axis\n";
    const QwtScaleDiv &x = plot.axisScaleDiv(QwtPlot::xBottom);
    const double x0 = std::min(x.lowerBound(), x.upperBound()), x1 = std::max(x.lowerBound(), x.upperBound());
    int n = 0;
    for (const QwtPlotItem *item : plot.itemList(QwtPlotItem::Rtti_PlotCurve)) {
        const auto *curve = static_cast<const QwtPlotCurve *>(item);
        if (!curve->isVisible())
            continue;
        const QString name = PlotInteraction::csvField(curve->title().text());
        const QString axis = PlotInteraction::csvField(title(curve->yAxis()));
        for (size_t i = 0; i < curve->dataSize(); ++i) {
            const QPointF p = curve->sample(i);
            if (p.x() < x0 || p.x() > x1)
                continue;
            out << name << ',' << QString::number(p.x(), 'g', 12) << ',' << QString::number(p.y(), 'g', 10) << ',' << axis << '\n';
            ++n;
        }
    }
    return n;
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
        // Right button: the menu. Zoom out one step: Backspace, Ctrl+right button or the menu.
        zoomer->setMousePattern(QwtEventPattern::MouseSelect2, Qt::RightButton, Qt::ControlModifier | Qt::ShiftModifier);
        zoomer->setMousePattern(QwtEventPattern::MouseSelect3, Qt::RightButton, Qt::ControlModifier);
        // The zoomer's own stack would not know the other ways of zooming: one history here.
        zoomer->setKeyPattern(QwtEventPattern::KeyUndo, Qt::Key_unknown);
        zoomer->setKeyPattern(QwtEventPattern::KeyRedo, Qt::Key_unknown);
        zoomer->setKeyPattern(QwtEventPattern::KeyHome, Qt::Key_unknown);
        connect(zoomer, &QwtPlotZoomer::zoomed, p, [p] {
            if (p->m_hasPressed)
                p->m_history.push_back(p->m_pressed);
            p->m_hasPressed = false;
        });
    }
    auto *undo = new QShortcut(QKeySequence(Qt::Key_Backspace), plot);
    undo->setContext(Qt::WidgetWithChildrenShortcut);
    connect(undo, &QShortcut::activated, p, &PlotInteraction::undoZoom);
    plot->canvas()->installEventFilter(p);
    for (int axis = 0; axis < QwtPlot::axisCnt; ++axis)
        if (QwtScaleWidget *w = plot->axisWidget(axis))
            w->installEventFilter(p);
    return p;
}

PlotInteraction *PlotInteraction::of(const QwtPlot *plot)
{
    return plot ? plot->findChild<PlotInteraction *>(QStringLiteral("PlotInteraction"), Qt::FindDirectChildrenOnly) : nullptr;
}

PlotInteraction::Snapshot PlotInteraction::snapshot() const
{
    Snapshot s(QwtPlot::axisCnt);
    for (int axis = 0; axis < QwtPlot::axisCnt; ++axis) {
        const QwtScaleDiv &div = m_plot->axisScaleDiv(axis);
        s[axis] = {div.lowerBound(), div.upperBound(), m_plot->axisAutoScale(axis)};
    }
    return s;
}

void PlotInteraction::restore(const Snapshot &s)
{
    for (int axis = 0; axis < QwtPlot::axisCnt && axis < s.size(); ++axis) {
        if (s[axis].autoScale)
            m_plot->setAxisAutoScale(axis, true);
        else
            m_plot->setAxisScale(axis, s[axis].lo, s[axis].hi);
    }
    m_plot->replot();
}

void PlotInteraction::pushZoom()
{
    m_history.push_back(snapshot());
    m_wheelWidget = nullptr;
}

void PlotInteraction::pushWheelStep(const QObject *widget)
{
    if (widget == m_wheelWidget && m_wheelTime.isValid() && m_wheelTime.elapsed() < 600 && !m_history.isEmpty()) {
        m_wheelTime.restart();
        return;
    }
    pushZoom();
    m_wheelWidget = widget;
    m_wheelTime.restart();
}

bool PlotInteraction::undoZoom()
{
    if (m_history.isEmpty())
        return false;
    restore(m_history.takeLast());
    m_wheelWidget = nullptr;
    return true;
}

void PlotInteraction::resetZoom()
{
    if (!m_history.isEmpty()) {
        restore(m_history.first());
        m_history.clear();
    } else if (m_zoomer) {
        m_zoomer->zoom(0);
    }
    m_wheelWidget = nullptr;
}

bool PlotInteraction::eventFilter(QObject *watched, QEvent *event)
{
    // Only input events reach the code below. A plot being destroyed sends others (hide, child
    // removed) through this filter while its QwtPlot part is already gone, so m_plot must not be
    // called for them (UBSan: member call on a QWidget).
    switch (event->type()) {
    case QEvent::MouseButtonPress:
    case QEvent::MouseMove:
    case QEvent::MouseButtonRelease:
    case QEvent::Wheel:
    case QEvent::ContextMenu:
        break;
    default:
        return QObject::eventFilter(watched, event);
    }
    if (watched == m_plot->canvas()) {
        // Before the zoomer, the panner and the magnifier see it (filters run newest first).
        if (event->type() == QEvent::MouseButtonPress) {
            auto *e = static_cast<QMouseEvent *>(event);
            if (e->button() == Qt::LeftButton && e->modifiers() == Qt::NoModifier) {
                m_pressed = snapshot(); // pushed if the rubber band zooms
                m_hasPressed = true;
            } else if (e->button() == Qt::MiddleButton) {
                pushZoom(); // the panner moves the view
            }
        } else if (event->type() == QEvent::Wheel) {
            pushWheelStep(watched); // the magnifier zooms both axes
        }
    }
    if (event->type() == QEvent::MouseButtonPress || event->type() == QEvent::MouseMove ||
        event->type() == QEvent::MouseButtonRelease) {
        for (int axis = 0; axis < QwtPlot::axisCnt; ++axis) {
            // A colour bar's scale is the colour map's: zooming it alone would relabel the colours.
            if (watched != m_plot->axisWidget(axis) || !m_plot->axisEnabled(axis) || m_plot->axisWidget(axis)->isColorBarEnabled())
                continue;
            auto *e = static_cast<QMouseEvent *>(event);
            const bool horizontal = axis == QwtPlot::xBottom || axis == QwtPlot::xTop;
            if (event->type() == QEvent::MouseButtonPress && e->button() == Qt::LeftButton) {
                pushZoom();
                m_dragAxis = axis;
                m_dragLast = e->pos();
                return true;
            }
            if (event->type() == QEvent::MouseMove && m_dragAxis == axis && (e->buttons() & Qt::LeftButton)) {
                // Pan: the scale value under the pointer stays under it.
                const QwtScaleMap map = m_plot->canvasMap(axis);
                const double from = map.invTransform(horizontal ? m_dragLast.x() : m_dragLast.y());
                const double to = map.invTransform(horizontal ? e->pos().x() : e->pos().y());
                const QwtScaleDiv &div = m_plot->axisScaleDiv(axis);
                m_plot->setAxisScale(axis, div.lowerBound() - (to - from), div.upperBound() - (to - from));
                m_plot->replot();
                m_dragLast = e->pos();
                return true;
            }
            if (event->type() == QEvent::MouseButtonRelease && m_dragAxis == axis) {
                m_dragAxis = -1;
                return true;
            }
        }
    }
    if (event->type() == QEvent::ContextMenu && watched == m_plot->canvas()) {
        auto *e = static_cast<QContextMenuEvent *>(event);
        QMenu *menu = createMenu(m_plot);
        menu->setAttribute(Qt::WA_DeleteOnClose);
        menu->popup(e->globalPos());
        return true;
    }
    if (event->type() == QEvent::Wheel) {
        for (int axis = 0; axis < QwtPlot::axisCnt; ++axis) {
            // A colour bar's scale is the colour map's: zooming it alone would relabel the colours.
            if (watched != m_plot->axisWidget(axis) || !m_plot->axisEnabled(axis) || m_plot->axisWidget(axis)->isColorBarEnabled())
                continue;
            auto *e = static_cast<QWheelEvent *>(event);
            const int delta = e->angleDelta().y() != 0 ? e->angleDelta().y() : e->angleDelta().x();
            if (delta == 0)
                return false;
            // (The axis widget is no ancestor of the canvas: QWidget::mapFrom would walk off the tree.)
            const QPoint at = m_plot->canvas()->mapFromGlobal(m_plot->axisWidget(axis)->mapToGlobal(e->position().toPoint()));
            const bool horizontal = axis == QwtPlot::xBottom || axis == QwtPlot::xTop;
            const double centre = m_plot->canvasMap(axis).invTransform(horizontal ? at.x() : at.y());
            pushWheelStep(watched);
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
    QAction *undo = menu->addAction(tr("Undo zoom"), this, &PlotInteraction::undoZoom);
    undo->setShortcut(QKeySequence(Qt::Key_Backspace));
    undo->setEnabled(canUndoZoom());
    QAction *reset = menu->addAction(tr("Reset zoom"), this, &PlotInteraction::resetZoom);
    reset->setEnabled(canUndoZoom() || (m_zoomer && m_zoomer->zoomRectIndex() > 0));
    menu->addSeparator();
    ExportActions actions;
    actions.image = [this] { return m_plot->grab(); };
    actions.save = [this](const QString &path) { PlotExporter::exportPlot(*m_plot, path); };
    actions.csvTitle = tr("Export visible data as CSV...");
    if (m_writer)
        actions.csv = m_writer;
    else if (!m_plot->itemList(QwtPlotItem::Rtti_PlotCurve).isEmpty())
        actions.csv = [this](QTextStream &out) { return curveRows(*m_plot, out); };
    addExportActions(menu, m_plot, actions);
    return menu;
}

void PlotInteraction::addExportActions(QMenu *menu, QWidget *owner, const ExportActions &actions)
{
    menu->addAction(tr("Copy image"), owner, [actions] { QApplication::clipboard()->setPixmap(actions.image()); });
    menu->addAction(tr("Save image (PNG, SVG, PDF)..."), owner, [owner, actions] {
        const QString out = QFileDialog::getSaveFileName(owner, tr("Save image"), QStringLiteral("plot.png"),
                                                         tr("PNG (*.png);;SVG (*.svg);;PDF (*.pdf)"));
        if (out.isEmpty())
            return;
        try {
            actions.save(out);
        } catch (const std::exception &e) {
            QMessageBox::warning(owner, tr("Save image"), QString::fromUtf8(e.what()));
        }
    });
    QAction *csv = menu->addAction(actions.csvTitle, owner, [owner, actions] {
        const QString out = QFileDialog::getSaveFileName(owner, tr("Export CSV"), QStringLiteral("plot.csv"), tr("CSV (*.csv)"));
        QString error;
        if (!out.isEmpty() && !writeCsv(out, actions.csv, &error))
            QMessageBox::warning(owner, tr("Export CSV"), error);
    });
    csv->setEnabled(bool(actions.csv));
}

bool PlotInteraction::exportVisible(const QString &path, QString *error, int *rows) const
{
    return m_writer ? writeCsv(path, m_writer, error, rows) : exportVisibleData(*m_plot, path, error, rows);
}

bool PlotInteraction::writeCsv(const QString &path, const CsvWriter &write, QString *error, int *rows)
{
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) {
        if (error)
            *error = tr("%1: cannot write: %2").arg(path, file.errorString());
        return false;
    }
    QTextStream out(&file);
    out.setCodec("UTF-8");
    const int n = write(out);
    out.flush();
    if (out.status() != QTextStream::Ok || !file.flush() || !file.commit()) {
        if (error)
            *error = tr("%1: cannot write: %2").arg(path, file.errorString());
        return false;
    }
    if (rows)
        *rows = n;
    return true;
}

bool PlotInteraction::exportVisibleData(const QwtPlot &plot, const QString &path, QString *error, int *rows)
{
    return writeCsv(path, [&plot](QTextStream &out) { return curveRows(plot, out); }, error, rows);
}

} // namespace driftlab

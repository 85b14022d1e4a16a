#include "ErrorSurface3D.h"

#include "ElapsedTimeAxis.h"
#include "PlotExporter.h"
#include "PlotInteraction.h"

#include <QLabel>
#include <QMenu>
#include <QMouseEvent>
#include <QTextStream>
#include <QVBoxLayout>
#include <QtDataVisualization/Q3DCamera>
#include <QtDataVisualization/Q3DScene>
#include <QtDataVisualization/Q3DSurface>
#include <QtDataVisualization/Q3DTheme>
#include <QtDataVisualization/QSurface3DSeries>
#include <QtDataVisualization/QSurfaceDataProxy>
#include <QtDataVisualization/QValue3DAxis>
#include <QtDataVisualization/QValue3DAxisFormatter>

#include <algorithm>
#include <cmath>

using namespace QtDataVisualization;

namespace driftlab {

namespace {
// The time axis of the 3-D view in h:mm:ss, like every other time axis (ElapsedTimeAxis).
class ElapsedAxisFormatter : public QValue3DAxisFormatter {
public:
    QValue3DAxisFormatter *createNewInstance() const override { return new ElapsedAxisFormatter; }

protected:
    QString stringForValue(qreal value, const QString &) const override { return ElapsedTimeAxis::format(value); }
};
} // namespace

ErrorSurface3D::ErrorSurface3D(QWidget *parent) : QWidget(parent)
{
    m_graph = new Q3DSurface();
    m_proxy = new QSurfaceDataProxy();
    auto *series = m_series = new QSurface3DSeries(m_proxy);
    series->setDrawMode(QSurface3DSeries::DrawSurfaceAndWireframe);
    series->setFlatShadingEnabled(false);
    QLinearGradient gradient;
    gradient.setColorAt(0.0, QColor(49, 54, 149));
    gradient.setColorAt(0.5, QColor(255, 255, 191));
    gradient.setColorAt(1.0, QColor(165, 0, 38));
    series->setBaseGradient(gradient);
    series->setColorStyle(Q3DTheme::ColorStyleRangeGradient);
    m_graph->addSeries(series);
    m_graph->axisX()->setTitle(tr("axis position (mm)"));
    m_graph->axisZ()->setTitle(tr("elapsed time (h:mm:ss)"));
    m_graph->axisZ()->setFormatter(new ElapsedAxisFormatter);
    m_graph->axisY()->setTitle(tr("thermal error (µm)"));
    for (QValue3DAxis *axis : {m_graph->axisX(), m_graph->axisY(), m_graph->axisZ()})
        axis->setTitleVisible(true);
    m_graph->axisX()->setLabelFormat(QStringLiteral("%.0f"));
    m_graph->axisY()->setLabelFormat(QStringLiteral("%.1f"));
    m_graph->axisZ()->setSegmentCount(4);
    // Position and time as long as each other: by default the box takes the data's own ratio,
    // and 520 mm against 14,400 s squeezed the position axis to one label ("520") at 1366 x 768.
    m_graph->setHorizontalAspectRatio(1.0);
    resetView();
    m_graph->activeTheme()->setFont(QFont(QStringLiteral("DejaVu Sans"), 44)); // larger than the default: the camera is zoomed out
    m_readout = new QLabel(this);
    m_readout->setTextInteractionFlags(Qt::TextSelectableByMouse);
    clearCursors(); // the readout's first text says what a click does
    connect(series, &QSurface3DSeries::selectedPointChanged, this, [this](const QPoint &p) {
        if (p == QSurface3DSeries::invalidSelectionPosition())
            return;
        if (m_shiftPress)
            setCursor(!m_cursor[0] || m_cursor[1] ? 0 : 1, p);
        else if (!m_cursor[0])
            m_readout->setText(selectionText(m_table, p));
    });
    m_graph->installEventFilter(this); // the right click's menu (the graph is a window of its own)
    auto *layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    m_container = QWidget::createWindowContainer(m_graph, this);
    layout->addWidget(m_container, 1);
    layout->addWidget(m_readout);
}

ErrorSurface3D::~ErrorSurface3D() = default;

void ErrorSurface3D::fillProxy(QSurfaceDataProxy &proxy, const ThermalErrorTable &table)
{
    auto *rows = new QSurfaceDataArray();
    rows->reserve(static_cast<int>(table.runCount()));
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        auto *row = new QSurfaceDataRow(static_cast<int>(table.targetCount()));
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            double e = table.error(r, k);
            for (std::size_t d = 1; std::isnan(e) && d < table.targetCount(); ++d) {
                if (k >= d)
                    e = table.error(r, k - d);
                if (std::isnan(e) && k + d < table.targetCount())
                    e = table.error(r, k + d);
            }
            (*row)[static_cast<int>(k)].setPosition(QVector3D(static_cast<float>(table.targets_mm()[k]),
                                                              static_cast<float>(std::isnan(e) ? 0.0 : e),
                                                              static_cast<float>(table.runTimes_s()[r])));
        }
        rows->append(row);
    }
    proxy.resetArray(rows);
}

QImage ErrorSurface3D::renderImage() const
{
    if (!m_graph->isExposed() && !m_graph->isVisible())
        return {};
    return m_graph->renderToImage(0, m_container->size() * devicePixelRatioF());
}

QRect ErrorSurface3D::graphRect() const
{
    return m_container->geometry();
}

QString ErrorSurface3D::selectionText(const ThermalErrorTable &table, QPoint rowColumn)
{
    const int r = rowColumn.x(), k = rowColumn.y();
    if (r < 0 || k < 0 || r >= static_cast<int>(table.runCount()) || k >= static_cast<int>(table.targetCount()))
        return QString();
    const double e = table.error(static_cast<std::size_t>(r), static_cast<std::size_t>(k));
    return tr("axis position %1 mm   elapsed time %2   thermal error %3")
        .arg(table.targets_mm()[static_cast<std::size_t>(k)], 0, 'f', 1)
        .arg(ElapsedTimeAxis::format(table.runTimes_s()[static_cast<std::size_t>(r)]))
        .arg(std::isnan(e) ? tr("not measured (drawn from the nearest target)") : QStringLiteral("%1 µm").arg(e, 0, 'f', 2));
}

void ErrorSurface3D::select(QPoint rowColumn)
{
    m_series->setSelectedPoint(rowColumn);
}

void ErrorSurface3D::setCursor(int which, QPoint rowColumn)
{
    if (which == 0)
        m_cursor[1].reset(); // A again: B starts afresh, as on the 2-D plots
    m_cursor[which != 0] = rowColumn;
    m_readout->setText(cursorsText(m_table, m_cursor[0], m_cursor[1]));
}

void ErrorSurface3D::clearCursors()
{
    m_cursor[0].reset();
    m_cursor[1].reset();
    m_readout->setText(tr("Click the surface to read a point, Shift+click for cursors A and B; right click (without dragging) for the menu."));
}

void ErrorSurface3D::resetView()
{
    m_graph->scene()->activeCamera()->setCameraPreset(Q3DCamera::CameraPresetIsometricRightHigh);
    // Zoomed out: the axis titles and the front corner's labels inside the view at 1366 x 768.
    m_graph->scene()->activeCamera()->setZoomLevel(62.0f);
}

QString ErrorSurface3D::cursorsText(const ThermalErrorTable &table, const std::optional<QPoint> &a, const std::optional<QPoint> &b)
{
    const auto valid = [&table](const std::optional<QPoint> &p) {
        return p && p->x() >= 0 && p->y() >= 0 && p->x() < static_cast<int>(table.runCount()) && p->y() < static_cast<int>(table.targetCount());
    };
    QStringList parts;
    if (valid(a))
        parts << QStringLiteral("A  ") + selectionText(table, *a);
    if (valid(b))
        parts << QStringLiteral("B  ") + selectionText(table, *b);
    if (valid(a) && valid(b)) {
        const auto at = [&table](QPoint p) {
            return std::make_tuple(table.targets_mm()[static_cast<std::size_t>(p.y())], table.runTimes_s()[static_cast<std::size_t>(p.x())],
                                   table.error(static_cast<std::size_t>(p.x()), static_cast<std::size_t>(p.y())));
        };
        const auto [xa, ta, ea] = at(*a);
        const auto [xb, tb, eb] = at(*b);
        const double dt = tb - ta;
        const double de = eb - ea;
        parts << tr("Δ axis position %1 mm   Δ elapsed time %2   Δ thermal error %3")
                     .arg(xb - xa, 0, 'f', 1)
                     .arg(ElapsedTimeAxis::format(dt)) // signed: B before A reads "-2:30:00"
                     .arg(std::isnan(de) ? QStringLiteral("-") : QStringLiteral("%1 µm").arg(de, 0, 'f', 2));
    }
    return parts.join(QLatin1Char('\n'));
}

QString ErrorSurface3D::readout() const
{
    return m_readout->text();
}

int ErrorSurface3D::writeCsv(const ThermalErrorTable &table, QTextStream &out)
{
    out << "position_mm,time_s,thermal_error_um\n";
    int n = 0;
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            const double e = table.error(r, k);
            out << QString::number(table.targets_mm()[k], 'g', 12) << ',' << QString::number(table.runTimes_s()[r], 'g', 12) << ','
                << (std::isnan(e) ? QString() : QString::number(e, 'g', 10)) << '\n';
            ++n;
        }
    }
    return n;
}

QMenu *ErrorSurface3D::createMenu(QWidget *parent)
{
    auto *menu = new QMenu(parent);
    PlotInteraction::ExportActions actions;
    actions.image = [this] { return QPixmap::fromImage(renderImage()); };
    actions.save = [this](const QString &path) { PlotExporter::exportImage(renderImage(), path); };
    actions.csvTitle = tr("Export the table as CSV...");
    if (m_table.runCount() > 0)
        actions.csv = [this](QTextStream &out) { return writeCsv(m_table, out); };
    menu->addAction(tr("Reset view"), this, [this] { resetView(); });
    if (m_cursor[0])
        menu->addAction(tr("Clear cursors"), this, [this] { clearCursors(); });
    menu->addSeparator();
    PlotInteraction::addExportActions(menu, this, actions);
    return menu;
}

bool ErrorSurface3D::eventFilter(QObject *watched, QEvent *event)
{
    if (watched == m_graph && (event->type() == QEvent::MouseButtonPress || event->type() == QEvent::MouseButtonRelease)) {
        const auto *mouse = static_cast<QMouseEvent *>(event);
        if (mouse->button() == Qt::LeftButton && event->type() == QEvent::MouseButtonPress)
            m_shiftPress = mouse->modifiers() & Qt::ShiftModifier; // the selection comes with the next frame
        if (mouse->button() == Qt::RightButton) {
            if (event->type() == QEvent::MouseButtonPress) {
                m_rightPress = mouse->globalPos();
            } else if ((mouse->globalPos() - m_rightPress).manhattanLength() <= 3) {
                QMenu *menu = createMenu(this); // a click, not a rotation
                menu->setAttribute(Qt::WA_DeleteOnClose);
                menu->popup(mouse->globalPos());
            }
        }
    }
    return QWidget::eventFilter(watched, event);
}

void ErrorSurface3D::setTable(const ThermalErrorTable &table)
{
    m_table = table;
    fillProxy(*m_proxy, table);
    // Ticks on round clock steps over the runs' time span.
    if (table.runCount() > 0) {
        const double t1 = *std::max_element(table.runTimes_s().begin(), table.runTimes_s().end());
        const double step = ElapsedTimeAxis::roundStep(std::max(1.0, t1) / 4.0);
        const int segments = std::max(1, static_cast<int>(std::ceil(t1 / step - 1e-9)));
        m_graph->axisZ()->setRange(0.0f, static_cast<float>(segments * step));
        m_graph->axisZ()->setSegmentCount(segments);
    }
}

} // namespace driftlab

#include "ErrorSurface3D.h"

#include "ElapsedTimeAxis.h"
#include "ThermalErrorTable.h"

#include <QHBoxLayout>
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
    auto *series = new QSurface3DSeries(m_proxy);
    series->setDrawMode(QSurface3DSeries::DrawSurfaceAndWireframe);
    series->setFlatShadingEnabled(false);
    QLinearGradient gradient;
    gradient.setColorAt(0.0, QColor(49, 54, 149));
    gradient.setColorAt(0.5, QColor(255, 255, 191));
    gradient.setColorAt(1.0, QColor(165, 0, 38));
    series->setBaseGradient(gradient);
    series->setColorStyle(Q3DTheme::ColorStyleRangeGradient);
    m_graph->addSeries(series);
    m_graph->axisX()->setTitle(tr("position (mm)"));
    m_graph->axisZ()->setTitle(tr("elapsed time (h:mm:ss)"));
    m_graph->axisZ()->setFormatter(new ElapsedAxisFormatter);
    m_graph->axisY()->setTitle(tr("thermal error (µm)"));
    for (QValue3DAxis *axis : {m_graph->axisX(), m_graph->axisY(), m_graph->axisZ()})
        axis->setTitleVisible(true);
    m_graph->axisX()->setLabelFormat(QStringLiteral("%.0f"));
    m_graph->axisY()->setLabelFormat(QStringLiteral("%.1f"));
    m_graph->axisZ()->setSegmentCount(4);
    m_graph->scene()->activeCamera()->setCameraPreset(Q3DCamera::CameraPresetIsometricRightHigh);
    m_graph->activeTheme()->setFont(QFont(QStringLiteral("DejaVu Sans"), 32));
    auto *layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(QWidget::createWindowContainer(m_graph, this));
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
    return m_graph->renderToImage(0, size() * devicePixelRatioF());
}

void ErrorSurface3D::setTable(const ThermalErrorTable &table)
{
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

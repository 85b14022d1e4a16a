#include "InfraredPanel.h"

#include "ErrorSurfacePlot.h"
#include "InfraredProfileExtractor.h"
#include "InfraredView.h"
#include "SessionReviewData.h"
#include "TimeSeriesPlot.h"

#include <QLabel>
#include <QSlider>
#include <QSplitter>
#include <QVBoxLayout>

#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace driftlab {

namespace {
constexpr int kProfilePoints = 81;
}

InfraredPanel::InfraredPanel(QWidget *parent)
    : QWidget(parent),
      m_view(new InfraredView(this)),
      m_slider(new QSlider(Qt::Horizontal, this)),
      m_label(new QLabel(this)),
      m_profile(new TimeSeriesPlot(this)),
      m_surface(new ErrorSurfacePlot(this))
{
    auto *layout = new QVBoxLayout(this);
    auto *split = new QSplitter(Qt::Vertical, this);
    auto *top = new QWidget(split);
    auto *topLayout = new QVBoxLayout(top);
    topLayout->setContentsMargins(0, 0, 0, 0);
    topLayout->addWidget(m_view, 1);
    topLayout->addWidget(m_slider);
    topLayout->addWidget(m_label);
    m_label->setWordWrap(true);
    auto *bottom = new QSplitter(Qt::Horizontal, split);
    bottom->addWidget(m_profile);
    bottom->addWidget(m_surface);
    split->addWidget(top);
    split->addWidget(bottom);
    layout->addWidget(split);
    m_profile->setTimeAxis(false); // x is the position along the screw
    m_profile->setAxisTitle(QwtPlot::xBottom, tr("axial position from the fixed end (m)"));
    m_profile->setAxisTitles(tr("screw temperature (°C)"), QString());
    m_profile->enableAxis(QwtPlot::yRight, false);
    m_surface->setTitle(tr("Axial screw temperature over time"));
    m_surface->setAxisTitle(QwtPlot::xBottom, tr("axial position (m)"));
    m_surface->setAxisTitle(QwtPlot::yRight, tr("temperature (°C)"));
    m_surface->setCsvColumns({QStringLiteral("axial_position_m"), QStringLiteral("time_s"), QStringLiteral("temperature_C")});
    connect(m_slider, &QSlider::valueChanged, this, &InfraredPanel::showFrame);
    connect(m_view, &InfraredView::readout, m_label, &QLabel::setText);
}

InfraredPanel::~InfraredPanel() = default;

int InfraredPanel::frameCount() const
{
    return m_data ? m_data->infraredFrames().size() : 0;
}

void InfraredPanel::profileGrid(const SessionReviewData &data, int points, std::vector<double> &x_m,
                                std::vector<double> &t_s, std::vector<double> &temperature_C)
{
    const InfraredProfileExtractor extractor(data.infraredCalibration());
    x_m.clear();
    t_s.clear();
    temperature_C.clear();
    for (const IrFrame &f : data.infraredFrames()) {
        const auto nut = data.nutCentreAt(f.t);
        const auto profile = extractor.extract(data.frameTemperature(f.id), points, nut.value_or(0.0),
                                               nut ? data.nutLength_m() : -1.0);
        if (x_m.empty()) {
            for (const ProfilePoint &p : profile)
                x_m.push_back(p.x_m);
        }
        t_s.push_back(f.t);
        for (const ProfilePoint &p : profile)
            temperature_C.push_back(p.valid ? p.temperature_C : std::numeric_limits<double>::quiet_NaN());
    }
}

void InfraredPanel::setSession(std::shared_ptr<const SessionReviewData> data)
{
    m_data = std::move(data);
    const int n = frameCount();
    m_slider->setRange(0, std::max(0, n - 1));
    m_slider->setEnabled(n > 1);
    if (n == 0) {
        m_label->setText(tr("This session has no infrared frames."));
        m_surface->showEmpty(tr("This session has no infrared frames."));
        m_view->setFrame(cv::Mat(), {});
        m_profile->clearCurves();
        return;
    }
    std::vector<double> x, t, z;
    profileGrid(*m_data, kProfilePoints, x, t, z);
    if (t.size() >= 2)
        m_surface->setGrid(x, t, z);
    else
        m_surface->showEmpty(tr("One infrared frame: a temperature map over time needs two or more."));
    // Open on the most informative frame: the largest axial temperature spread.
    int best = 0;
    double bestSpread = -1.0;
    for (std::size_t f = 0; f < t.size(); ++f) {
        double lo = 1e300, hi = -1e300;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double v = z[f * x.size() + i];
            if (!std::isnan(v)) {
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        }
        if (hi - lo > bestSpread) {
            bestSpread = hi - lo;
            best = static_cast<int>(f);
        }
    }
    m_slider->setValue(best);
    showFrame(best);
}

void InfraredPanel::showFrame(int index)
{
    if (!m_data || index < 0 || index >= frameCount())
        return;
    const IrFrame f = m_data->infraredFrames().at(index);
    const InfraredCalibration cal = m_data->infraredCalibration();
    const cv::Mat t = m_data->frameTemperature(f.id);
    m_view->setFrame(t, cal);
    const auto nut = m_data->nutCentreAt(f.t);
    const auto profile = InfraredProfileExtractor(cal).extract(t, kProfilePoints, nut.value_or(0.0),
                                                               nut ? m_data->nutLength_m() : -1.0);
    QVector<double> x, y;
    for (const ProfilePoint &p : profile) {
        if (p.valid) {
            x.push_back(p.x_m);
            y.push_back(p.temperature_C);
        }
    }
    m_profile->clearCurves();
    QwtPlotCurve *c = m_profile->addCurve(tr("t = %1 s").arg(f.t), x, y, false);
    c->setStyle(QwtPlotCurve::NoCurve);
    c->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(c->pen().color()), QPen(Qt::NoPen), QSize(5, 5)));
    m_profile->setTitle(tr("Axial profile, frame %1 of %2").arg(index + 1).arg(frameCount()));
    m_profile->zoomToData();
    m_label->setText(tr("frame %1 of %2 at t = %3 s%4")
                         .arg(index + 1)
                         .arg(frameCount())
                         .arg(f.t)
                         .arg(nut ? tr(", nut at %1 m from the fixed end (masked)").arg(*nut, 0, 'f', 3) : QString()));
}

} // namespace driftlab

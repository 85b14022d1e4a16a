#include "AnalysisPlots.h"

#include "AnalysisResultKind.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"

#include <qwt_color_map.h>
#include <qwt_column_symbol.h>
#include <qwt_legend.h>
#include <qwt_matrix_raster_data.h>
#include <qwt_plot.h>
#include <qwt_plot_barchart.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_widget.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <QJsonArray>
#include <QPen>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace driftlab {

namespace {

const QVector<QColor> &clusterColours()
{
    static const QVector<QColor> c = {QColor(31, 119, 180), QColor(214, 39, 40), QColor(44, 160, 44), QColor(255, 127, 14),
                                      QColor(148, 103, 189), QColor(140, 86, 75), QColor(227, 119, 194), QColor(127, 127, 127),
                                      QColor(188, 189, 34), QColor(23, 190, 207)};
    return c;
}

// Integer ticks labelled with channel ids.
class ChannelScaleDraw : public QwtScaleDraw {
public:
    explicit ChannelScaleDraw(QStringList names) : m_names(std::move(names)) {}
    QwtText label(double v) const override
    {
        const int i = static_cast<int>(std::lround(v));
        if (std::fabs(v - i) > 1e-6 || i < 0 || i >= m_names.size())
            return QwtText();
        return QwtText(m_names.at(i));
    }

private:
    QStringList m_names;
};

QwtScaleDiv channelDiv(int n, double offset)
{
    QList<double> ticks;
    for (int i = 0; i < n; ++i)
        ticks << i + offset;
    QwtScaleDiv div(-0.5 + offset, n - 0.5 + offset);
    div.setTicks(QwtScaleDiv::MajorTick, ticks);
    return div;
}

struct ChannelRow {
    QString id;
    int cluster = 0;
    double grade = 0, gradeAll = 0;
    bool chosen = false;
};

// Channels ordered by cluster (then by their order in the session).
QVector<ChannelRow> orderedChannels(const QJsonObject &selection, QVector<int> *originalIndex = nullptr)
{
    QVector<ChannelRow> rows;
    const QJsonArray channels = selection.value(QStringLiteral("channels")).toArray();
    for (const QJsonValue &v : channels) {
        const QJsonObject o = v.toObject();
        rows.push_back({o.value(QStringLiteral("channel")).toString(), o.value(QStringLiteral("cluster")).toInt(),
                        o.value(QStringLiteral("grade")).toDouble(), o.value(QStringLiteral("grade_all")).toDouble(),
                        o.value(QStringLiteral("chosen")).toBool()});
    }
    QVector<int> index(rows.size());
    for (int i = 0; i < rows.size(); ++i)
        index[i] = i;
    std::stable_sort(index.begin(), index.end(), [&](int a, int b) { return rows[a].cluster < rows[b].cluster; });
    QVector<ChannelRow> out;
    for (int i : index)
        out.push_back(rows[i]);
    if (originalIndex)
        *originalIndex = index;
    return out;
}

std::unique_ptr<QwtPlot> gradesPlot(const QJsonObject &selection, QWidget *parent)
{
    auto plot = std::make_unique<QwtPlot>(parent);
    plot->setCanvasBackground(Qt::white);
    const QVector<ChannelRow> rows = orderedChannels(selection);
    QStringList names;
    double lo = 1.0;
    QMap<int, QVector<QPointF>> byCluster;
    for (int i = 0; i < rows.size(); ++i) {
        names << rows[i].id + (rows[i].chosen ? QStringLiteral("*") : QString());
        byCluster[rows[i].cluster].push_back(QPointF(i, rows[i].grade));
        lo = std::min(lo, rows[i].grade);
    }
    // Bars start at the axis minimum: outputs without clipping (SVG) draw them inside the canvas too.
    const double yMin = std::max(0.0, std::floor(lo * 20.0 - 1.0) / 20.0);
    for (auto it = byCluster.begin(); it != byCluster.end(); ++it) {
        auto *bars = new QwtPlotBarChart(QObject::tr("cluster %1").arg(it.key()));
        bars->setSamples(it.value());
        bars->setBaseline(yMin);
        auto *symbol = new QwtColumnSymbol(QwtColumnSymbol::Box);
        symbol->setFrameStyle(QwtColumnSymbol::Plain);
        symbol->setPalette(QPalette(clusterColours().at((it.key() - 1) % clusterColours().size())));
        bars->setSymbol(symbol);
        bars->setLayoutPolicy(QwtPlotBarChart::ScaleSamplesToAxes);
        bars->setLayoutHint(0.7); // 70 % of the space between channels
        bars->setLegendMode(QwtPlotBarChart::LegendChartTitle);
        bars->attach(plot.get());
    }
    plot->setAxisScaleDraw(QwtPlot::xBottom, new ChannelScaleDraw(names));
    plot->setAxisScaleDiv(QwtPlot::xBottom, channelDiv(rows.size(), 0.0));
    plot->axisScaleDraw(QwtPlot::xBottom)->setLabelRotation(-45.0);
    plot->axisScaleDraw(QwtPlot::xBottom)->setLabelAlignment(Qt::AlignLeft | Qt::AlignBottom);
    plot->setAxisScale(QwtPlot::yLeft, yMin, 1.0);
    plot->setAxisTitle(QwtPlot::yLeft, QObject::tr("grey relational grade (within cluster)"));
    plot->setTitle(QObject::tr("Grey relational grade to %1, K = %2 (chosen point marked *)")
                       .arg(selection.value(QStringLiteral("target")).toString())
                       .arg(selection.value(QStringLiteral("k")).toInt()));
    plot->insertLegend(new QwtLegend(), QwtPlot::BottomLegend);
    auto *grid = new QwtPlotGrid();
    grid->enableX(false);
    grid->setMajorPen(QColor(225, 225, 225), 0.0, Qt::SolidLine);
    grid->attach(plot.get());
    plot->replot();
    return plot;
}

std::unique_ptr<QwtPlot> clustersPlot(const QJsonObject &selection, QWidget *parent)
{
    auto plot = std::make_unique<QwtPlot>(parent);
    QVector<int> index;
    const QVector<ChannelRow> rows = orderedChannels(selection, &index);
    const QJsonArray matrix = selection.value(QStringLiteral("correlation_matrix")).toArray();
    const int n = rows.size();
    if (matrix.size() != n)
        throw std::invalid_argument("the stored selection has no correlation matrix (run select-points again)");
    QVector<double> values(n * n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) // raster row 0 is the bottom: put the first channel on top
            values[(n - 1 - r) * n + c] = matrix.at(index[r]).toArray().at(index[c]).toDouble();
    auto *data = new QwtMatrixRasterData();
    data->setValueMatrix(values, n);
    data->setInterval(Qt::XAxis, QwtInterval(-0.5, n - 0.5));
    data->setInterval(Qt::YAxis, QwtInterval(-0.5, n - 0.5));
    data->setInterval(Qt::ZAxis, QwtInterval(-1.0, 1.0));
    auto colourMap = [] {
        auto *map = new QwtLinearColorMap(QColor(49, 54, 149), QColor(165, 0, 38));
        map->addColorStop(0.5, Qt::white);
        return map;
    };
    auto *spectrogram = new QwtPlotSpectrogram();
    spectrogram->setColorMap(colourMap());
    spectrogram->setData(data);
    spectrogram->attach(plot.get());
    QStringList names, reversed;
    for (const ChannelRow &r : rows)
        names << r.id + (r.chosen ? QStringLiteral("*") : QString());
    for (int i = n - 1; i >= 0; --i)
        reversed << names.at(i);
    plot->setAxisScaleDraw(QwtPlot::xBottom, new ChannelScaleDraw(names));
    plot->setAxisScaleDiv(QwtPlot::xBottom, channelDiv(n, 0.0));
    plot->axisScaleDraw(QwtPlot::xBottom)->setLabelRotation(-45.0);
    plot->axisScaleDraw(QwtPlot::xBottom)->setLabelAlignment(Qt::AlignLeft | Qt::AlignBottom);
    plot->setAxisScaleDraw(QwtPlot::yLeft, new ChannelScaleDraw(reversed));
    plot->setAxisScaleDiv(QwtPlot::yLeft, channelDiv(n, 0.0));
    plot->enableAxis(QwtPlot::yRight, true);
    plot->axisWidget(QwtPlot::yRight)->setColorBarEnabled(true);
    plot->axisWidget(QwtPlot::yRight)->setColorMap(QwtInterval(-1.0, 1.0), colourMap());
    plot->setAxisScale(QwtPlot::yRight, -1.0, 1.0);
    plot->setAxisTitle(QwtPlot::yRight, QObject::tr("correlation of the temperature rises"));
    // Cluster boundaries.
    for (int i = 1; i < n; ++i) {
        if (rows[i].cluster == rows[i - 1].cluster)
            continue;
        for (Qt::Orientation o : {Qt::Vertical, Qt::Horizontal}) {
            auto *m = new QwtPlotMarker();
            m->setLineStyle(o == Qt::Vertical ? QwtPlotMarker::VLine : QwtPlotMarker::HLine);
            m->setLinePen(Qt::black, 1.5);
            if (o == Qt::Vertical)
                m->setXValue(i - 0.5);
            else
                m->setYValue(n - i - 0.5);
            m->attach(plot.get());
        }
    }
    plot->setTitle(QObject::tr("Correlation matrix ordered by cluster (K = %1, chosen points marked *)")
                       .arg(selection.value(QStringLiteral("k")).toInt()));
    plot->replot();
    return plot;
}

std::unique_ptr<QwtPlot> pointsPlot(const QJsonObject &selection, const SessionStore *store, qint64 session, QWidget *parent)
{
    if (!store)
        throw std::invalid_argument("the points view needs the session's store");
    auto plot = std::make_unique<TimeSeriesPlot>(parent);
    QStringList wanted;
    for (const QJsonValue &c : selection.value(QStringLiteral("chosen")).toArray())
        wanted << c.toString();
    const QString target = selection.value(QStringLiteral("target")).toString();
    const double from = selection.value(QStringLiteral("from_s")).toDouble(), to = selection.value(QStringLiteral("to_s")).toDouble();
    QString targetTitle = target;
    for (const QString &id : wanted + QStringList{target}) {
        for (const ChannelInfo &c : store->channels(session)) {
            if (c.key != id)
                continue;
            const SampleBlock b = store->samples(c.id, from, to);
            plot->addCurve(QStringLiteral("%1 [%2]").arg(c.key, c.unit), b.t, b.v, id == target);
            if (id == target)
                targetTitle = QStringLiteral("%1 (%2)").arg(c.key, c.unit);
        }
    }
    plot->setAxisTitles(QObject::tr("chosen temperatures (°C)"), targetTitle);
    plot->setTitle(QObject::tr("Sensitive points chosen for %1: %2").arg(target, wanted.join(QStringLiteral(", "))));
    plot->zoomToData();
    return plot;
}

QVector<double> vec(const std::vector<double> &v)
{
    return QVector<double>(v.begin(), v.end());
}

} // namespace

QStringList AnalysisPlots::selectionViews()
{
    return {QStringLiteral("selection-grades"), QStringLiteral("selection-clusters"), QStringLiteral("selection-points")};
}

std::unique_ptr<QwtPlot> AnalysisPlots::selectionPlot(const QString &view, const QJsonObject &selection,
                                                      const SessionStore *store, qint64 session, QWidget *parent)
{
    if (view == QLatin1String("selection-grades"))
        return gradesPlot(selection, parent);
    if (view == QLatin1String("selection-clusters"))
        return clustersPlot(selection, parent);
    if (view == QLatin1String("selection-points"))
        return pointsPlot(selection, store, session, parent);
    throw std::invalid_argument(QStringLiteral("unknown view '%1'").arg(view).toStdString());
}

QJsonObject AnalysisPlots::storedSelection(const SessionStore &store, qint64 session)
{
    const QJsonObject s = store.latestAnalysisResult(session, AnalysisResultKind::sensitivePoints());
    if (s.isEmpty())
        throw std::invalid_argument(QStringLiteral("session %1 has no stored sensitive-point selection; run "
                                                   "'driftlab-cli select-points %1 --target CHANNEL' first")
                                        .arg(session)
                                        .toStdString());
    return s;
}

void AnalysisPlots::showPrediction(TimeSeriesPlot &plot, const ValidationSeries &training, const ValidationSeries *holdout)
{
    plot.clearCurves();
    const bool points = !training.position_mm.empty();
    auto add = [&](const QString &title, const std::vector<double> &t, const std::vector<double> &v) {
        QwtPlotCurve *c = plot.addCurve(title, vec(t), vec(v), false);
        if (points) {
            c->setStyle(QwtPlotCurve::NoCurve);
            c->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(c->pen().color()), QPen(c->pen().color()), QSize(4, 4)));
        }
    };
    add(QObject::tr("measured (training)"), training.t, training.measured);
    add(QObject::tr("predicted (training)"), training.t, training.predicted);
    if (holdout) {
        const QString where = holdout->session == training.session ? QObject::tr("held-out range")
                                                                  : QObject::tr("held-out session %1").arg(holdout->session);
        add(QObject::tr("measured (%1)").arg(where), holdout->t, holdout->measured);
        add(QObject::tr("predicted (%1)").arg(where), holdout->t, holdout->predicted);
    }
    plot.setAxisTitles(QObject::tr("thermal error (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    plot.zoomToData();
}

void AnalysisPlots::showResidual(TimeSeriesPlot &plot, const ValidationSeries &training, const ValidationSeries *holdout)
{
    plot.clearCurves();
    auto residual = [](const ValidationSeries &s) {
        std::vector<double> r(s.measured.size());
        for (std::size_t i = 0; i < r.size(); ++i)
            r[i] = s.measured[i] - s.predicted[i];
        return r;
    };
    plot.addCurve(QObject::tr("residual (training)"), vec(training.t), vec(residual(training)), false);
    if (holdout)
        plot.addCurve(QObject::tr("residual (held out)"), vec(holdout->t), vec(residual(*holdout)), false);
    plot.setAxisTitles(QObject::tr("measured - predicted (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    plot.zoomToData();
}

void AnalysisPlots::showSeries(TimeSeriesPlot &plot, const ValidationSeries &series, const QString &label)
{
    plot.clearCurves();
    const bool points = !series.position_mm.empty();
    for (const auto &[title, values] : {std::pair<QString, const std::vector<double> *>{QObject::tr("measured (%1)").arg(label), &series.measured},
                                        {QObject::tr("predicted (%1)").arg(label), &series.predicted}}) {
        QwtPlotCurve *c = plot.addCurve(title, vec(series.t), vec(*values), false);
        if (points) {
            c->setStyle(QwtPlotCurve::NoCurve);
            c->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(c->pen().color()), QPen(c->pen().color()), QSize(4, 4)));
        }
    }
    plot.setAxisTitles(QObject::tr("thermal error (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    plot.zoomToData();
}

void AnalysisPlots::showSeriesResidual(TimeSeriesPlot &plot, const ValidationSeries &series, const QString &label)
{
    plot.clearCurves();
    std::vector<double> r(series.measured.size());
    for (std::size_t i = 0; i < r.size(); ++i)
        r[i] = series.measured[i] - series.predicted[i];
    plot.addCurve(QObject::tr("residual (%1)").arg(label), vec(series.t), vec(r), false);
    plot.setAxisTitles(QObject::tr("measured - predicted (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    plot.zoomToData();
}

} // namespace driftlab

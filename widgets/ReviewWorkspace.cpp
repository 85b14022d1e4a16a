#include "ReviewWorkspace.h"

#include "ErrorSurface3D.h"
#include "ErrorSurfacePlot.h"
#include "InfraredPanel.h"
#include "OverlayMarks.h"
#include "SessionReviewData.h"
#include "SessionStore.h"
#include "ThermalErrorViews.h"
#include "TimeSeriesPlot.h"
#include "UnitLabels.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QTabWidget>
#include <QVBoxLayout>

#include <qwt_plot_curve.h>

#include <cmath>

namespace driftlab {

namespace {
// Channels longer than this are drawn from decimated min/max levels.
constexpr qint64 kRawCurveLimit = 20000;

enum Tab { TimeSeriesTab, SurfaceTab, ProfilesTab, HistoriesTab, TemperatureTab, ThreeDTab, InfraredTab };
} // namespace

ReviewWorkspace::ReviewWorkspace(QWidget *parent)
    : QWidget(parent),
      m_heading(new QLabel(this)),
      m_tabs(new QTabWidget(this)),
      m_timeSeries(new TimeSeriesPlot(this)),
      m_surface(new ErrorSurfacePlot(this)),
      m_profiles(new TimeSeriesPlot(this)),
      m_histories(new TimeSeriesPlot(this)),
      m_temperaturePage(new QWidget(this)),
      m_temperatureChannel(new QComboBox(this)),
      m_target(new QComboBox(this)),
      m_againstTemperature(new TimeSeriesPlot(this)),
      m_3dPage(new QWidget(this)),
      m_infrared(new InfraredPanel(this))
{
    auto *layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    m_heading->setObjectName(QStringLiteral("SessionHeading"));
    m_heading->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_heading->setContentsMargins(4, 2, 4, 0);
    m_heading->setWordWrap(true); // a long session name wraps instead of widening the compare view
    m_heading->setText(tr("No session"));
    layout->addWidget(m_heading);
    // The tab pages' widest row (pickers, infrared plots) would otherwise set the minimum:
    // two sessions compared side by side must fit beside the side docks at 1366 px.
    m_tabs->setMinimumWidth(240);
    layout->addWidget(m_tabs);
    auto *tempLayout = new QVBoxLayout(m_temperaturePage);
    auto *pickers = new QHBoxLayout();
    pickers->addWidget(new QLabel(tr("Temperature channel:"), m_temperaturePage));
    pickers->addWidget(m_temperatureChannel, 1);
    pickers->addWidget(new QLabel(tr("Target:"), m_temperaturePage));
    pickers->addWidget(m_target, 1);
    tempLayout->addLayout(pickers);
    tempLayout->addWidget(m_againstTemperature, 1);
    new QVBoxLayout(m_3dPage);

    m_tabs->insertTab(TimeSeriesTab, m_timeSeries, tr("Channels"));
    m_tabs->insertTab(SurfaceTab, m_surface, tr("Error surface"));
    m_tabs->insertTab(ProfilesTab, m_profiles, tr("Error vs position"));
    m_tabs->insertTab(HistoriesTab, m_histories, tr("Error vs time"));
    m_tabs->insertTab(TemperatureTab, m_temperaturePage, tr("Error vs temperature"));
    m_tabs->insertTab(ThreeDTab, m_3dPage, tr("3-D surface"));
    m_tabs->insertTab(InfraredTab, m_infrared, tr("Infrared"));
    connect(m_temperatureChannel, QOverload<int>::of(&QComboBox::currentIndexChanged), this,
            &ReviewWorkspace::updateTemperatureView);
    connect(m_target, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &ReviewWorkspace::updateTemperatureView);
    // The 3-D view needs OpenGL: create it only when someone looks at it.
    connect(m_tabs, &QTabWidget::currentChanged, this, [this](int index) {
        if (index == ThreeDTab)
            ensure3D();
    });
    clear();
}

ReviewWorkspace::~ReviewWorkspace() = default;

QString ReviewWorkspace::heading() const
{
    return m_heading->text();
}

void ReviewWorkspace::clear()
{
    m_store = nullptr;
    m_sessionId = 0;
    m_data.reset();
    m_hasErrors = false;
    m_overlay.clear();
    m_envelopes.clear();
    clearMarks();
    m_timeSeries->clearCurves();
    m_heading->setText(tr("No session"));
    m_tabs->setCurrentIndex(TimeSeriesTab); // before disabling the others (see setSession)
    for (int t = SurfaceTab; t <= InfraredTab; ++t)
        m_tabs->setTabEnabled(t, false);
}

void ReviewWorkspace::setSession(const SessionStore *store, qint64 sessionId)
{
    auto data = std::make_shared<SessionReviewData>(*store, sessionId);
    const TimeSeriesPlot::Batch batch(m_timeSeries); // events and curves, then one replot
    m_store = store;
    m_sessionId = sessionId;
    m_data = data;
    m_overlay.clear();
    m_envelopes.clear();
    // Envelopes of a finished session do not change (overlaid sessions' channels: same rule).
    m_envelopesComplete = data->info().complete;
    m_timeSeries->setTitle(data->info().name);
    const SessionInfo &info = data->info();
    m_heading->setText(tr("<b>Session #%1</b>&nbsp;&nbsp;%2&nbsp;&nbsp;<span style='color:#555'>started %3 UTC%4%5</span>")
                           .arg(sessionId)
                           .arg(info.name.toHtmlEscaped(), UnitLabels::startTime(info.started).toHtmlEscaped(),
                                info.operatorName.isEmpty() ? QString() : tr(", operator %1").arg(info.operatorName.toHtmlEscaped()),
                                info.complete ? QString() : tr(", incomplete")));
    m_timeSeries->setEvents(store->events(sessionId));

    m_hasErrors = data->hasInterferometer();
    // Leave a tab before disabling it: QTabWidget would move on to the next enabled one,
    // the 3-D tab among them, and build its OpenGL view for nothing.
    const int current = m_tabs->currentIndex();
    if ((current >= SurfaceTab && current <= ThreeDTab && !m_hasErrors) ||
        (current == InfraredTab && data->infraredFrames().isEmpty()))
        m_tabs->setCurrentIndex(TimeSeriesTab);
    for (int t = SurfaceTab; t <= ThreeDTab; ++t) {
        m_tabs->setTabEnabled(t, m_hasErrors);
        m_tabs->setTabToolTip(t, m_hasErrors ? QString()
                                             : tr("This session has no interferometer runs besides the reference run: "
                                                  "no thermal errors to show"));
    }
    m_profiles->clearCurves();
    m_profiles->setFooter(QString());
    if (!m_hasErrors)
        m_surface->showEmpty(tr("This session has no interferometer runs besides the reference run: no thermal errors to show."));
    if (m_hasErrors) {
        const ThermalErrorTable table = data->thermalErrors();
        m_surface->setTable(table);
        ThermalErrorViews::showProfiles(*m_profiles, table);
        ThermalErrorViews::showHistories(*m_histories, table);
        m_target->blockSignals(true);
        m_temperatureChannel->blockSignals(true);
        m_target->clear();
        for (double x : table.targets_mm())
            m_target->addItem(ThermalErrorViews::targetLabel(x));
        m_target->setCurrentIndex(m_target->count() - 1);
        m_temperatureChannel->clear();
        for (const ChannelInfo &c : data->channels()) {
            if (c.kind == QLatin1String("temperature"))
                m_temperatureChannel->addItem(QStringLiteral("%1 (%2)").arg(c.key, c.role), c.id);
        }
        // Start on the temperature that explains the far target's error best.
        int best = 0;
        double bestR2 = -1.0;
        TimeSeriesPlot scratch;
        for (int i = 0; i < m_temperatureChannel->count(); ++i) {
            const LineFit fit = ThermalErrorViews::showAgainstTemperature(
                scratch, table, table.targetCount() - 1, data->series(m_temperatureChannel->itemData(i).toLongLong()),
                QString());
            if (fit.r2 > bestR2) {
                bestR2 = fit.r2;
                best = i;
            }
        }
        m_temperatureChannel->setCurrentIndex(best);
        m_target->blockSignals(false);
        m_temperatureChannel->blockSignals(false);
        updateTemperatureView();
        if (m_3d)
            m_3d->setTable(table);
    }
    m_tabs->setTabEnabled(InfraredTab, !data->infraredFrames().isEmpty());
    m_tabs->setTabToolTip(InfraredTab, data->infraredFrames().isEmpty() ? tr("This session has no infrared frames") : QString());
    if (!m_tabs->isTabEnabled(m_tabs->currentIndex()))
        m_tabs->setCurrentIndex(TimeSeriesTab);
    m_infrared->setSession(data);
    showChannels(defaultChannels());
}

QVector<qint64> ReviewWorkspace::defaultChannels() const
{
    QVector<qint64> shown;
    if (!m_data)
        return shown;
    // Temperatures and displacements, not the CNC's fast position and feed.
    for (const ChannelInfo &c : m_data->channels()) {
        if (c.kind == QLatin1String("temperature") || c.kind == QLatin1String("displacement"))
            shown.push_back(c.id);
    }
    return shown;
}

QwtPlotCurve *ReviewWorkspace::addChannelCurve(qint64 id, const QString &title, bool right, bool keep)
{
    // One query decides and draws (a 10-hour open spent most of its time in three per
    // channel: count, span, envelope): the whole channel's envelope at one bucket per pixel
    // column. Channels over kRawCurveLimit samples are drawn decimated; shorter ones raw (the
    // level-0 answer is the samples themselves when no more than one falls in a bucket). A
    // finished session's curves are kept for the next showChannels() or overlay.
    const SessionStore *store = m_store;
    const int buckets = m_timeSeries->decimationBuckets();
    auto fetch = [store, id](double t0, double t1, int n) { return store->decimated(id, t0, t1, n); };
    auto draw = [&](const KeptCurve &k) {
        return k.decimated ? m_timeSeries->addDecimatedCurve(title, fetch, k.envelope, right)
                           : m_timeSeries->addCurve(title, k.envelope.x, k.envelope.y, right);
    };
    auto cached = m_envelopes.constFind(id);
    if (cached != m_envelopes.cend() && cached->envelope.buckets <= buckets)
        return draw(*cached);
    const DecimatedSeries whole = store->decimated(id, -1e300, 1e300, buckets);
    KeptCurve kept;
    // Level 2 or coarser holds >= 200 entries of 256 samples: far over kRawCurveLimit. At
    // level 1 the count decides (one more query, only for such mid-length channels).
    kept.decimated = whole.level >= 2 || (whole.level == 1 && store->sampleCount(id) > kRawCurveLimit);
    if (kept.decimated) {
        kept.envelope = TimeSeriesPlot::envelope(whole, buckets);
    } else {
        bool raw = true;
        for (int i = 0; i < whole.tFirst.size() && raw; ++i)
            raw = whole.tFirst[i] == whole.tLast[i];
        kept.envelope.buckets = whole.tFirst.size();
        if (raw) {
            kept.envelope.x = whole.tFirst;
            kept.envelope.y = whole.min;
        } else {
            const SampleBlock block = m_store->samples(id);
            kept.envelope.x = block.t;
            kept.envelope.y = block.v;
        }
    }
    if (keep && m_envelopesComplete)
        m_envelopes.insert(id, kept);
    return draw(kept);
}

void ReviewWorkspace::setOverlay(const QVector<qint64> &sessionIds)
{
    m_overlay.clear();
    for (qint64 id : sessionIds)
        if (id != m_sessionId && id != 0 && !m_overlay.contains(id))
            m_overlay.push_back(id);
    if (!m_store || !m_data)
        return;
    // The title says which session each mark is (showChannels: the overlaid sessions' curves
    // carry open symbols, a dash pattern is invisible on dense noisy data).
    QStringList names{tr("#%1 %2 (line)").arg(m_sessionId).arg(m_data->info().name)};
    for (int k = 0; k < m_overlay.size(); ++k)
        names << tr("#%1 %2 (line with %3)").arg(m_overlay[k]).arg(m_store->session(m_overlay[k]).name, OverlayMarks::styleName(k + 1));
    m_timeSeries->setTitle(m_overlay.isEmpty() ? m_data->info().name : names.join(QStringLiteral(", ")));
    showChannels(m_shown);
    updateProfiles();
    if (m_tabs->currentIndex() != ProfilesTab || !m_tabs->isTabEnabled(ProfilesTab))
        m_tabs->setCurrentIndex(TimeSeriesTab);
}

void ReviewWorkspace::clearMarks()
{
    for (OverlayMarks *m : m_marks) {
        m->detach();
        delete m;
    }
    m_marks.clear();
}

void ReviewWorkspace::updateProfiles()
{
    m_profiles->setFooter(QString());
    if (m_overlay.isEmpty()) {
        if (m_hasErrors)
            ThermalErrorViews::showProfiles(*m_profiles, m_data->thermalErrors());
        m_tabs->setTabEnabled(ProfilesTab, m_hasErrors);
        return;
    }
    QStringList names, without;
    std::vector<ThermalErrorTable> tables;
    auto add = [&](qint64 id, const SessionReviewData &d) {
        const QString name = QStringLiteral("#%1 %2").arg(id).arg(d.info().name);
        if (!d.hasInterferometer()) {
            without << name;
            return;
        }
        tables.push_back(d.thermalErrors());
        names << QStringLiteral("%1 (%2)").arg(name, UnitLabels::startTime(d.info().started));
    };
    add(m_sessionId, *m_data);
    for (qint64 id : m_overlay)
        add(id, SessionReviewData(*m_store, id));
    ThermalErrorViews::showLastRuns(*m_profiles, names, tables);
    if (!without.isEmpty())
        m_profiles->setFooter(tr("No interferometer runs: %1").arg(without.join(QStringLiteral(", "))));
    if (tables.empty() && m_tabs->currentIndex() == ProfilesTab)
        m_tabs->setCurrentIndex(TimeSeriesTab);
    m_tabs->setTabEnabled(ProfilesTab, !tables.empty());
    m_tabs->setTabToolTip(ProfilesTab, tables.empty() ? tr("None of these sessions has interferometer runs") : QString());
}

void ReviewWorkspace::showChannels(const QVector<qint64> &channelIds)
{
    m_shown = channelIds;
    const TimeSeriesPlot::Batch batch(m_timeSeries);
    clearMarks();
    m_timeSeries->clearCurves();
    m_leftOut.clear();
    if (!m_store || !m_data)
        return;
    // One unit per value axis (an axis reading "(µm, mm)" is no scale): temperatures on the
    // left, the first other unit on the right (on the left when no temperature is shown);
    // channels of a third unit are left out and the plot's footer says so.
    QVector<ChannelInfo> chosen;
    for (const ChannelInfo &c : m_data->channels())
        if (channelIds.contains(c.id))
            chosen.push_back(c);
    QString leftUnit, rightUnit;
    for (const ChannelInfo &c : chosen)
        if (c.kind == QLatin1String("temperature") && leftUnit.isEmpty())
            leftUnit = c.unit;
    for (const ChannelInfo &c : chosen) {
        if (leftUnit.isEmpty())
            leftUnit = c.unit;
        else if (rightUnit.isEmpty() && c.unit != leftUnit)
            rightUnit = c.unit;
    }
    QStringList leftNames, rightNames, leftOut;
    for (const ChannelInfo &c : chosen) {
        const bool right = c.unit == rightUnit && c.unit != leftUnit;
        if (c.unit != leftUnit && !right) {
            leftOut << QStringLiteral("%1 (%2)").arg(c.key, UnitLabels::display(c.unit));
            continue;
        }
        // Overlaid sessions (setOverlay): the same channel (key and unit) of each, marked with
        // open circles, triangles, ... (OverlayMarks); every curve then names its session.
        for (int k = 0; k <= m_overlay.size(); ++k) {
            const qint64 session = k == 0 ? m_sessionId : m_overlay[k - 1];
            qint64 id = k == 0 ? c.id : 0;
            for (const ChannelInfo &o : k == 0 ? QVector<ChannelInfo>() : m_store->channels(session))
                if (o.key == c.key && o.unit == c.unit)
                    id = o.id;
            if (id == 0)
                continue;
            const QString name = m_overlay.isEmpty() ? c.key : QStringLiteral("#%1 %2").arg(session).arg(c.key);
            QwtPlotCurve *curve = addChannelCurve(id, name, right, k == 0); // keeps this session's curves
            if (k > 0) {
                auto *marks = new OverlayMarks(curve, k);
                marks->attach(m_timeSeries);
                m_marks.push_back(marks);
            }
        }
        QStringList &names = right ? rightNames : leftNames;
        if (!names.contains(UnitLabels::quantity(c.kind)))
            names << UnitLabels::quantity(c.kind);
    }
    if (!leftOut.isEmpty())
        m_leftOut = tr("Not drawn: %1 (a third unit; a plot has two value axes)").arg(leftOut.join(QStringLiteral(", ")));
    m_timeSeries->setFooter(m_leftOut);
    m_timeSeries->enableAxis(QwtPlot::yRight, !rightUnit.isEmpty());
    auto title = [](const QStringList &names, const QString &unit) {
        return unit.isEmpty() ? QString() : QStringLiteral("%1 (%2)").arg(names.join(QStringLiteral(", ")), UnitLabels::display(unit));
    };
    m_timeSeries->setAxisTitles(title(leftNames, leftUnit), title(rightNames, rightUnit));
    m_timeSeries->zoomToData();
}

void ReviewWorkspace::updateTemperatureView()
{
    if (!m_data || !m_hasErrors || m_temperatureChannel->count() == 0 || m_target->currentIndex() < 0)
        return;
    const qint64 id = m_temperatureChannel->currentData().toLongLong();
    ThermalErrorViews::showAgainstTemperature(*m_againstTemperature, m_data->thermalErrors(),
                                              static_cast<std::size_t>(m_target->currentIndex()), m_data->series(id),
                                              m_temperatureChannel->currentText().section(QLatin1Char(' '), 0, 0));
}

bool ReviewWorkspace::selectTarget(double position_mm)
{
    if (!m_data || !m_hasErrors)
        return false;
    const std::vector<double> targets = m_data->thermalErrors().targets_mm();
    int best = 0;
    for (int i = 1; i < static_cast<int>(targets.size()); ++i)
        if (std::fabs(targets[static_cast<size_t>(i)] - position_mm) < std::fabs(targets[static_cast<size_t>(best)] - position_mm))
            best = i;
    m_target->setCurrentIndex(best);
    updateTemperatureView();
    return true;
}

void ReviewWorkspace::ensure3D()
{
    if (m_3d)
        return;
    m_3d = new ErrorSurface3D(m_3dPage);
    m_3dPage->layout()->addWidget(m_3d);
    if (m_data && m_hasErrors)
        m_3d->setTable(m_data->thermalErrors());
}

QStringList ReviewWorkspace::viewNames()
{
    return {QStringLiteral("timeseries"), QStringLiteral("error-surface"), QStringLiteral("error-position"),
            QStringLiteral("error-time"), QStringLiteral("error-temperature"), QStringLiteral("ir-profile"),
            QStringLiteral("ir-surface")};
}

QwtPlot *ReviewWorkspace::plotForView(const QString &name)
{
    const int index = viewNames().indexOf(name);
    const bool errors = m_hasErrors;
    const bool ir = m_infrared->frameCount() > 0;
    switch (index) {
    case 0:
        m_tabs->setCurrentIndex(TimeSeriesTab);
        return m_timeSeries;
    case 1:
        m_tabs->setCurrentIndex(SurfaceTab);
        return errors ? m_surface : nullptr;
    case 2:
        m_tabs->setCurrentIndex(ProfilesTab);
        return m_tabs->isTabEnabled(ProfilesTab) ? m_profiles : nullptr; // own runs, or an overlay's
    case 3:
        m_tabs->setCurrentIndex(HistoriesTab);
        return errors ? m_histories : nullptr;
    case 4:
        m_tabs->setCurrentIndex(TemperatureTab);
        return errors && m_temperatureChannel->count() > 0 ? m_againstTemperature : nullptr;
    case 5:
        m_tabs->setCurrentIndex(InfraredTab);
        return ir ? static_cast<QwtPlot *>(m_infrared->profilePlot()) : nullptr;
    case 6:
        m_tabs->setCurrentIndex(InfraredTab);
        return ir && m_infrared->frameCount() >= 2 ? static_cast<QwtPlot *>(m_infrared->profileSurface()) : nullptr;
    default:
        return nullptr;
    }
}

bool ReviewWorkspace::selectView(const QString &name)
{
    if (name == QLatin1String("error-3d")) {
        if (!m_hasErrors)
            return false;
        m_tabs->setCurrentIndex(ThreeDTab);
        return true;
    }
    return plotForView(name) != nullptr;
}

QString ReviewWorkspace::currentViewName() const
{
    switch (m_tabs->currentIndex()) {
    case SurfaceTab:
        return QStringLiteral("error-surface");
    case ProfilesTab:
        return QStringLiteral("error-position");
    case HistoriesTab:
        return QStringLiteral("error-time");
    case TemperatureTab:
        return QStringLiteral("error-temperature");
    case InfraredTab:
        return QStringLiteral("ir-profile");
    default:
        return QStringLiteral("timeseries");
    }
}

} // namespace driftlab

#include "LiveRecordingView.h"

#include "PlotInteraction.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "UnitLabels.h"

#include <QDoubleSpinBox>
#include <QEvent>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonDocument>
#include <QLabel>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <QScrollBar>
#include <QSettings>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>

#include <qwt_plot_canvas.h>
#include <qwt_plot_curve.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>

namespace driftlab {

namespace {
enum Column { ColChannel, ColValue, ColLow, ColHigh, ColCount };
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

QString limitText(double v)
{
    return std::isnan(v) ? QString() : QLocale().toString(v, 'g', 6);
}

double parseLimit(const QString &text)
{
    const QString s = text.trimmed();
    if (s.isEmpty())
        return kNaN;
    bool ok = false;
    double v = QLocale().toDouble(s, &ok);
    if (!ok)
        v = s.toDouble(&ok);
    return ok ? v : kNaN;
}

bool isTemperature(const ChannelInfo &c)
{
    return c.kind == QLatin1String("temperature");
}

QString settingsKey(const QString &rig)
{
    QString key = rig;
    key.replace(QLatin1Char('/'), QLatin1Char('_')).replace(QLatin1Char('\\'), QLatin1Char('_'));
    return QStringLiteral("liveLimits/") + key;
}
} // namespace

LiveRecordingView::LiveRecordingView(QWidget *parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("LiveRecordingView"));
    m_title = new QLabel(tr("No recording"), this);
    QFont bold = m_title->font();
    bold.setBold(true);
    m_title->setFont(bold);
    // Both wrap: a long session name or clock line must not widen the central area past a
    // 1366-pixel screen beside the docks (it did, by 20 px, while recording).
    m_title->setWordWrap(true);
    m_clock = new QLabel(this);
    m_clock->setWordWrap(true);
    m_alarm = new QLabel(this);
    m_alarm->setObjectName(QStringLiteral("LiveAlarm"));
    m_alarm->setWordWrap(true);
    m_alarm->setStyleSheet(QStringLiteral("QLabel { background: #b00020; color: white; padding: 4px; font-weight: bold; }"));
    m_alarm->hide();
    m_stop = new QPushButton(tr("Stop recording..."), this);
    m_stop->setEnabled(false);
    m_table = new QTableWidget(0, ColCount, this);
    m_table->setHorizontalHeaderLabels({tr("Channel"), tr("Value"), tr("Low"), tr("High")});
    m_table->horizontalHeaderItem(ColLow)->setToolTip(tr("Low limit (empty: none)"));
    m_table->horizontalHeaderItem(ColHigh)->setToolTip(tr("High limit (empty: none)"));
    m_table->verticalHeader()->hide();
    // Column widths are set once per recording: ResizeToContents would measure every row at
    // every value change (10 times a second, 68 rows).
    m_table->horizontalHeader()->setSectionResizeMode(QHeaderView::Interactive);
    m_table->horizontalHeader()->setSectionResizeMode(ColChannel, QHeaderView::Stretch);
    m_table->horizontalHeader()->setStretchLastSection(false);
    m_table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    // Before the first recording (no rows to size by) the four headers at their own width,
    // not Qt's 100 px each: the empty table fits its side of the view as the filled one does.
    m_table->horizontalHeader()->setMinimumSectionSize(24);
    m_table->horizontalHeader()->setDefaultSectionSize(m_table->fontMetrics().horizontalAdvance(QStringLiteral("-000.0")) + 10);
    m_table->setToolTip(tr("Tick the channels to plot; a value outside the low or high limit raises an alarm, "
                           "stored as an event of the session (empty: no limit)"));
    m_silent = new QDoubleSpinBox(this);
    m_silent->setRange(0.0, 86400.0);
    m_silent->setDecimals(0);
    m_silent->setSuffix(tr(" s"));
    m_silent->setSpecialValueText(tr("not watched"));
    m_silent->setToolTip(tr("A channel with a limit that delivers no sample for this long (session time) raises "
                            "\"sensor silent\""));
    m_plot = new TimeSeriesPlot(this);
    m_plot->insertLegend(nullptr); // the channel table is the legend (64 channels would bury the plot)
    m_plot->setAxisTitles(tr("temperature (°C)"), tr("elongation (µm)"));
    m_plot->setAxisScale(QwtPlot::yLeft, 15.0, 35.0);
    m_plot->setAxisScale(QwtPlot::yRight, -5.0, 50.0);
    m_plot->setAxisScale(QwtPlot::xBottom, 0.0, 60.0);
    m_plot->canvas()->installEventFilter(this);
    // The canvas paints inside replot(), so that drawCurves() measures what drawing costs.
    if (auto *canvas = qobject_cast<QwtPlotCanvas *>(m_plot->canvas()))
        canvas->setPaintAttribute(QwtPlotCanvas::ImmediatePaint, true);
    m_drawLater = new QTimer(this);
    m_drawLater->setSingleShot(true);
    connect(m_drawLater, &QTimer::timeout, this, [this] {
        if (std::any_of(m_tracked.cbegin(), m_tracked.cend(), [](const Tracked &t) { return t.dirty; }))
            drawCurves(m_waitingNow_s);
    });

    auto *top = new QHBoxLayout;
    top->addWidget(m_title, 1);
    top->addSpacing(12);
    top->addWidget(m_clock, 1);
    top->addWidget(m_stop);
    auto *side = new QWidget(this);
    auto *sideLayout = new QVBoxLayout(side);
    sideLayout->setContentsMargins(0, 0, 0, 0);
    sideLayout->addWidget(m_table, 1);
    auto *silentForm = new QFormLayout;
    silentForm->addRow(tr("Sensor silent after"), m_silent);
    sideLayout->addLayout(silentForm);
    auto *split = new QSplitter(Qt::Horizontal, this);
    m_split = split;
    split->addWidget(side);
    split->addWidget(m_plot);
    split->setStretchFactor(0, 0);
    split->setStretchFactor(1, 1);
    split->setChildrenCollapsible(false);
    split->setSizes({240, 1000});
    auto *layout = new QVBoxLayout(this);
    layout->addLayout(top);
    layout->addWidget(m_alarm);
    layout->addWidget(split, 1);

    m_ask = [](QWidget *parent) {
        return QMessageBox::question(parent, tr("Stop recording"),
                                     tr("Stop the recording? The session is closed and cannot be continued."),
                                     QMessageBox::Yes | QMessageBox::No, QMessageBox::No) == QMessageBox::Yes;
    };
    connect(m_stop, &QPushButton::clicked, this, &LiveRecordingView::requestStop);
    connect(m_table, &QTableWidget::itemChanged, this, [this](QTableWidgetItem *item) {
        if (m_filling)
            return;
        if (item->column() == ColChannel) {
            const QString key = item->data(Qt::UserRole).toString();
            if (QwtPlotCurve *c = m_plot->curve(key)) {
                c->setVisible(item->checkState() == Qt::Checked);
                if (m_tracked.constFind(key)->dirty) // samples it took while hidden, not drawn yet
                    drawCurves(m_drawnAt_s);
                else
                    m_plot->replot();
            }
        } else if (item->column() == ColLow || item->column() == ColHigh) {
            readLimitsFromTable(item->row());
            stateLimits();
        }
    });
    connect(m_silent, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this](double) {
        if (m_filling)
            return;
        for (int r = 0; r < m_table->rowCount(); ++r)
            readLimitsFromTable(r);
        stateLimits();
    });
}

void LiveRecordingView::begin(const QString &title, const QString &rig, double end_s)
{
    m_rig = rig;
    m_end_s = end_s;
    m_active = true;
    m_refreshes = 0;
    m_title->setText(title);
    m_stop->setEnabled(true);
    m_plot->clearCurves();
    for (int axis : {QwtPlot::yLeft, QwtPlot::yRight, QwtPlot::xBottom})
        m_plot->setAxisAutoScale(axis, true);
    if (PlotInteraction *i = PlotInteraction::of(m_plot))
        i->clearZoomHistory();
    m_channels.clear();
    m_tracked.clear();
    m_drawnAt_s = -std::numeric_limits<double>::infinity();
    m_drawnColumn_s = 0.0;
    m_drawnColumns = 0;
    m_draws = 0;
    m_drawCost_ns = 0;
    m_drawLater->stop();
    m_filling = true;
    m_table->setRowCount(0);
    m_filling = false;
    m_monitor.reset();
    m_statedLimits.clear();
    m_monitor.fromJson(QJsonDocument::fromJson(QSettings().value(settingsKey(rig)).toByteArray()).object());
    double silent = 0.0;
    for (const QString &key : m_monitor.limitedChannels())
        silent = std::max(silent, m_monitor.limit(key).silent_s);
    m_filling = true;
    m_silent->setValue(silent);
    m_filling = false;
    showAlarms();
    setClock(0.0, false);
}

void LiveRecordingView::finish(const QString &message)
{
    m_active = false;
    m_stop->setEnabled(false);
    m_clock->setText(message);
}

void LiveRecordingView::setClock(double now_s, bool paused)
{
    QString text = tr("%1 elapsed").arg(UnitLabels::clock(now_s));
    if (m_end_s > 0)
        text += tr(", %1 remaining").arg(UnitLabels::clock(std::max(0.0, m_end_s - now_s)));
    else
        text += tr(", until Stop");
    if (paused)
        text += tr(" (paused)");
    m_clock->setText(text);
}

QString LiveRecordingView::clockText() const
{
    return m_clock->text();
}

void LiveRecordingView::rebuildTable(const QVector<ChannelInfo> &channels)
{
    m_channels = channels;
    m_filling = true;
    m_table->setRowCount(channels.size());
    for (int r = 0; r < channels.size(); ++r) {
        const ChannelInfo &c = channels[r];
        const QString unit = UnitLabels::display(c.unit);
        m_monitor.setChannel(c.key, unit, isTemperature(c));
        auto *name = new QTableWidgetItem(c.key);
        name->setToolTip(unit.isEmpty() ? c.key : QStringLiteral("%1 [%2]").arg(c.key, unit));
        name->setData(Qt::UserRole, c.key);
        name->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable | Qt::ItemIsSelectable);
        const bool plotted = isTemperature(c) || c.kind == QLatin1String("displacement");
        name->setCheckState(plotted ? Qt::Checked : Qt::Unchecked);
        m_table->setItem(r, ColChannel, name);
        auto *value = new QTableWidgetItem;
        value->setToolTip(unit); // the unit: in the channel's tooltip too, and on the plot's axis
        value->setFlags(Qt::ItemIsEnabled);
        value->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        m_table->setItem(r, ColValue, value);
        const LiveLimitMonitor::Limit l = m_monitor.limit(c.key);
        m_table->setItem(r, ColLow, new QTableWidgetItem(limitText(l.low)));
        m_table->setItem(r, ColHigh, new QTableWidgetItem(limitText(l.high)));
        m_table->item(r, ColValue)->setText(QStringLiteral("-0,000.00")); // sized for, below
        if (!m_tracked.contains(c.key)) {
            Tracked t;
            t.id = c.id;
            t.unit = c.unit;
            t.temperature = isTemperature(c);
            m_tracked.insert(c.key, t);
        }
    }
    m_table->resizeColumnsToContents();
    for (int c : {ColLow, ColHigh})
        m_table->setColumnWidth(c, m_table->fontMetrics().horizontalAdvance(QStringLiteral("-000.0")) + 10);
    for (int r = 0; r < channels.size(); ++r)
        m_table->item(r, ColValue)->setText(QString());
    // The whole table beside the plot, without sideways scrolling (at most 45 % of the view).
    // The channel column stretches (and elides, its tooltip naming it): the side is sized
    // for the longest name, yet a narrower side never scrolls sideways.
    int width = 2 * m_table->frameWidth() + m_table->verticalScrollBar()->sizeHint().width() + 4;
    for (int c = 0; c < ColCount; ++c)
        width += c == ColChannel ? std::max(static_cast<const QAbstractItemView *>(m_table)->sizeHintForColumn(c), m_table->horizontalHeader()->sectionSizeHint(c))
                                 : m_table->columnWidth(c);
    if (m_split)
        m_split->setSizes({std::min(width, m_split->width() * 9 / 20), std::max(1, m_split->width() - width)});
    m_filling = false;
}

void LiveRecordingView::readLimitsFromTable(int row)
{
    const QTableWidgetItem *name = m_table->item(row, ColChannel);
    if (!name)
        return;
    LiveLimitMonitor::Limit l;
    l.low = parseLimit(m_table->item(row, ColLow) ? m_table->item(row, ColLow)->text() : QString());
    l.high = parseLimit(m_table->item(row, ColHigh) ? m_table->item(row, ColHigh)->text() : QString());
    l.silent_s = m_silent->value();
    m_monitor.setLimit(name->data(Qt::UserRole).toString(), l);
    saveLimits();
}

void LiveRecordingView::setLimit(const QString &key, const LiveLimitMonitor::Limit &limit)
{
    m_monitor.setLimit(key, limit);
    m_filling = true;
    for (int r = 0; r < m_table->rowCount(); ++r) {
        if (m_table->item(r, ColChannel)->data(Qt::UserRole).toString() != key)
            continue;
        m_table->item(r, ColLow)->setText(limitText(limit.low));
        m_table->item(r, ColHigh)->setText(limitText(limit.high));
    }
    m_filling = false;
    saveLimits();
    stateLimits();
}

void LiveRecordingView::saveLimits()
{
    if (!m_rig.isEmpty())
        QSettings().setValue(settingsKey(m_rig), QJsonDocument(m_monitor.toJson()).toJson(QJsonDocument::Compact));
}

void LiveRecordingView::stateLimits()
{
    if (!m_active || m_channels.isEmpty())
        return;
    const QString text = m_monitor.describe();
    if (text == m_statedLimits)
        return;
    m_statedLimits = text;
    emit limitsApplied(text);
}

void LiveRecordingView::setChannelShown(const QString &key, bool shown)
{
    for (int r = 0; r < m_table->rowCount(); ++r)
        if (m_table->item(r, ColChannel)->data(Qt::UserRole).toString() == key)
            m_table->item(r, ColChannel)->setCheckState(shown ? Qt::Checked : Qt::Unchecked);
}

bool LiveRecordingView::channelShown(const QString &key) const
{
    for (int r = 0; r < m_table->rowCount(); ++r)
        if (m_table->item(r, ColChannel)->data(Qt::UserRole).toString() == key)
            return m_table->item(r, ColChannel)->checkState() == Qt::Checked;
    return false;
}

QStringList LiveRecordingView::channelKeys() const
{
    QStringList keys;
    for (const ChannelInfo &c : m_channels)
        keys << c.key;
    return keys;
}

void LiveRecordingView::update(const SessionStore &reader, qint64 sessionId, double now_s)
{
    if (sessionId <= 0)
        return;
    // Channels are created when the recording starts; re-read until there are some.
    if (m_channels.isEmpty()) {
        const QVector<ChannelInfo> channels = reader.channels(sessionId);
        if (channels.isEmpty())
            return;
        rebuildTable(channels);
        stateLimits(); // the limits this recording starts with, stored with it
    }
    QVector<LiveLimitMonitor::Alarm> alarms;
    bool force = false;
    for (int r = 0; r < m_channels.size(); ++r) {
        const ChannelInfo &c = m_channels[r];
        Tracked &ch = m_tracked[c.key];
        double last = kNaN;
        bool grew = false; // the envelope took samples this time
        if (!ch.seeded) {
            // The first look: what is stored so far, decimated (a session opened late, or long).
            ch.seeded = true;
            const DecimatedSeries d = reader.decimated(c.id, 0.0, std::max(1.0, now_s), ch.envelope.capacity() / 4);
            for (int i = 0; i < d.min.size(); ++i)
                ch.envelope.appendRange(d.tFirst[i], d.tLast[i], d.min[i], d.max[i]);
            if (!d.tLast.isEmpty()) {
                ch.checked_t = d.tLast.last();
                ch.lastSample_t = d.tLast.last();
                last = d.max.last();
                grew = true;
            }
        }
        // Only what is new since the last look.
        const SampleBlock fresh = reader.samples(c.id, std::nextafter(ch.checked_t, std::numeric_limits<double>::infinity()), 1e300);
        if (!fresh.t.isEmpty()) {
            ch.checked_t = fresh.t.last();
            ch.lastSample_t = std::isnan(ch.lastSample_t) ? fresh.t.last() : std::max(ch.lastSample_t, fresh.t.last());
            ch.envelope.append(fresh.t, fresh.v);
            last = fresh.v.last();
            grew = true;
        }
        if (m_monitor.limit(c.key).any())
            alarms += m_monitor.observe(c.key, fresh.t, fresh.v, ch.lastSample_t, now_s);
        if (grew) {
            ch.dirty = true;
            // A new curve (a seeded one too: a finished or paused session has no fresh samples
            // to wait for) is drawn at once.
            force = force || !m_plot->curve(c.key);
        }
        // The table repaints only what changed.
        const QString text = std::isnan(last) ? ch.shownValue : QLocale().toString(last, 'f', 2);
        const bool alarm = m_monitor.inAlarm(c.key);
        if (text != ch.shownValue || alarm != ch.shownAlarm) {
            m_filling = true;
            m_table->item(r, ColValue)->setText(text);
            m_table->item(r, ColValue)->setBackground(alarm ? QBrush(QColor(255, 205, 210)) : QBrush());
            m_filling = false;
            ch.shownValue = text;
            ch.shownAlarm = alarm;
        }
    }
    if (drawDue(now_s, force) && !drawWaits(now_s))
        drawCurves(now_s);
    ++m_refreshes;
    for (const LiveLimitMonitor::Alarm &a : alarms)
        emit alarmRaised(a.label);
    showAlarms();
}

bool LiveRecordingView::drawDue(double now_s, bool force) const
{
    if (std::none_of(m_tracked.cbegin(), m_tracked.cend(), [](const Tracked &t) { return t.dirty; }))
        return false;
    if (force || m_plot->decimationBuckets() != m_drawnColumns || !(now_s - m_drawnAt_s < m_drawnColumn_s))
        return true;
    for (const ChannelInfo &c : m_channels) {
        const Tracked &ch = *m_tracked.constFind(c.key);
        const QwtPlotCurve *curve = m_plot->curve(c.key);
        if (!ch.dirty || !curve || !curve->isVisible())
            continue;
        double lo = kNaN, hi = kNaN;
        ch.envelope.rangeFrom(ch.drawnTail_t, lo, hi);
        const QwtScaleMap map = m_plot->canvasMap(curve->yAxis());
        auto moved = [&map](double now, double drawn) {
            return std::isnan(drawn) ? !std::isnan(now) : std::abs(map.transform(now) - map.transform(drawn)) >= 1.0;
        };
        if (moved(lo, ch.drawnTailMin) || moved(hi, ch.drawnTailMax))
            return true;
    }
    return false;
}

bool LiveRecordingView::drawWaits(double now_s)
{
    if (m_drawCost_ns <= 10'000'000 || !m_sinceDraw.isValid())
        return false;
    const qint64 wait_ms = static_cast<qint64>(m_drawCost_ns / kDrawBudget / 1e6) - m_sinceDraw.elapsed();
    if (wait_ms <= 0)
        return false;
    m_waitingNow_s = now_s;
    if (!m_drawLater->isActive())
        m_drawLater->start(static_cast<int>(wait_ms));
    return true;
}

void LiveRecordingView::drawCurves(double now_s)
{
    m_drawLater->stop();
    timespec cpu0{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu0);
    const int columns = m_plot->decimationBuckets();
    const bool all = columns != m_drawnColumns;
    double columnWidth = 0.0;
    QVector<double> x, y;
    for (int r = 0; r < m_channels.size(); ++r) {
        const ChannelInfo &c = m_channels[r];
        Tracked &ch = m_tracked[c.key];
        if (!ch.dirty && !all)
            continue;
        ch.dirty = false;
        const double width = ch.envelope.points(x, y, columns);
        if (x.isEmpty())
            continue;
        columnWidth = std::max(columnWidth, width);
        ch.drawnTail_t = x.last() - 0.5 * width;
        ch.envelope.rangeFrom(ch.drawnTail_t, ch.drawnTailMin, ch.drawnTailMax);
        if (QwtPlotCurve *curve = m_plot->curve(c.key)) {
            curve->setSamples(x, y);
        } else {
            curve = m_plot->addCurve(c.key, x, y, !ch.temperature, TimeSeriesPlot::CurveStyle::Envelope);
            QTableWidgetItem *name = m_table->item(r, ColChannel);
            curve->setVisible(name->checkState() == Qt::Checked);
            m_filling = true;
            name->setForeground(curve->pen().color());
            m_filling = false;
        }
    }
    m_drawnColumns = columns;
    m_drawnAt_s = now_s;
    if (columnWidth > 0.0)
        m_drawnColumn_s = columnWidth;
    m_plot->replot();
    ++m_draws;
    timespec cpu1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu1);
    m_drawCost_ns = (cpu1.tv_sec - cpu0.tv_sec) * 1'000'000'000LL + (cpu1.tv_nsec - cpu0.tv_nsec);
    m_sinceDraw.start();
}

bool LiveRecordingView::eventFilter(QObject *watched, QEvent *event)
{
    // A wider or narrower canvas: the envelopes again at its new pixel columns (once the
    // resize has settled; a running recording would do it at its next refresh anyway).
    if (watched == m_plot->canvas() && event->type() == QEvent::Resize && !m_channels.isEmpty())
        QTimer::singleShot(0, this, [this] {
            if (m_plot->decimationBuckets() != m_drawnColumns)
                drawCurves(m_drawnAt_s);
        });
    return QWidget::eventFilter(watched, event);
}

void LiveRecordingView::showAlarms()
{
    const QStringList active = m_monitor.activeAlarms();
    m_alarm->setText(active.join(QLatin1Char('\n')));
    m_alarm->setVisible(!active.isEmpty());
}

QString LiveRecordingView::alarmText() const
{
    return m_alarm->isHidden() ? QString() : m_alarm->text();
}

bool LiveRecordingView::alarmVisible() const
{
    return !m_alarm->isHidden();
}

bool LiveRecordingView::requestStop()
{
    if (!m_active || !m_ask(this))
        return false;
    emit stopRequested();
    return true;
}

} // namespace driftlab

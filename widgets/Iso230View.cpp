#include "Iso230View.h"

#include "Iso230Report.h"
#include "SessionIso230.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "UnitLabels.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QPushButton>
#include <QScrollBar>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

// As the iso230 command and the report write it (UnitLabels::clock: whole seconds, floored;
// this view rounded, so a run could read one second later here).
QString hms(double s)
{
    return std::isfinite(s) ? UnitLabels::clock(s) : QStringLiteral("-");
}

// A cell with the value's exact double behind its rounded text ("-" for NaN: not given by the data).
QTableWidgetItem *valueItem(double v, int decimals = 2)
{
    auto *item = new QTableWidgetItem(std::isfinite(v) ? QString::number(v, 'f', decimals) : QStringLiteral("-"));
    item->setData(Qt::UserRole, std::isfinite(v) ? QVariant(v) : QVariant());
    item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    item->setFlags(item->flags() & ~Qt::ItemIsEditable);
    return item;
}

QTableWidgetItem *textItem(const QString &text)
{
    auto *item = new QTableWidgetItem(text);
    item->setFlags(item->flags() & ~Qt::ItemIsEditable);
    return item;
}

QString direction(int d)
{
    return d > 0 ? QStringLiteral("↑ +") : d < 0 ? QStringLiteral("↓ −") : QStringLiteral("one");
}

} // namespace

Iso230View::Iso230View(QWidget *parent)
    : QWidget(parent),
      m_heading(new QLabel(this)),
      m_test(new QComboBox(this)),
      m_temperature(new QComboBox(this)),
      m_tabs(new QTabWidget(this)),
      m_axis(new QTableWidget(AxisRows, 3, this)),
      m_targets(new QTableWidget(0, TargetColumns, this)),
      m_positioning(new TimeSeriesPlot(this)),
      m_drift(new TimeSeriesPlot(this)),
      m_driftSummary(new QLabel(this)),
      m_storeButton(new QPushButton(tr("Store for the report"), this))
{
    setObjectName(QStringLiteral("Iso230View"));
    m_heading->setWordWrap(true);
    m_heading->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_test->setObjectName(QStringLiteral("Iso230Test"));
    m_test->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_test->setMinimumContentsLength(28); // "run 12 at 10:02:22 (reference)"
    m_temperature->setObjectName(QStringLiteral("Iso230Temperature"));
    m_temperature->setToolTip(tr("Temperature channel the drift is regressed on (µm/K)"));
    auto *controls = new QHBoxLayout;
    controls->addWidget(new QLabel(tr("Test"), this));
    controls->addWidget(m_test);
    controls->addSpacing(12);
    controls->addWidget(new QLabel(tr("Drift against"), this));
    controls->addWidget(m_temperature);
    controls->addStretch();
    // The button goes beside the (wrapping) heading, not after the two combo boxes: that row
    // would then be wider than the central area beside the docks at 1366 x 768.
    m_storeButton->setObjectName(QStringLiteral("Iso230Store"));
    m_storeButton->setToolTip(tr("Store this evaluation with the session: the test report shows it (as `driftlab-cli iso230` stores it)"));
    auto *headingRow = new QHBoxLayout;
    headingRow->addWidget(m_heading, 1);
    headingRow->addWidget(m_storeButton, 0, Qt::AlignTop);

    // ISO 230-2: the axis values, the table per target and direction, and the plot.
    m_axis->setObjectName(QStringLiteral("Iso230Axis"));
    m_axis->setHorizontalHeaderLabels({tr("↑ (µm)"), tr("↓ (µm)"), tr("both (µm)")});
    m_axis->setVerticalHeaderLabels({tr("A accuracy"), tr("E systematic"), tr("R repeatability"), tr("B reversal"),
                                     tr("B̄ mean reversal"), tr("M mean deviation range")});
    m_axis->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
    m_axis->setSizeAdjustPolicy(QAbstractScrollArea::AdjustToContents);
    m_axis->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    m_targets->setObjectName(QStringLiteral("Iso230Targets"));
    m_targets->setHorizontalHeaderLabels({tr("target (mm)"), tr("direction"), tr("n"), tr("x̄ (µm)"), tr("s (µm)"),
                                          tr("x̄ − 2s"), tr("x̄ + 2s"), tr("R (µm)"), tr("B (µm)")});
    m_targets->verticalHeader()->hide();
    m_targets->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    m_targets->setToolTip(tr("Per target: mean deviation x̄ and standard uncertainty s of the approaches in each direction, "
                             "the x̄ ± 2s band, repeatability R (4s per direction; max(2s↑ + 2s↓ + |B|, R↑, R↓) for both) "
                             "and reversal B = x̄↑ − x̄↓ (ISO 230-2, docs/iso230.md)"));
    auto *tables = new QWidget(this);
    auto *tablesLayout = new QVBoxLayout(tables);
    tablesLayout->setContentsMargins(0, 0, 0, 0);
    tablesLayout->addWidget(m_axis);
    tablesLayout->addWidget(m_targets, 1);
    m_positioning->setTimeAxis(false);
    m_positioning->setAxisTitle(QwtPlot::xBottom, tr("target position (mm)"));
    m_positioning->setAxisTitles(tr("positional deviation (µm)"), QString());
    m_positioning->enableAxis(QwtPlot::yRight, false);
    m_positioning->setTitle(tr("ISO 230-2: x̄ and x̄ ± 2s"));
    auto *positioning = m_split = new QSplitter(Qt::Horizontal, this);
    positioning->addWidget(tables);
    positioning->addWidget(m_positioning);
    positioning->setChildrenCollapsible(false);
    positioning->setStretchFactor(0, 1);
    positioning->setStretchFactor(1, 1);

    // ISO 230-3: drift of each target from the reference test against time.
    m_drift->setAxisTitles(tr("drift from the reference test (µm)"), QString());
    m_drift->enableAxis(QwtPlot::yRight, false);
    m_drift->setTitle(tr("ISO 230-3: thermal drift per target"));
    m_driftSummary->setWordWrap(true);
    m_driftSummary->setTextInteractionFlags(Qt::TextSelectableByMouse);
    auto *drift = new QWidget(this);
    auto *driftLayout = new QVBoxLayout(drift);
    driftLayout->setContentsMargins(0, 0, 0, 0);
    driftLayout->addWidget(m_driftSummary);
    driftLayout->addWidget(m_drift, 1);

    m_tabs->addTab(positioning, tr("Positioning (ISO 230-2)"));
    m_tabs->addTab(drift, tr("Drift (ISO 230-3)"));
    auto *layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    layout->addLayout(headingRow);
    layout->addLayout(controls);
    layout->addWidget(m_tabs, 1);

    connect(m_test, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int i) {
        if (!m_updating && i >= 0)
            showTest(i);
    });
    connect(m_temperature, QOverload<int>::of(&QComboBox::activated), this,
            [this](int i) { setTemperatureChannel(m_temperature->itemData(i).toString()); });
    connect(m_storeButton, &QPushButton::clicked, this, [this] {
        if (!storeResult())
            m_heading->setText(m_heading->text() + QStringLiteral("<br>") + m_lastError.toHtmlEscaped());
    });
    clear();
}

Iso230View::~Iso230View()
{
    m_job.cancel();
}

QString Iso230View::heading() const
{
    return m_heading->text();
}

void Iso230View::clear()
{
    m_report.reset();
    m_store = nullptr;
    m_session = 0;
    m_request = Iso230Request();
    m_updating = true;
    m_test->clear();
    m_temperature->clear();
    m_updating = false;
    m_test->setEnabled(false);
    m_temperature->setEnabled(false);
    m_storeButton->setEnabled(false);
    m_heading->setText(tr("No session: ISO 230 evaluates the interferometer runs of the selected session."));
    m_targets->setRowCount(0);
    for (int r = 0; r < AxisRows; ++r)
        for (int c = 0; c < 3; ++c)
            m_axis->setItem(r, c, valueItem(NAN));
    m_positioning->clearCurves();
    m_drift->clearCurves();
    m_driftSummary->clear();
}

bool Iso230View::setSession(const SessionStore *store, qint64 sessionId)
{
    const QString temperature = sessionId == m_session ? m_temperature->currentData().toString() : QString();
    clear();
    if (!store || sessionId == 0)
        return false;
    m_store = store;
    m_session = sessionId;
    m_updating = true;
    m_temperature->addItem(tr("no temperature"), QString());
    for (const ChannelInfo &c : store->channels(sessionId))
        if (c.kind == QLatin1String("temperature"))
            m_temperature->addItem(c.location.isEmpty() ? c.key : QStringLiteral("%1 (%2)").arg(c.key, c.location), c.key);
    m_temperature->setCurrentIndex(std::max(0, m_temperature->findData(temperature)));
    m_updating = false;
    return setTemperatureChannel(m_temperature->currentData().toString());
}

bool Iso230View::setTemperatureChannel(const QString &key)
{
    if (!m_store || m_session == 0)
        return false;
    Iso230Request request;
    request.session = m_session;
    request.temperatureChannel = key;
    std::optional<Iso230Report> report;
    try {
        report = SessionIso230(*m_store, request).run();
    } catch (const std::invalid_argument &e) {
        showFailure(QString::fromUtf8(e.what()));
        return false;
    }
    m_request = request;
    m_updating = true;
    m_temperature->setCurrentIndex(std::max(0, m_temperature->findData(key)));
    m_temperature->setEnabled(m_temperature->count() > 1);
    m_updating = false;
    display(*report);
    m_storeButton->setEnabled(!m_job.running());
    return true;
}

void Iso230View::showFailure(const QString &why)
{
    m_report.reset();
    m_heading->setText(tr("#%1  %2: %3").arg(m_session).arg(m_store ? m_store->session(m_session).name : QString(), why));
    m_test->setEnabled(false);
    m_temperature->setEnabled(false);
    m_storeButton->setEnabled(false);
    m_positioning->clearCurves();
    m_drift->clearCurves();
}

void Iso230View::showReport(const Iso230Report &report)
{
    clear();
    display(report);
}

void Iso230View::display(const Iso230Report &report)
{
    m_report = std::make_unique<Iso230Report>(report);
    m_updating = true;
    m_test->clear();
    const int reference = m_report->referenceTest();
    const std::vector<Iso230Test> &tests = m_report->tests();
    for (std::size_t i = 0; i < tests.size(); ++i) {
        const Iso230Test &t = tests[i];
        QString runs = QString::number(t.runs.front());
        if (t.runs.size() > 1)
            runs += QStringLiteral("–%1").arg(t.runs.back());
        m_test->addItem(tr("run %1 at %2%3").arg(runs, hms(t.time_s), static_cast<int>(i) == reference ? tr(" (reference)") : QString()));
    }
    m_test->setEnabled(tests.size() > 1);
    m_test->setCurrentIndex(reference);
    m_updating = false;
    QString text = tr("<b>#%1  %2</b>: %n ISO 230-2 test(s) of the interferometer runs", nullptr, static_cast<int>(tests.size()))
                       .arg(m_report->request().session)
                       .arg(m_report->sessionName().toHtmlEscaped());
    for (const QString &n : m_report->leftOut())
        text += QStringLiteral("<br>") + tr("left out: %1").arg(n.toHtmlEscaped());
    m_heading->setText(text);
    showTest(reference);
    fillDriftPlot();
}

bool Iso230View::storeResult()
{
    m_lastError.clear();
    if (m_job.running())
        m_lastError = tr("an ISO 230 evaluation is being stored");
    else if (!m_store || !m_report || m_request.session == 0)
        m_lastError = tr("no evaluated session to store");
    else {
        try {
            SessionIso230::checkWritable(*m_store);
        } catch (const std::invalid_argument &e) {
            m_lastError = QString::fromUtf8(e.what());
        }
    }
    if (!m_lastError.isEmpty())
        return false;
    m_storeButton->setEnabled(false);
    m_job.start([this, request = m_request, path = m_store->path()] {
        QString error;
        try {
            SessionStore store(path); // this thread's own connection
            const std::optional<Iso230Report> report =
                SessionIso230(store, request).run([this](double, const QString &) { return !m_job.cancelled(); });
            if (report)
                SessionIso230::store(store, *report);
            else
                error = tr("Cancelled: nothing was stored");
        } catch (const std::exception &e) {
            error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(this, [this, error] { finishStore(error.isEmpty(), error); }, Qt::QueuedConnection);
    });
    return true;
}

void Iso230View::cancel()
{
    m_job.cancel();
}

void Iso230View::finishStore(bool ok, const QString &error)
{
    m_job.finish();
    m_lastError = error;
    m_storeButton->setEnabled(m_report && m_request.session != 0);
    emit finished(ok);
}

void Iso230View::showTest(int index)
{
    if (!m_report || index < 0 || index >= static_cast<int>(m_report->tests().size()))
        return;
    if (m_test->currentIndex() != index) {
        m_updating = true;
        m_test->setCurrentIndex(index);
        m_updating = false;
    }
    fillTables(index);
    fillPositioningPlot(index);
    fitTables();
}

void Iso230View::fillTables(int index)
{
    const Iso230Test &t = m_report->tests()[static_cast<std::size_t>(index)];
    const Iso230Axis &a = t.axis;
    const double rows[AxisRows][3] = {{a.accuracyUp_um, a.accuracyDown_um, a.accuracy_um},
                                      {a.systematicUp_um, a.systematicDown_um, a.systematic_um},
                                      {a.repeatUp_um, a.repeatDown_um, a.repeat_um},
                                      {NAN, NAN, a.reversal_um},
                                      {NAN, NAN, a.meanReversal_um},
                                      {NAN, NAN, a.meanRange_um}};
    for (int r = 0; r < AxisRows; ++r)
        for (int c = 0; c < 3; ++c)
            m_axis->setItem(r, c, valueItem(rows[r][c]));
    m_axis->setToolTip(t.notes.empty() ? QString() : QString::fromStdString(t.notes.front()));

    m_targets->setRowCount(0);
    const int perTarget = t.bidirectional ? 3 : 1;
    m_targets->setRowCount(static_cast<int>(t.targets.size()) * perTarget);
    int row = 0;
    const auto put = [this, &row](double position, const QString &dir, int n, double mean, double s, double repeat,
                                  double reversal) {
        m_targets->setItem(row, Position, valueItem(position, 1));
        m_targets->setItem(row, Direction, textItem(dir));
        auto *count = valueItem(n, 0);
        m_targets->setItem(row, Approaches, count);
        m_targets->setItem(row, Mean, valueItem(mean));
        m_targets->setItem(row, Sigma, valueItem(s));
        m_targets->setItem(row, LowBand, valueItem(mean - 2.0 * s));
        m_targets->setItem(row, HighBand, valueItem(mean + 2.0 * s));
        m_targets->setItem(row, Repeatability, valueItem(repeat));
        m_targets->setItem(row, Reversal, valueItem(reversal));
        ++row;
    };
    for (const Iso230Target &g : t.targets) {
        if (t.bidirectional) {
            put(g.position_mm, direction(1), g.approachesUp, g.meanUp_um, g.sUp_um, g.repeatUp_um, NAN);
            put(g.position_mm, direction(-1), g.approachesDown, g.meanDown_um, g.sDown_um, g.repeatDown_um, NAN);
            put(g.position_mm, tr("both"), g.approachesUp + g.approachesDown, g.mean_um, NAN, g.repeat_um, g.reversal_um);
        } else if (g.approachesDown > 0) {
            put(g.position_mm, direction(-1), g.approachesDown, g.meanDown_um, g.sDown_um, g.repeatDown_um, NAN);
        } else {
            put(g.position_mm, direction(t.directionRecorded ? 1 : 0), g.approachesUp, g.meanUp_um, g.sUp_um, g.repeatUp_um, NAN);
        }
    }
}

void Iso230View::fitTables()
{
    // The tables get the width their columns need and the plot the rest, side by side when
    // both fit (the plot at least 260 px); otherwise the plot goes below the tables, so the
    // tables never scroll sideways (a laptop screen with the docks open). The user can still
    // move the splitter.
    int need = 2 * m_targets->frameWidth() + m_targets->verticalScrollBar()->sizeHint().width() + 6;
    for (int c = 0; c < TargetColumns; ++c)
        need += m_targets->columnWidth(c);
    const int total = m_split->width();
    if (total <= 0)
        return;
    if (total >= need + 260) {
        m_split->setOrientation(Qt::Horizontal);
        m_split->setSizes({need, total - need});
    } else {
        m_split->setOrientation(Qt::Vertical);
        const int height = m_split->height();
        m_split->setSizes({height / 2, height - height / 2});
    }
}

void Iso230View::resizeEvent(QResizeEvent *event)
{
    QWidget::resizeEvent(event);
    fitTables();
}

void Iso230View::fillPositioningPlot(int index)
{
    const Iso230Test &t = m_report->tests()[static_cast<std::size_t>(index)];
    m_positioning->clearCurves();
    for (int dir : {1, -1}) {
        QVector<double> x, mean, low, high;
        for (const Iso230Target &g : t.targets) {
            const double m = dir > 0 ? g.meanUp_um : g.meanDown_um;
            const double s = dir > 0 ? g.sUp_um : g.sDown_um;
            if (!std::isfinite(m))
                continue;
            x << g.position_mm;
            mean << m;
            low << (std::isfinite(s) ? m - 2.0 * s : m);
            high << (std::isfinite(s) ? m + 2.0 * s : m);
        }
        if (x.isEmpty())
            continue;
        const QString name = t.directionRecorded ? (dir > 0 ? tr("x̄↑") : tr("x̄↓")) : tr("x̄");
        QwtPlotCurve *c = m_positioning->addCurve(name, x, mean, false);
        c->setSymbol(new QwtSymbol(dir > 0 ? QwtSymbol::Triangle : QwtSymbol::DTriangle, QBrush(c->pen().color()),
                                   QPen(c->pen().color()), QSize(7, 7)));
        for (const auto &band : {std::make_pair(tr("%1 − 2s").arg(name), low), std::make_pair(tr("%1 + 2s").arg(name), high)}) {
            QwtPlotCurve *b = m_positioning->addCurve(band.first, x, band.second, false);
            QPen pen = c->pen();
            pen.setStyle(Qt::DashLine);
            pen.setWidthF(1.0);
            b->setPen(pen);
        }
    }
    m_positioning->zoomToData();
}

void Iso230View::fillDriftPlot()
{
    m_drift->clearCurves();
    const Iso230DriftSummary &d = m_report->drift();
    // One curve per target in the direction that holds the largest drift (both directions
    // of every target would be 2 x 12 curves; the table of `iso230 --json` has them all).
    const int shown = d.maxDriftDirection;
    for (const Iso230DriftSeries &s : d.series) {
        if (s.direction != shown)
            continue;
        QVector<double> t, v;
        for (const Iso230DriftPoint &p : s.points) {
            t << p.time_s;
            v << p.drift_um;
        }
        m_drift->addCurve(tr("%1 mm").arg(s.position_mm, 0, 'f', 0), t, v, false)
            ->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(Qt::white), QPen(Qt::darkGray), QSize(5, 5)));
    }
    m_drift->zoomToData();
    QString summary = tr("Reference: run %1. Largest drift %2 µm at %3 mm%4 after %5 (run %6).")
                          .arg(d.referenceRun)
                          .arg(d.maxDrift_um, 0, 'f', 2)
                          .arg(d.maxDriftPosition_mm, 0, 'f', 1)
                          .arg(shown ? QStringLiteral(" ") + direction(shown) : QString())
                          .arg(hms(d.maxDriftTime_s))
                          .arg(d.maxDriftRun);
    if (shown)
        summary += tr(" Curves: direction %1.").arg(direction(shown));
    if (d.withTemperature) {
        for (const Iso230DriftSeries &s : d.series)
            if (s.position_mm == d.maxDriftPosition_mm && s.direction == d.maxDriftDirection && std::isfinite(s.slope_um_per_K))
                summary += tr(" Against %1 (range %2 K): %3 µm/K there, r = %4.")
                               .arg(m_temperature->currentData().toString())
                               .arg(d.temperatureRange_K, 0, 'f', 2)
                               .arg(s.slope_um_per_K, 0, 'f', 2)
                               .arg(s.correlation, 0, 'f', 3);
    }
    m_driftSummary->setText(summary);
}

} // namespace driftlab

#include "CompensationPanel.h"

#include "CompensationLoop.h"
#include "ExportableModelJson.h"
#include "SessionOffsetSource.h"
#include "SessionStore.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QTimer>
#include <QVBoxLayout>

#include <cmath>
#include <atomic>

namespace driftlab {

struct CompensationPanel::Progress {
    std::atomic<double> time_s{std::nan("")};
    std::atomic<double> error_um{std::nan("")};
};

CompensationPanel::CompensationPanel(QWidget *parent)
    : QWidget(parent),
      m_model(new QLineEdit(this)),
      m_endpoint(new QLineEdit(QStringLiteral("127.0.0.1:502"), this)),
      m_map(new QComboBox(this)),
      m_axis(new QComboBox(this)),
      m_maxOffset(new QDoubleSpinBox(this)),
      m_maxRate(new QDoubleSpinBox(this)),
      m_rate(new QDoubleSpinBox(this)),
      m_session(new QLabel(tr("no session selected"), this)),
      m_status(new QLabel(tr("stopped"), this)),
      m_offsets(new QLabel(this)),
      m_start(new QPushButton(tr("Start"), this)),
      m_stop(new QPushButton(tr("Stop"), this)),
      m_enable(new QCheckBox(tr("Write to the controller"), this)),
      m_log(new QPlainTextEdit(this)),
      m_timer(new QTimer(this))
{
    m_model->setPlaceholderText(tr("MODEL.json (fit --json, fit --model ... --out, or the Analysis dock)"));
    auto *browse = new QPushButton(tr("Browse..."), this);
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString f = QFileDialog::getOpenFileName(this, tr("Fitted model"), QString(), tr("Model (*.json)"));
        if (!f.isEmpty())
            m_model->setText(f);
    });
    auto *modelRow = new QHBoxLayout;
    modelRow->addWidget(m_model, 1);
    modelRow->addWidget(browse);
    m_map->setEditable(true);
    m_map->addItems(OffsetRegisterMap::presetNames());
    m_map->setToolTip(tr("A preset (m80: R5700/R5701 X, R5702/R5703 Y, R5704/R5705 Z, 1 µm steps) or a map file"));
    m_axis->addItems({QStringLiteral("X"), QStringLiteral("Y"), QStringLiteral("Z")});
    m_maxOffset->setRange(0.1, 1000.0);
    m_maxOffset->setValue(50.0);
    m_maxOffset->setSuffix(QStringLiteral(" µm"));
    m_maxRate->setRange(0.01, 1000.0);
    m_maxRate->setValue(5.0);
    m_maxRate->setSuffix(QStringLiteral(" µm/s"));
    m_rate->setRange(0.1, 100.0);
    m_rate->setValue(10.0);
    m_rate->setSuffix(QStringLiteral(" Hz"));
    m_log->setReadOnly(true);
    m_log->setMaximumBlockCount(5000);
    m_log->setPlaceholderText(tr("Writes and connection events appear here."));
    m_status->setWordWrap(true);
    m_session->setWordWrap(true);

    auto *form = new QFormLayout;
    form->addRow(tr("Model"), modelRow);
    form->addRow(tr("Session"), m_session);
    form->addRow(tr("Controller"), m_endpoint);
    form->addRow(tr("Register map"), m_map);
    form->addRow(tr("Axis"), m_axis);
    form->addRow(tr("Maximum offset"), m_maxOffset);
    form->addRow(tr("Maximum rate"), m_maxRate);
    form->addRow(tr("Loop rate"), m_rate);
    auto *buttons = new QHBoxLayout;
    buttons->addWidget(m_start);
    buttons->addWidget(m_stop);
    buttons->addWidget(m_enable);
    buttons->addStretch(1);
    auto *layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addLayout(buttons);
    layout->addWidget(m_status);
    layout->addWidget(m_offsets);
    layout->addWidget(m_log, 1);

    connect(m_start, &QPushButton::clicked, this, [this] {
        if (!start())
            QMessageBox::warning(this, tr("Compensation"), m_lastError);
    });
    connect(m_stop, &QPushButton::clicked, this, &CompensationPanel::stop);
    connect(m_enable, &QCheckBox::toggled, this, &CompensationPanel::onEnableToggled);
    m_timer->setInterval(200);
    connect(m_timer, &QTimer::timeout, this, &CompensationPanel::onTick);
    updateButtons();
}

CompensationPanel::~CompensationPanel()
{
    m_loop.reset(); // joins the loop's thread
}

void CompensationPanel::setSession(const QString &databasePath, qint64 sessionId)
{
    m_dbPath = databasePath;
    m_sessionId = sessionId;
    m_session->setText(sessionId > 0 ? tr("session %1 of %2").arg(sessionId).arg(QFileInfo(databasePath).fileName()) : tr("no session selected"));
    updateButtons();
}

void CompensationPanel::setModelPath(const QString &path)
{
    m_model->setText(path);
}

void CompensationPanel::setEndpoint(const QString &hostPort)
{
    m_endpoint->setText(hostPort);
}

void CompensationPanel::setMap(const QString &presetOrFile)
{
    m_map->setCurrentText(presetOrFile);
}

void CompensationPanel::setLimits(double maxOffset_um, double maxRate_um_s)
{
    m_maxOffset->setValue(maxOffset_um);
    m_maxRate->setValue(maxRate_um_s);
}

bool CompensationPanel::start()
{
    if (m_loop)
        return true;
    m_lastError.clear();
    try {
        if (m_sessionId <= 0)
            throw std::invalid_argument(tr("Select the session to follow in the Sessions list first.").toStdString());
        CompensationLoop::Options o;
        if (!o.setEndpoint(m_endpoint->text()))
            throw std::invalid_argument(tr("Controller: expected HOST:PORT, got '%1'").arg(m_endpoint->text()).toStdString());
        const QString map = m_map->currentText().trimmed();
        o.map = OffsetRegisterMap::presetNames().contains(map) ? OffsetRegisterMap::fromPreset(map) : OffsetRegisterMap::fromFile(map);
        m_axisIndex = o.map.axisIndex(m_axis->currentText());
        if (m_axisIndex < 0)
            throw std::invalid_argument(tr("Register map: no axis '%1'").arg(m_axis->currentText()).toStdString());
        o.limits = {m_maxOffset->value(), m_maxRate->value()};
        o.rate_Hz = m_rate->value();
        o.enabled = false;
        const ExportableModel model = ExportableModelJson::read(m_model->text().trimmed());
        auto source = std::make_shared<SessionOffsetSource>(m_dbPath, m_sessionId, model);
        SessionStore(m_dbPath).session(m_sessionId);
        auto progress = std::make_shared<Progress>();
        const OffsetRegisterMap registers = o.map;
        const QString axis = o.map.axes[m_axisIndex].name;
        m_loop = std::make_unique<CompensationLoop>(o, [source, progress, registers, axis](double) {
            QVector<double> offsets(registers.axes.size(), std::nan(""));
            try {
                const double here = source->update();
                offsets = registers.requests(axis, here, [&](double x) { return source->offsetAt(x); });
                progress->time_s = source->modelTime_s() > -1e299 ? source->modelTime_s() : std::nan("");
                progress->error_um = source->error_um();
            } catch (const std::exception &) {
                // a channel not recorded yet: hold (the status shows the model time not moving)
            }
            return offsets;
        });
        m_progress = progress;
        m_axisNames.clear();
        for (const OffsetRegisterMap::Axis &a : o.map.axes)
            m_axisNames << a.label();
    } catch (const std::exception &e) {
        m_lastError = QString::fromUtf8(e.what());
        m_status->setText(tr("<span style='color:#b00020'>Cannot start: %1</span>").arg(m_lastError.toHtmlEscaped()));
        return false;
    }
    m_log->clear();
    m_shown = 0;
    {
        const QSignalBlocker block(m_enable);
        m_enable->setChecked(false);
    }
    m_loop->start();
    m_timer->start();
    updateButtons();
    emit started();
    return true;
}

void CompensationPanel::stop()
{
    if (!m_loop)
        return;
    m_timer->stop();
    m_loop->stop();
    onTick();
    m_loop.reset();
    {
        const QSignalBlocker block(m_enable);
        m_enable->setChecked(false);
    }
    m_status->setText(tr("stopped; the controller keeps the last offsets written"));
    updateButtons();
    emit stopped();
}

void CompensationPanel::setWritingEnabled(bool enabled)
{
    {
        const QSignalBlocker block(m_enable);
        m_enable->setChecked(enabled);
    }
    if (m_loop)
        m_loop->setEnabled(enabled);
}

void CompensationPanel::onEnableToggled(bool on)
{
    if (on && m_loop &&
        QMessageBox::question(this, tr("Compensation"),
                              tr("Write thermal offsets to the controller at %1? The machine's axis will move by them.")
                                  .arg(m_endpoint->text())) != QMessageBox::Yes) {
        const QSignalBlocker block(m_enable);
        m_enable->setChecked(false);
        return;
    }
    setWritingEnabled(on);
}

void CompensationPanel::onTick()
{
    if (!m_loop)
        return;
    const CompensationLoop::Status s = m_loop->status();
    const QVector<CompensationLoop::Entry> log = m_loop->log();
    for (; m_shown < log.size(); ++m_shown)
        m_log->appendPlainText(QStringLiteral("%1 s  %2")
                                   .arg(log[m_shown].t_s, 8, 'f', 2)
                                   .arg(log[m_shown].what));
    QString state = s.connected ? tr("connected") : tr("<span style='color:#b00020'>%1</span>").arg(s.message.toHtmlEscaped());
    state += s.enabled ? tr(", writing") : tr(", writing off");
    if (s.clamped)
        state += tr(", held at the maximum offset");
    if (s.rateLimited)
        state += tr(", following at the rate limit");
    if (m_progress && !std::isnan(m_progress->time_s.load()))
        state += tr("; model at %1 s of the session, E = %2 µm").arg(m_progress->time_s.load(), 0, 'f', 1).arg(m_progress->error_um.load(), 0, 'f', 2);
    state += tr("; period %1 ms (jitter %2 ms), %3 writes, %4 reconnects")
                 .arg(s.meanPeriod_s * 1e3, 0, 'f', 1)
                 .arg(s.periodJitter_s * 1e3, 0, 'f', 2)
                 .arg(s.writes)
                 .arg(s.reconnects);
    m_status->setText(state);
    QStringList axes;
    for (int i = 0; i < s.requested_um.size(); ++i) {
        const double r = s.requested_um[i], w = s.written_um.value(i);
        if (std::isnan(r) && std::isnan(w))
            continue;
        axes << tr("%1: requested %2 µm, controller holds %3 µm")
                    .arg(m_axisNames.value(i))
                    .arg(std::isnan(r) ? QStringLiteral("-") : QString::number(r, 'f', 2))
                    .arg(std::isnan(w) ? QStringLiteral("-") : QString::number(w, 'f', 0));
    }
    m_offsets->setText(axes.join(QLatin1Char('\n')));
}

void CompensationPanel::updateButtons()
{
    const bool on = static_cast<bool>(m_loop);
    m_start->setEnabled(!on);
    m_stop->setEnabled(on);
    m_enable->setEnabled(on);
    for (QWidget *w : std::initializer_list<QWidget *>{m_model, m_endpoint, m_map, m_axis, m_maxOffset, m_maxRate, m_rate})
        w->setEnabled(!on);
}

QString CompensationPanel::statusText() const
{
    return m_status->text();
}

QString CompensationPanel::offsetsText() const
{
    return m_offsets->text();
}

QString CompensationPanel::logText() const
{
    return m_log->toPlainText();
}

} // namespace driftlab

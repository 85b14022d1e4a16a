#include "AcquisitionPanel.h"

#include "AcquisitionEngine.h"
#include "ElapsedTimeBox.h"
#include "LiveRecordingView.h"
#include "RigConfigLoader.h"
#include "RigDeviceSet.h"
#include "RigSetupDialog.h"
#include "MeasurementRunDialog.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"
#include "UnitLabels.h"

#include <QComboBox>
#include <QDir>
#include <QFileInfo>
#include <QDateTime>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QInputDialog>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>

#include <qwt_plot_curve.h>

#include <cmath>

namespace driftlab {

namespace {
constexpr int kTick_ms = 40;        // status refresh: at most 25 per second
constexpr int kPlotPeriod_ms = 100; // data re-read and plot redraw
const char *kBrowse = "Rig file...";

} // namespace

AcquisitionPanel::AcquisitionPanel(QWidget *parent) : QWidget(parent)
{
    m_rig = new QComboBox(this);
    m_rig->addItems(RigConfigLoader::presetNames());
    m_rig->addItem(QString::fromLatin1(kBrowse));
    m_db = new QLabel(this);
    m_db->setWordWrap(true);
    m_db->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_name = new QLineEdit(this);
    m_name->setPlaceholderText(tr("automatic: rig and start time"));
    m_operator = new QLineEdit(this);
    m_duration = new ElapsedTimeBox(this); // 0:00:00 shows as "until Stop"
    m_duration->setSpecialValueText(tr("until Stop"));
    m_duration->setToolTip(tr("Simulated duration of the run in h:mm:ss (or 90 min, 2 h); it stops by itself when reached"));
    m_notes = new QPlainTextEdit(this);
    m_notes->setPlaceholderText(tr("what is tested, set-up, anything unusual"));
    m_notes->setMaximumHeight(2 * fontMetrics().lineSpacing() + 12);
    m_message = new QLabel(this);
    m_message->setWordWrap(true);
    m_message->setTextInteractionFlags(Qt::TextSelectableByMouse);
    setDatabasePath(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/driftlab.sqlite"));
    m_speed = new QDoubleSpinBox(this);
    m_speed->setRange(1.0, 100000.0);
    m_speed->setDecimals(0);
    m_speed->setValue(60.0);
    m_speed->setSuffix(QStringLiteral(" x"));
    m_start = new QPushButton(tr("Start"), this);
    m_pause = new QPushButton(tr("Pause"), this);
    m_pause->setCheckable(true);
    m_marker = new QPushButton(tr("Marker..."), this);
    m_stop = new QPushButton(tr("Stop"), this);
    m_setup = new QPushButton(tr("Rig setup..."), this);
    m_run = new QPushButton(tr("Measurement run..."), this);
    m_elapsed = new QLabel(tr("not recording"), this);
    m_devices = new QTableWidget(0, 5, this);
    // Fits the dock at 1366 px without sideways scrolling: short headers (the long names in
    // their tooltips), the device name takes the room left and elides (full name in its
    // tooltip), the state column shows the state alone (its message is the cell's tooltip).
    m_devices->setHorizontalHeaderLabels({tr("Device"), tr("State"), tr("Hz"), tr("Samples"), tr("Gaps")});
    const QStringList headerTips{tr("Device id in the rig file"), tr("Device state; hover a cell for its last message"),
                                 tr("Rate (Hz): samples per second over the last seconds"), tr("Samples recorded"),
                                 tr("Gaps: missed reads")};
    for (int c = 0; c < headerTips.size(); ++c)
        m_devices->horizontalHeaderItem(c)->setToolTip(headerTips[c]);
    m_devices->horizontalHeader()->setStretchLastSection(false);
    m_devices->horizontalHeader()->setMinimumSectionSize(24);
    m_devices->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    m_devices->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
    m_devices->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    m_devices->setTextElideMode(Qt::ElideMiddle);
    m_devices->verticalHeader()->hide();
    m_devices->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_showLive = new QPushButton(tr("Show live view"), this);
    m_showLive->setToolTip(tr("The running recording at full size: channels, limits and alarms, Stop"));
    // The live plot is not in the dock (at 768 px it had to be scrolled to): it is a full view.
    m_live = new LiveRecordingView(this);
    m_live->hide();
    m_devices->setMinimumHeight(72); // five devices scroll inside; the dock itself fits 768 px

    auto *form = new QFormLayout;
    auto *rigRow = new QHBoxLayout; // the rig and, beside it, where its devices are set up
    rigRow->addWidget(m_rig, 1);
    rigRow->addWidget(m_setup);
    form->addRow(tr("Rig"), rigRow);
    form->addRow(tr("Records into"), m_db);
    form->addRow(tr("Name"), m_name);
    form->addRow(tr("Operator"), m_operator);
    form->addRow(tr("Duration"), m_duration);
    form->addRow(tr("Notes"), m_notes);
    form->addRow(tr("Simulation speed"), m_speed);
    // Two rows of two: the dock stays narrow enough for a 1366-pixel screen beside the sessions.
    auto *buttons = new QGridLayout;
    buttons->addWidget(m_start, 0, 0);
    buttons->addWidget(m_pause, 0, 1);
    buttons->addWidget(m_marker, 1, 0);
    buttons->addWidget(m_stop, 1, 1);
    auto *during = new QHBoxLayout; // what a running recording offers, and how far it is
    during->addWidget(m_run);
    during->addWidget(m_showLive);
    during->addStretch();
    during->addWidget(m_elapsed);
    auto *layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addLayout(buttons);
    layout->addLayout(during);
    layout->addWidget(m_message);
    layout->addWidget(m_devices, 1);

    m_timer = new QTimer(this);
    m_timer->setInterval(kTick_ms);
    connect(m_timer, &QTimer::timeout, this, &AcquisitionPanel::onTick);
    connect(m_rig, QOverload<int>::of(&QComboBox::activated), this, [this](int index) {
        if (m_rig->itemText(index) != QLatin1String(kBrowse))
            return;
        const QString f = QFileDialog::getOpenFileName(this, tr("Rig file"), QString(), tr("Rig files (*.json)"));
        if (!f.isEmpty()) {
            m_rig->insertItem(index, f);
            m_rig->setCurrentIndex(index);
        } else {
            m_rig->setCurrentIndex(0);
        }
    });
    connect(m_start, &QPushButton::clicked, this, [this] {
        startRecording(m_rig->currentText(), m_target, m_speed->value());
    });
    connect(m_stop, &QPushButton::clicked, this, &AcquisitionPanel::requestStop);
    connect(m_live, &LiveRecordingView::stopRequested, this, &AcquisitionPanel::stopRecording);
    // An alarm (a limit crossed, a silent sensor) is an event of the session.
    connect(m_live, &LiveRecordingView::alarmRaised, this, &AcquisitionPanel::addMarker);
    // So are the limits in force (at the start and on every change): the session says which applied.
    connect(m_live, &LiveRecordingView::limitsApplied, this, &AcquisitionPanel::addMarker);
    connect(m_showLive, &QPushButton::clicked, this, &AcquisitionPanel::liveViewRequested);
    connect(m_pause, &QPushButton::toggled, this, &AcquisitionPanel::setPaused);
    connect(m_marker, &QPushButton::clicked, this, [this] {
        bool ok = false;
        const QString label = QInputDialog::getText(this, tr("Marker"), tr("Label"), QLineEdit::Normal, QString(), &ok);
        if (ok && !label.isEmpty())
            addMarker(label);
    });
    connect(m_setup, &QPushButton::clicked, this, [this] {
        RigSetupDialog dialog(this);
        if (dialog.exec() == QDialog::Accepted && !dialog.savedPath().isEmpty()) {
            m_rig->insertItem(m_rig->count() - 1, dialog.savedPath());
            m_rig->setCurrentIndex(m_rig->count() - 2);
        }
    });
    connect(m_run, &QPushButton::clicked, this, [this] {
        if (!m_engine)
            return;
        AcquisitionEngine *engine = m_engine.get();
        int firstRun = 0; // entered runs follow the session's stored runs
        for (const InterferometerPoint &p : m_reader->interferometerPoints(m_session))
            firstRun = std::max(firstRun, p.run + 1);
        auto *dialog = new MeasurementRunDialog([engine] { return engine->now_s(); },
                                                [engine](const QVector<InterferometerPoint> &points, const QString &note) {
                                                    engine->addInterferometerPoints(points, note);
                                                },
                                                this, firstRun);
        dialog->setAttribute(Qt::WA_DeleteOnClose);
        connect(this, &AcquisitionPanel::recordingStopped, dialog, &QDialog::reject);
        dialog->show();
    });
    updateButtons();
}

AcquisitionPanel::AcquisitionPanel(Workbench *workbench, QWidget *parent) : AcquisitionPanel(parent)
{
    connect(workbench, &Workbench::storeChanged, this, [this, workbench](SessionStore *store) {
        if (!store)
            return;
        // A central store is for review: recordings keep going to the local database.
        if (!workbench->localPath().isEmpty())
            setDatabasePath(workbench->localPath());
        if (!recording())
            clearView();
    });
    connect(this, &AcquisitionPanel::recordingStarted, workbench,
            [this, workbench](qint64 id) { workbench->recordingChanged(m_dbPath, id); });
    connect(this, &AcquisitionPanel::recordingStopped, workbench,
            [this, workbench](qint64 id) { workbench->recordingChanged(m_dbPath, id); });
    workbench->addGuard(this, [this, workbench](qint64 id) {
        if (id != 0 && recording() && id == m_session && QFileInfo(m_dbPath).absoluteFilePath() == workbench->localPath())
            return tr("Session %1 is being recorded; stop the recording first").arg(id);
        return QString();
    });
}

void AcquisitionPanel::clearView()
{
    m_session = 0;
    m_devices->setRowCount(0);
    if (m_live) {
        m_live->begin(tr("No recording"), QString(), 0.0);
        m_live->finish(tr("not recording"));
    }
    m_message->clear();
    m_elapsed->setText(tr("not recording"));
}

AcquisitionPanel::~AcquisitionPanel()
{
    stopRecording();
}

void AcquisitionPanel::setDatabasePath(const QString &path)
{
    m_target = path;
    m_db->setText(path);
    m_db->setToolTip(tr("Sessions are recorded into the database open in the window (File > New / Open database)"));
}

void AcquisitionPanel::setRunDetails(const QString &name, const QString &operatorName, double duration_s, const QString &notes)
{
    m_name->setText(name);
    m_operator->setText(operatorName);
    m_duration->setValue(duration_s);
    m_notes->setPlainText(notes);
}

bool AcquisitionPanel::startRecording(const QString &rigNameOrPath, const QString &dbPath, double speed)
{
    if (m_engine)
        return false;
    m_message->clear();
    QString liveTitle;
    try {
        // A fresh install has no data folder yet.
        const QString folder = QFileInfo(dbPath).absolutePath();
        if (!QDir().mkpath(folder))
            throw std::runtime_error(tr("cannot create the folder %1 for %2").arg(folder, dbPath).toStdString());
        const RigConfig config = RigConfigLoader::load(rigNameOrPath);
        RigDeviceSet set = RigDeviceSet::build(config, QString());
        set.session.name = (set.realDevices ? tr("Rig '%1', %2") : tr("Simulated rig '%1', %2"))
                               .arg(config.name, QDateTime::currentDateTime().toString(QStringLiteral("yyyy-MM-dd HH:mm")));
        AcquisitionEngine::Options options;
        options.speed = set.realDevices ? 1.0 : speed; // real instruments record in real time
        m_end_s = m_duration->value();
        if (m_end_s > 0)
            options.end_s = m_end_s;
        auto engine = std::make_unique<AcquisitionEngine>(options);
        for (auto &d : set.devices)
            engine->addDevice(std::move(d));
        SessionInfo info = set.session;
        if (!m_name->text().trimmed().isEmpty())
            info.name = m_name->text().trimmed();
        info.operatorName = m_operator->text().trimmed();
        if (!m_notes->toPlainText().trimmed().isEmpty())
            info.notes = m_notes->toPlainText().trimmed() + (info.notes.isEmpty() ? QString() : QStringLiteral("\n") + info.notes);
        m_session = engine->start(dbPath, info);
        liveTitle = tr("#%1  %2").arg(m_session).arg(info.name);
        m_engine = std::move(engine);
        m_dbPath = dbPath;
        m_reader = std::make_unique<SessionStore>(dbPath);
    } catch (const std::exception &e) {
        m_lastError = QString::fromUtf8(e.what());
        m_message->setText(tr("<span style='color:#b00020'>Cannot record: %1</span>").arg(m_lastError.toHtmlEscaped()));
        return false;
    }
    m_devices->setRowCount(m_engine->deviceCount());
    for (int i = 0; i < m_engine->deviceCount(); ++i) {
        auto *name = new QTableWidgetItem(m_engine->device(i).id());
        name->setToolTip(m_engine->device(i).id());
        m_devices->setItem(i, 0, name);
        for (int c = 1; c < 5; ++c)
            m_devices->setItem(i, c, new QTableWidgetItem);
    }
    if (m_live)
        m_live->begin(liveTitle, rigNameOrPath, m_end_s);
    m_plotRefreshes = 0;
    m_lastPlot_ms = 0;
    m_timer->start();
    updateButtons();
    emit recordingStarted(m_session);
    return true;
}

void AcquisitionPanel::stopRecording()
{
    if (!m_engine)
        return;
    m_timer->stop();
    QString failure;
    try {
        m_engine->stop();
    } catch (const std::exception &e) {
        failure = QString::fromUtf8(e.what());
        m_lastError = failure;
    }
    onTick(); // final state of the table
    refreshPlot();
    m_engine.reset();
    m_reader.reset();
    m_pause->setChecked(false);
    updateButtons();
    m_elapsed->setText(tr("stopped"));
    if (m_live)
        m_live->finish(failure.isEmpty() ? tr("Stopped: session %1 recorded").arg(m_session)
                                         : tr("Recording stopped: %1").arg(failure));
    if (failure.isEmpty()) {
        m_message->setStyleSheet(QString());
        m_message->setText(tr("Session %1 recorded into %2").arg(m_session).arg(m_dbPath));
    } else {
        // Disk full and other writer failures: say so; what was committed stays (session incomplete).
        m_message->setStyleSheet(QStringLiteral("color: #b00020;"));
        m_message->setText(tr("Recording stopped: %1. What was stored before is kept: session %2, marked incomplete.")
                               .arg(failure)
                               .arg(m_session));
    }
    emit recordingStopped(m_session);
}

LiveRecordingView *AcquisitionPanel::liveView() const
{
    return m_live;
}

TimeSeriesPlot *AcquisitionPanel::plot() const
{
    return m_live ? m_live->plot() : nullptr;
}

bool AcquisitionPanel::requestStop()
{
    return m_live && m_live->requestStop(); // stopRequested -> stopRecording
}

QString AcquisitionPanel::messageText() const
{
    return m_message->text();
}

void AcquisitionPanel::addMarker(const QString &label)
{
    if (m_engine)
        m_engine->addMarker(label);
}

void AcquisitionPanel::setPaused(bool paused)
{
    if (!m_engine)
        return;
    if (paused)
        m_engine->pause();
    else
        m_engine->resume();
}

double AcquisitionPanel::elapsed_s() const
{
    return m_engine ? m_engine->now_s() : 0.0;
}

int AcquisitionPanel::deviceRowCount() const
{
    return m_devices->rowCount();
}

QString AcquisitionPanel::deviceCell(int row, int column) const
{
    const QTableWidgetItem *item = m_devices->item(row, column);
    return item ? item->text() : QString();
}

void AcquisitionPanel::updateButtons()
{
    const bool rec = static_cast<bool>(m_engine);
    m_start->setEnabled(!rec);
    m_rig->setEnabled(!rec);
    for (QWidget *w : {static_cast<QWidget *>(m_name), static_cast<QWidget *>(m_operator), static_cast<QWidget *>(m_duration),
                       static_cast<QWidget *>(m_notes), static_cast<QWidget *>(m_speed)})
        w->setEnabled(!rec);
    m_pause->setEnabled(rec);
    m_marker->setEnabled(rec);
    m_stop->setEnabled(rec);
    m_setup->setEnabled(!rec);
    m_run->setEnabled(rec);
}

void AcquisitionPanel::onTick()
{
    if (!m_engine)
        return;
    if (m_timer->isActive() && ((m_end_s > 0 && m_engine->now_s() >= m_end_s) || !m_engine->writerError().empty())) {
        stopRecording(); // the run's duration is reached, or the writer failed (stopRecording's own last tick skips this)
        return;
    }
    m_elapsed->setText(tr("%1%2 elapsed%3")
                           .arg(UnitLabels::clock(m_engine->now_s()), m_end_s > 0 ? tr(" of %1").arg(UnitLabels::clock(m_end_s)) : QString(),
                                m_engine->paused() ? tr(" (paused)") : QString()));
    if (m_live)
        m_live->setClock(m_engine->now_s(), m_engine->paused());
    const QVector<DeviceHealth> health = m_engine->health();
    for (int i = 0; i < health.size() && i < m_devices->rowCount(); ++i) {
        const DeviceHealth &h = health[i];
        QTableWidgetItem *state = m_devices->item(i, 1);
        const QString message = h.message.isEmpty() || h.state == DeviceHealth::State::Running ? QString() : h.message;
        state->setText(DeviceHealth::stateName(h.state) + (message.isEmpty() ? QString() : QStringLiteral(" ⚠")));
        state->setToolTip(message.isEmpty() ? DeviceHealth::stateName(h.state) : DeviceHealth::stateName(h.state) + QStringLiteral(": ") + message);
        m_devices->item(i, 2)->setText(QString::number(h.rate_Hz, 'f', 1));
        m_devices->item(i, 3)->setText(QString::number(h.samples));
        m_devices->item(i, 4)->setText(QString::number(h.gaps));
    }
    const qint64 now = QDateTime::currentMSecsSinceEpoch();
    if (now - m_lastPlot_ms >= kPlotPeriod_ms) {
        m_lastPlot_ms = now;
        refreshPlot();
    }
}

void AcquisitionPanel::refreshPlot()
{
    if (!m_reader || m_session <= 0)
        return;
    if (!m_live)
        return;
    try {
        // The last refresh after stop reads to the end of the data.
        m_live->update(*m_reader, m_session, m_engine ? m_engine->now_s() : 1e300);
        ++m_plotRefreshes;
    } catch (const std::exception &) {
        // The writer may hold the database for a moment: try again at the next tick.
    }
}

} // namespace driftlab

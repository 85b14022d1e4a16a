#include "ModelsPanel.h"

#include "ErrorSurfacePlot.h"
#include "ScrewModelFit.h"
#include "Workbench.h"
#include "SessionStore.h"
#include "UnitLabels.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace driftlab {

namespace {
constexpr int kIdRole = Qt::UserRole + 1;
} // namespace

ModelsPanel::ModelsPanel(QWidget *parent)
    : QWidget(parent),
      m_sessions(new QListWidget(this)),
      m_heldOut(new QComboBox(this)),
      m_fit(new QPushButton(tr("Fit seed-000 model"), this)),
      m_cancel(new QPushButton(tr("Cancel"), this)),
      m_progress(new QProgressBar(this)),
      m_status(new QLabel(this)),
      m_parameters(new QTableWidget(0, 5, this)),
      m_show(new QComboBox(this)),
      m_measured(new ErrorSurfacePlot(this)),
      m_predicted(new ErrorSurfacePlot(this)),
      m_residual(new ErrorSurfacePlot(this))
{
    auto *left = new QVBoxLayout();
    left->addWidget(new QLabel(tr("Training sessions"), this));
    left->addWidget(m_sessions, 1);
    left->addWidget(new QLabel(tr("Held-out session"), this));
    left->addWidget(m_heldOut);
    auto *buttons = new QHBoxLayout();
    buttons->addWidget(m_fit);
    buttons->addWidget(m_cancel);
    left->addLayout(buttons);
    left->addWidget(m_progress);
    left->addWidget(m_status);
    m_status->setWordWrap(true);
    m_parameters->setHorizontalHeaderLabels({tr("parameter"), tr("value"), tr("± std. error"), tr("unit"), tr("check")});
    m_parameters->horizontalHeader()->setStretchLastSection(true);
    m_parameters->verticalHeader()->hide();
    left->addWidget(m_parameters, 1);
    left->addWidget(new QLabel(tr("Show recording"), this));
    left->addWidget(m_show);

    m_measured->setTitle(tr("Measured thermal error"));
    m_predicted->setTitle(tr("Predicted thermal error"));
    m_residual->setTitle(tr("Residual (measured − predicted)"));
    for (ErrorSurfacePlot *p : {m_measured, m_predicted, m_residual})
        p->showEmpty(tr("Fit the physical model (Models dock): the maps of each recording appear here."));
    // One row: the panel stays usable in a bottom dock of a 768-pixel-high screen.
    m_results = new QSplitter(Qt::Horizontal, this);
    m_results->setObjectName(QStringLiteral("ModelFitView"));
    m_results->addWidget(m_measured);
    m_results->addWidget(m_predicted);
    m_results->addWidget(m_residual);
    m_results->setChildrenCollapsible(false);
    auto *layout = new QHBoxLayout(this);
    layout->addLayout(left, 1);
    layout->addWidget(m_results, 4);

    m_progress->setRange(0, 1);
    m_progress->setValue(0);
    m_cancel->setEnabled(false);
    connect(m_fit, &QPushButton::clicked, this, &ModelsPanel::onFitClicked);
    connect(m_cancel, &QPushButton::clicked, this, &ModelsPanel::cancel);
    connect(m_show, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &ModelsPanel::showRecording);
}

ModelsPanel::ModelsPanel(Workbench *workbench, QWidget *parent) : ModelsPanel(parent)
{
    connect(workbench, &Workbench::storeChanged, this, [this](SessionStore *store) { setStore(store); });
    connect(workbench, &Workbench::sessionsChanged, this, [this, workbench] {
        if (!running())
            setStore(workbench->store());
    });
    workbench->addGuard(this, [this](qint64) { return running() ? tr("A model fit is running on the open database; cancel it first") : QString(); });
}

ModelsPanel::~ModelsPanel()
{
    m_job.cancel();
    m_job.finish();
}

QWidget *ModelsPanel::resultsView() const
{
    return m_results;
}

void ModelsPanel::setStore(const SessionStore *store)
{
    m_store = store;
    m_sessions->clear();
    m_heldOut->clear();
    m_heldOut->addItem(tr("(none)"), 0);
    if (!store)
        return;
    for (const SessionInfo &s : store->sessions()) {
        auto *item = new QListWidgetItem(QStringLiteral("#%1  %2").arg(s.id).arg(s.name), m_sessions);
        item->setData(kIdRole, s.id);
        item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
        item->setCheckState(Qt::Unchecked);
        m_heldOut->addItem(QStringLiteral("#%1  %2").arg(s.id).arg(s.name), s.id);
    }
}

void ModelsPanel::onFitClicked()
{
    QVector<qint64> training;
    for (int i = 0; i < m_sessions->count(); ++i) {
        if (m_sessions->item(i)->checkState() == Qt::Checked)
            training.push_back(m_sessions->item(i)->data(kIdRole).toLongLong());
    }
    if (!startFit(training, m_heldOut->currentData().toLongLong()))
        m_status->setText(m_lastError);
}

bool ModelsPanel::startFit(const QVector<qint64> &training, qint64 heldOut)
{
    if (running()) {
        m_lastError = tr("A fit is already running");
        return false;
    }
    if (!m_store || training.isEmpty()) {
        m_lastError = tr("Check at least one training session");
        return false;
    }
    if (training.contains(heldOut)) {
        m_lastError = tr("The held-out session must not be a training session");
        return false;
    }
    // Show the choice in the widgets too (when called programmatically).
    for (int i = 0; i < m_sessions->count(); ++i)
        m_sessions->item(i)->setCheckState(training.contains(m_sessions->item(i)->data(kIdRole).toLongLong()) ? Qt::Checked
                                                                                                             : Qt::Unchecked);
    m_heldOut->setCurrentIndex(std::max(0, m_heldOut->findData(heldOut)));
    ScrewFitRequest request;
    request.sessions.assign(training.begin(), training.end());
    request.holdout = heldOut > 0 ? heldOut : 0;
    try {
        ScrewModelFit::check(*m_store, request);
    } catch (const std::exception &e) {
        m_lastError = QString::fromStdString(e.what());
        return false;
    }
    m_recordingNames.clear();
    for (qint64 id : training)
        m_recordingNames << tr("session %1 (training)").arg(id);
    if (request.holdout)
        m_recordingNames << tr("session %1 (held out)").arg(heldOut);
    // Cancel first, and the focus with it: a disabled focused button hands the focus down
    // the chain, and the dock's scroll area followed it away from progress and Cancel.
    m_cancel->setEnabled(true);
    if (m_fit->hasFocus())
        m_cancel->setFocus();
    m_fit->setEnabled(false);
    m_progress->setRange(0, 0); // busy until the first iteration
    m_status->setText(tr("Simulating unit responses and fitting..."));
    const auto progress = [this](int iteration, double cost) {
        QMetaObject::invokeMethod(this, [this, iteration, cost] {
            m_progress->setRange(0, 100);
            m_progress->setValue(std::min(100, iteration));
            m_status->setText(tr("iteration %1, cost %2").arg(iteration).arg(cost, 0, 'g', 4));
        }, Qt::QueuedConnection);
        return !m_job.cancelled();
    };
    m_job.start([this, path = m_store->path(), request, progress] {
        ScrewFitResult fit;
        QString error;
        bool ok = true;
        try {
            SessionStore store(path); // this thread's own connection: reads, and stores the model
            fit = ScrewModelFit(store).run(request, progress);
        } catch (const IdentificationCancelled &) {
            ok = false;
            error = tr("Cancelled: no model was fitted");
        } catch (const std::exception &e) {
            ok = false;
            error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(this, [this, ok, error, fit] {
            if (ok)
                m_fitResult = fit;
            finish(ok, error);
        }, Qt::QueuedConnection);
    });
    return true;
}

void ModelsPanel::cancel()
{
    m_job.cancel();
    m_status->setText(tr("Cancelling..."));
}

void ModelsPanel::finish(bool ok, const QString &error)
{
    m_job.finish();
    m_fit->setEnabled(true);
    m_cancel->setEnabled(false);
    m_progress->setRange(0, 1);
    m_progress->setValue(ok ? 1 : 0);
    m_lastError = error;
    if (!ok) {
        m_status->setText(error);
        emit fitFinished(false);
        return;
    }
    const IdentificationResult &fitted = m_fitResult.identification;
    const FitStatistics &held = m_fitResult.validation;
    const FitStatistics &f = fitted.fit;
    QString text = tr("Fitted in %1 s (%2 iterations%3). Training: interferometer RMS %4 µm (P-V %5 µm), probe RMS %6 µm.")
                       .arg(fitted.wallTime_s, 0, 'f', 2)
                       .arg(fitted.iterations)
                       .arg(fitted.converged ? tr(", converged") : tr(", NOT converged"))
                       .arg(f.interferometerRms_um, 0, 'f', 2)
                       .arg(f.interferometerPeakToValley_um, 0, 'f', 1)
                       .arg(f.elongationRms_um, 0, 'f', 2);
    if (held.interferometerPoints + held.elongationPoints > 0)
        text += tr(" Held out: interferometer RMS %1 µm (P-V %2 µm), probe RMS %3 µm.")
                    .arg(held.interferometerRms_um, 0, 'f', 2)
                    .arg(held.interferometerPeakToValley_um, 0, 'f', 1)
                    .arg(held.elongationRms_um, 0, 'f', 2);
    m_status->setText(text);
    // The flags `fit` prints and stores (ParameterPlausibility, judged by ScrewModelFit).
    const std::vector<PlausibilityFlag> &implausible = m_fitResult.implausible;
    const std::vector<PlausibilityFlag> &poorly = m_fitResult.poorlyIdentified;
    int flagged = 0;
    m_parameters->setRowCount(static_cast<int>(fitted.all.size()));
    for (int r = 0; r < static_cast<int>(fitted.all.size()); ++r) {
        const IdentifiedParameter &p = fitted.all[static_cast<size_t>(r)];
        m_parameters->setItem(r, 0, new QTableWidgetItem(QString::fromStdString(p.name)));
        m_parameters->setItem(r, 1, new QTableWidgetItem(QString::number(p.value, 'g', 5)));
        m_parameters->setItem(r, 2, new QTableWidgetItem(p.fitted ? QString::number(p.standardError, 'g', 3) : tr("fixed")));
        m_parameters->setItem(r, 3, new QTableWidgetItem(UnitLabels::display(QString::fromStdString(p.unit))));
        QStringList checks, messages;
        for (const PlausibilityFlag &f : implausible)
            if (f.parameter == p.name) {
                checks << tr("implausible");
                messages << QString::fromStdString(f.message);
            }
        for (const PlausibilityFlag &f : poorly)
            if (f.parameter == p.name) {
                checks << tr("poorly identified");
                messages << QString::fromStdString(f.message);
            }
        checks.removeDuplicates();
        auto *check = new QTableWidgetItem(checks.isEmpty() ? tr("ok") : checks.join(QStringLiteral(", ")));
        if (!checks.isEmpty()) {
            ++flagged;
            const QColor warn(255, 224, 178);
            for (int c = 0; c < 4; ++c)
                m_parameters->item(r, c)->setBackground(warn);
            check->setBackground(warn);
            const QString tip = messages.join(QLatin1Char('\n'));
            for (int c = 0; c < 4; ++c)
                m_parameters->item(r, c)->setToolTip(tip);
            check->setToolTip(tip);
        }
        m_parameters->setItem(r, 4, check);
    }
    m_parameters->resizeColumnsToContents();
    if (flagged > 0)
        m_status->setText(m_status->text() +
                          tr(" %n parameter(s) flagged (implausible or poorly identified): see the table's check column.",
                             nullptr, flagged));
    if (!m_fitResult.feedNote.isEmpty())
        m_status->setText(m_status->text() + tr(" Note: %1.").arg(m_fitResult.feedNote));
    m_show->blockSignals(true);
    m_show->clear();
    m_show->addItems(m_recordingNames);
    m_show->blockSignals(false);
    showRecording(0);
    emit fitFinished(true);
}

void ModelsPanel::grid(const std::vector<ObservationFit> &points, int recording, int which, std::vector<double> &x,
                       std::vector<double> &y, std::vector<double> &z, double runGap_s)
{
    std::vector<const ObservationFit *> pts;
    for (const ObservationFit &p : points) {
        if (p.recording == recording && !p.elongation)
            pts.push_back(&p);
    }
    std::sort(pts.begin(), pts.end(), [](const ObservationFit *a, const ObservationFit *b) { return a->t_s < b->t_s; });
    x.clear();
    y.clear();
    z.clear();
    std::vector<std::vector<const ObservationFit *>> runs;
    for (const ObservationFit *p : pts) {
        if (runs.empty() || p->t_s - runs.back().back()->t_s > runGap_s)
            runs.emplace_back();
        runs.back().push_back(p);
        x.push_back(p->position_mm);
    }
    std::sort(x.begin(), x.end());
    std::vector<double> targets;
    for (double v : x) {
        if (targets.empty() || v - targets.back() > 0.05)
            targets.push_back(v);
    }
    x = targets;
    z.assign(runs.size() * x.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t r = 0; r < runs.size(); ++r) {
        double tSum = 0.0;
        for (const ObservationFit *p : runs[r]) {
            tSum += p->t_s;
            const auto it = std::lower_bound(x.begin(), x.end(), p->position_mm - 0.05);
            if (it == x.end())
                continue;
            const double v = which == 0 ? p->measured_um : (which == 1 ? p->predicted_um : p->measured_um - p->predicted_um);
            z[r * x.size() + static_cast<std::size_t>(it - x.begin())] = v;
        }
        y.push_back(tSum / static_cast<double>(runs[r].size()));
    }
}

void ModelsPanel::showRecording(int index)
{
    if (index < 0)
        return;
    const int trainingCount = m_recordingNames.size() - (m_fitResult.validation.points.empty() ? 0 : 1);
    const bool held = index >= trainingCount;
    const std::vector<ObservationFit> &points = held ? m_fitResult.validation.points : m_fitResult.identification.fit.points;
    const int recording = held ? 0 : index;
    ErrorSurfacePlot *plots[] = {m_measured, m_predicted, m_residual};
    for (int which = 0; which < 3; ++which) {
        std::vector<double> x, y, z;
        grid(points, recording, which, x, y, z);
        if (y.size() >= 2 && x.size() >= 2) {
            plots[which]->setGrid(x, y, z);
            plots[which]->setAxisTitle(QwtPlot::yRight, which == 2 ? tr("residual (µm)") : tr("thermal error (µm)"));
        } else { // not the previous recording's map
            plots[which]->showEmpty(tr("%1: fewer than two interferometer runs or targets, no map.").arg(m_recordingNames.value(index)));
        }
    }
}

} // namespace driftlab

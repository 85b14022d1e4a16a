#include "AnalysisPanel.h"

#include "DataDrivenFitRecord.h"
#include "DataDrivenModelJson.h"
#include "ElapsedTimeBox.h"
#include "FitRequestCheck.h"
#include "PointSelection.h"
#include "RequestError.h"
#include "SessionStore.h"
#include "Workbench.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <limits>
#include <utility>

namespace driftlab {

namespace {

// A session-time bound in h:mm:ss; the special text at the minimum leaves that side open.
QDoubleSpinBox *timeBox(const QString &open, QWidget *parent)
{
    auto *b = new ElapsedTimeBox(parent);
    b->setRange(-60.0, 1000.0 * 3600.0); // one step below 0:00:00 is the open side
    b->setSpecialValueText(open);
    b->setValue(b->minimum());
    return b;
}

// The bound in hours as the fit request takes it; `open` at the minimum.
double hours(const QDoubleSpinBox *b, double open)
{
    return b->value() <= b->minimum() ? open : b->value() / 3600.0;
}

QListWidget *sessionList(QWidget *parent)
{
    auto *l = new QListWidget(parent);
    l->setSelectionMode(QAbstractItemView::NoSelection);
    l->setMaximumHeight(l->fontMetrics().height() * 5 + 8); // about four sessions in view, then it scrolls
    return l;
}

QList<qint64> checked(const QListWidget *list)
{
    QList<qint64> ids;
    for (int i = 0; i < list->count(); ++i)
        if (list->item(i)->checkState() == Qt::Checked)
            ids << list->item(i)->data(Qt::UserRole).toLongLong();
    return ids;
}

bool check(QListWidget *list, const QList<qint64> &ids)
{
    for (qint64 id : ids) {
        bool found = false;
        for (int i = 0; i < list->count(); ++i)
            found = found || list->item(i)->data(Qt::UserRole).toLongLong() == id;
        if (!found)
            return false;
    }
    const QSignalBlocker block(list);
    for (int i = 0; i < list->count(); ++i)
        list->item(i)->setCheckState(ids.contains(list->item(i)->data(Qt::UserRole).toLongLong()) ? Qt::Checked : Qt::Unchecked);
    return true;
}

} // namespace

AnalysisPanel::AnalysisPanel(QWidget *parent)
    : QWidget(parent),
      m_training(sessionList(this)),
      m_heldOut(sessionList(this)),
      m_target(new QComboBox(this)),
      m_kMin(new QSpinBox(this)),
      m_kMax(new QSpinBox(this)),
      m_trainFrom(timeBox(tr("start"), this)),
      m_trainTo(timeBox(tr("end"), this)),
      m_holdoutFrom(timeBox(tr("start"), this)),
      m_holdoutTo(timeBox(tr("end"), this)),
      m_points(new QComboBox(this)),
      m_reference(new QComboBox(this)),
      m_select(new QPushButton(tr("Select points"), this)),
      m_fit(new QPushButton(tr("Fit checked"), this)),
      m_auto(new QPushButton(tr("Auto (choose)"), this)),
      m_cancel(new QPushButton(tr("Cancel"), this)),
      m_save(new QPushButton(tr("Save model..."), this)),
      m_progress(new QProgressBar(this)),
      m_stage(new QLabel(this)),
      m_results(new AnalysisResultsView(this))
{
    m_kMin->setRange(2, 64);
    m_kMax->setRange(2, 64);
    m_kMin->setValue(2);
    m_kMax->setValue(8);
    m_points->addItem(tr("model default"), QString());
    m_points->addItem(tr("sensitive points (auto)"), QStringLiteral("auto"));
    // fit --reference: auto (by CV with several sessions), start, absolute.
    m_reference->addItem(tr("auto (by CV)"), QStringLiteral("auto"));
    m_reference->addItem(tr("rise from each run's start"), QStringLiteral("start"));
    m_reference->addItem(tr("absolute"), QStringLiteral("absolute"));
    m_training->setToolTip(tr("Training sessions (runs): with three or more, cross-validation leaves whole sessions out"));
    m_heldOut->setToolTip(tr("Held-out sessions: validated per session and pooled, never used to fit or choose"));
    m_holdoutFrom->setToolTip(tr("Held-out part of the one training session, in session time h:mm:ss (when no held-out session is checked)"));
    auto *form = new QFormLayout();
    form->addRow(tr("Training"), m_training);
    form->addRow(tr("Held out"), m_heldOut);
    form->addRow(tr("Target"), m_target);
    auto *k = new QHBoxLayout();
    k->addWidget(m_kMin);
    k->addWidget(new QLabel(tr("to"), this));
    k->addWidget(m_kMax);
    form->addRow(tr("K range"), k);
    auto *train = new QHBoxLayout();
    train->addWidget(m_trainFrom);
    train->addWidget(m_trainTo);
    form->addRow(tr("Training time"), train);
    auto *held = new QHBoxLayout();
    held->addWidget(m_holdoutFrom);
    held->addWidget(m_holdoutTo);
    form->addRow(tr("or held-out time"), held);
    form->addRow(tr("Temperature inputs"), m_points);
    form->addRow(tr("Reference"), m_reference);
    auto *models = new QGroupBox(tr("Models"), this);
    auto *modelGrid = new QGridLayout(models);
    QStringList names = DataDrivenFit::allModels();
    names.removeAll(QStringLiteral("auto"));
    const QStringList byDefault{QStringLiteral("mlr"), QStringLiteral("ridge"), QStringLiteral("exp"), QStringLiteral("dynamic")};
    for (int i = 0; i < names.size(); ++i) {
        auto *box = new QCheckBox(names[i], models);
        box->setChecked(byDefault.contains(names[i]));
        modelGrid->addWidget(box, i / 3, i % 3);
        m_modelBoxes.push_back(box);
    }
    m_auto->setToolTip(tr("fit --model auto: every applicable family, chosen by nested cross-validation with the paired "
                          "one-standard-error rule, plain references (mean, lagridge) first"));
    auto *buttons = new QGridLayout();
    buttons->addWidget(m_select, 0, 0);
    buttons->addWidget(m_fit, 0, 1);
    buttons->addWidget(m_auto, 0, 2);
    buttons->addWidget(m_cancel, 1, 0);
    buttons->addWidget(m_save, 1, 1, 1, 2);
    auto *left = new QVBoxLayout();
    left->addLayout(form);
    left->addWidget(models);
    left->addLayout(buttons);
    left->addWidget(m_progress);
    m_stage->setWordWrap(true);
    left->addWidget(m_stage);
    left->addStretch(1);
    auto *layout = new QHBoxLayout(this);
    layout->addLayout(left, 0);
    layout->addWidget(m_results, 1);

    m_progress->setRange(0, 100);
    m_progress->setValue(0);
    setBusy(false);
    connect(m_training, &QListWidget::itemChanged, this, [this] { refreshTargets(); });
    connect(m_select, &QPushButton::clicked, this, [this] {
        if (!startSelection())
            m_stage->setText(m_lastError);
    });
    connect(m_fit, &QPushButton::clicked, this, [this] {
        if (!startFits())
            m_stage->setText(m_lastError);
    });
    connect(m_auto, &QPushButton::clicked, this, [this] {
        if (!startAuto())
            m_stage->setText(m_lastError);
    });
    connect(m_cancel, &QPushButton::clicked, this, &AnalysisPanel::cancel);
    connect(m_save, &QPushButton::clicked, this, [this] {
        const int row = m_results->currentModel();
        if (row < 0 || row >= static_cast<int>(m_rows.size()) || !m_rows[static_cast<std::size_t>(row)].result) {
            m_stage->setText(tr("Choose a fitted model in the comparison table first"));
            return;
        }
        const QString path = QFileDialog::getSaveFileName(this, tr("Save model"), m_rows[static_cast<std::size_t>(row)].model + QStringLiteral(".json"),
                                                          tr("DriftLab model (*.json)"));
        if (!path.isEmpty())
            m_stage->setText(saveModel(row, path) ? tr("saved %1").arg(path) : m_lastError);
    });
    connect(this, &AnalysisPanel::selectionFinished, this, [this](bool ok) {
        const Workflow w = std::exchange(m_workflow, Workflow::None);
        if (w == Workflow::SelectOnly || (w == Workflow::SelectThenFit && !ok))
            emit workflowFinished(ok);
        else if (w == Workflow::SelectThenFit && !startFits())
            emit workflowFinished(false);
        else if (w == Workflow::SelectThenFit)
            m_workflow = Workflow::SelectThenFit;
    });
    connect(this, &AnalysisPanel::fitsFinished, this, [this](bool ok) {
        if (std::exchange(m_workflow, Workflow::None) == Workflow::SelectThenFit)
            emit workflowFinished(ok);
    });
}

bool AnalysisPanel::startWorkflow(qint64 session, const QString &target, double trainTo_h, bool selectOnly)
{
    if (!setSession(session, target)) {
        m_lastError = tr("no session %1 with a displacement channel '%2'").arg(session).arg(target);
        return false;
    }
    m_trainFrom->setValue(m_trainFrom->minimum());
    m_trainTo->setValue(std::isfinite(trainTo_h) ? trainTo_h * 3600.0 : m_trainTo->minimum());
    m_holdoutFrom->setValue(std::isfinite(trainTo_h) ? trainTo_h * 3600.0 : m_holdoutFrom->minimum());
    m_holdoutTo->setValue(m_holdoutTo->minimum());
    m_workflow = selectOnly ? Workflow::SelectOnly : Workflow::SelectThenFit;
    if (!startSelection()) {
        m_workflow = Workflow::None;
        return false;
    }
    return true;
}

AnalysisPanel::AnalysisPanel(Workbench *workbench, QWidget *parent) : AnalysisPanel(parent)
{
    connect(workbench, &Workbench::storeChanged, this, [this](SessionStore *store) { setStore(store); });
    connect(workbench, &Workbench::sessionsChanged, this, [this, workbench] {
        if (!running())
            setStore(workbench->store());
    });
    workbench->addGuard(this, [this](qint64) { return running() ? tr("An analysis is running on the open database; cancel it first") : QString(); });
}

AnalysisPanel::~AnalysisPanel()
{
    m_job.cancel();
    m_job.finish();
}

QWidget *AnalysisPanel::resultsView() const
{
    return m_results;
}

QTableWidget *AnalysisPanel::comparisonTable() const
{
    return m_results->comparisonTable();
}

QTableWidget *AnalysisPanel::silhouetteTable() const
{
    return m_results->silhouetteTable();
}

QTableWidget *AnalysisPanel::channelTable() const
{
    return m_results->channelTable();
}

void AnalysisPanel::setBusy(bool busy)
{
    // Cancel enabled (and focused) before the buttons go: the focus must not wander down the
    // dock and scroll progress and Cancel out of view.
    m_cancel->setEnabled(busy);
    if (busy && (m_select->hasFocus() || m_fit->hasFocus() || m_auto->hasFocus()))
        m_cancel->setFocus();
    for (QPushButton *b : {m_select, m_fit, m_auto})
        b->setEnabled(!busy && m_store);
    m_training->setEnabled(!busy);
    m_heldOut->setEnabled(!busy);
}

void AnalysisPanel::setStore(const SessionStore *store)
{
    const bool same = store && store == m_store;
    const QList<qint64> training = same ? trainingSessions() : QList<qint64>{};
    const QList<qint64> heldOut = same ? heldOutSessions() : QList<qint64>{};
    m_store = store;
    {
        const QSignalBlocker a(m_training), b(m_heldOut);
        m_training->clear();
        m_heldOut->clear();
        if (store)
            for (const SessionInfo &s : store->sessions()) {
                const QString label = QStringLiteral("#%1  %2").arg(s.id).arg(s.name);
                for (QListWidget *list : {m_training, m_heldOut}) {
                    auto *i = new QListWidgetItem(label, list);
                    i->setData(Qt::UserRole, s.id);
                    i->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable);
                    i->setCheckState(Qt::Unchecked);
                }
            }
        if (!training.isEmpty()) {
            check(m_training, training);
            check(m_heldOut, heldOut);
        } else if (m_training->count() > 0) {
            m_training->item(m_training->count() - 1)->setCheckState(Qt::Checked); // the newest session
        }
    }
    refreshTargets();
    setBusy(running());
}

QList<qint64> AnalysisPanel::trainingSessions() const
{
    return checked(m_training);
}

QList<qint64> AnalysisPanel::heldOutSessions() const
{
    return checked(m_heldOut);
}

bool AnalysisPanel::setTrainingSessions(const QList<qint64> &sessions)
{
    if (sessions.isEmpty() || !check(m_training, sessions))
        return false;
    refreshTargets();
    return true;
}

bool AnalysisPanel::setHeldOutSessions(const QList<qint64> &sessions)
{
    return check(m_heldOut, sessions);
}

bool AnalysisPanel::setTarget(const QString &target)
{
    const int t = m_target->findText(target);
    if (t >= 0)
        m_target->setCurrentIndex(t);
    return t >= 0;
}

void AnalysisPanel::refreshTargets()
{
    const QString previous = m_target->currentText();
    m_target->clear();
    const QList<qint64> training = trainingSessions();
    if (!m_store || training.isEmpty())
        return;
    const qint64 session = training.front();
    for (const ChannelInfo &c : m_store->channels(session))
        if (c.kind == QLatin1String("displacement"))
            m_target->addItem(c.key);
    if (!m_store->interferometerPoints(session).isEmpty())
        m_target->addItem(QStringLiteral("interferometer"));
    const int keep = m_target->findText(previous);
    if (keep >= 0)
        m_target->setCurrentIndex(keep);
}

bool AnalysisPanel::setSession(qint64 session, const QString &target)
{
    if (!check(m_training, {session}))
        return false;
    check(m_heldOut, {});
    refreshTargets();
    return target.isEmpty() || setTarget(target);
}

DataDrivenFitRequest AnalysisPanel::request(const QString &model) const
{
    DataDrivenFitRequest q;
    q.sessions = trainingSessions();
    q.session = q.sessions.isEmpty() ? 0 : q.sessions.front();
    q.model = model;
    q.target = m_target->currentText();
    q.train = {hours(m_trainFrom, -std::numeric_limits<double>::infinity()), hours(m_trainTo, std::numeric_limits<double>::infinity())};
    q.kMin = m_kMin->value();
    q.kMax = m_kMax->value();
    q.autoPoints = m_points->currentData().toString() == QLatin1String("auto");
    q.reference = m_reference->currentData().toString();
    q.holdoutSessions = heldOutSessions();
    if (!q.holdoutSessions.isEmpty()) {
        q.holdoutSession = q.holdoutSessions.front();
    } else {
        const HourRange held{hours(m_holdoutFrom, -std::numeric_limits<double>::infinity()),
                             hours(m_holdoutTo, std::numeric_limits<double>::infinity())};
        if (!held.all())
            q.holdoutRange = held;
    }
    return q;
}

void AnalysisPanel::runInBackground(std::function<void()> work)
{
    m_progress->setValue(0);
    setBusy(true);
    m_job.start(std::move(work));
}

void AnalysisPanel::finishWorker()
{
    m_job.finish();
    setBusy(false);
}

bool AnalysisPanel::startSelection()
{
    if (running()) {
        m_lastError = tr("An analysis is already running");
        return false;
    }
    if (!m_store || trainingSessions().isEmpty() || m_target->currentText().isEmpty() ||
        m_target->currentText() == QLatin1String("interferometer")) {
        m_lastError = tr("Choose training sessions and a displacement channel as the target");
        return false;
    }
    const QString path = m_store->path();
    const DataDrivenFitRequest q = request(QString());
    runInBackground([this, path, q] {
        QJsonObject result;
        QString error;
        try {
            SessionStore store(path); // this thread's own connection
            PointSelectionRequest selection;
            selection.sessions = q.sessions;
            selection.target = q.target;
            selection.hours = q.train;
            selection.kMin = q.kMin;
            selection.kMax = q.kMax;
            // The use case the CLI's select-points runs: checks, selects, stores the same record.
            result = PointSelection(store).run(selection, [this](double f, const QString &stage) {
                QMetaObject::invokeMethod(this, [this, f, stage] {
                    m_progress->setValue(static_cast<int>(100 * f));
                    m_stage->setText(stage);
                }, Qt::QueuedConnection);
                return !m_job.cancelled();
            }).record;
        } catch (const std::exception &e) {
            error = m_job.cancelled() ? tr("Cancelled: no selection was made") : RequestError::forScreen(e);
        }
        QMetaObject::invokeMethod(this, [this, result, error, session = q.session] {
            finishWorker();
            m_lastError = error;
            if (!error.isEmpty()) {
                m_stage->setText(error);
                emit selectionFinished(false);
                return;
            }
            m_selection = result;
            m_results->showSelection(m_selection, m_store, session);
            m_progress->setValue(100);
            m_stage->setText(tr("chosen points: %1").arg(result.value(QStringLiteral("chosen")).toVariant().toStringList().join(QStringLiteral(", "))));
            emit selectionFinished(true);
        }, Qt::QueuedConnection);
    });
    return true;
}

bool AnalysisPanel::startFits(const QStringList &models)
{
    QStringList chosen = models;
    if (chosen.isEmpty())
        for (QCheckBox *b : m_modelBoxes)
            if (b->isChecked())
                chosen << b->text();
    if (chosen.isEmpty() && !running()) {
        m_lastError = tr("Check at least one model");
        return false;
    }
    return startModels(chosen, false);
}

bool AnalysisPanel::startAuto()
{
    return startModels({QStringLiteral("auto")}, true);
}

bool AnalysisPanel::startModels(const QStringList &models, bool automatic)
{
    if (running()) {
        m_lastError = tr("An analysis is already running");
        return false;
    }
    if (!m_store || trainingSessions().isEmpty() || m_target->currentText().isEmpty()) {
        m_lastError = tr("Choose training sessions and a target");
        return false;
    }
    std::vector<DataDrivenFitRequest> requests;
    for (const QString &m : models)
        requests.push_back(request(m));
    const QString path = m_store->path();
    m_results->setCurrentIndex(1);
    runInBackground([this, path, requests, automatic] {
        std::vector<ModelRow> rows;
        std::vector<qint64> stored;
        QString rule;
        try {
            SessionStore store(path);
            const DataDrivenFit fit(store);
            for (std::size_t i = 0; i < requests.size() && !m_job.cancelled(); ++i) {
                const DataDrivenFitRequest &q = requests[i];
                ModelRow row;
                row.model = q.model;
                try {
                    // The checks `fit` makes before any work, then the same use case.
                    FitRequestCheck::checkRanges(store, q.session, q.train, q.holdoutRange);
                    DataDrivenFitResult r = fit.fit(q, [this, i, n = requests.size(), model = row.model](double f, const QString &stage) {
                        QMetaObject::invokeMethod(this, [this, i, n, f, stage, model] {
                            m_progress->setValue(static_cast<int>(100.0 * (static_cast<double>(i) + f) / static_cast<double>(n)));
                            m_stage->setText(QStringLiteral("%1: %2").arg(model, stage));
                        }, Qt::QueuedConnection);
                        return !m_job.cancelled();
                    });
                    const qint64 id = DataDrivenFitRecord::store(store, r, r.document, DataDrivenFitRecord::Face::Gui);
                    if (automatic) {
                        rule = r.document.value(QStringLiteral("model_selection")).toObject().value(QStringLiteral("rule")).toString();
                        for (const FamilyComparison &c : r.comparison) {
                            ModelRow family;
                            family.model = c.model;
                            family.comparison = c;
                            family.error = c.error;
                            if (c.chosen)
                                family.result = r;
                            rows.push_back(std::move(family));
                            stored.push_back(c.chosen ? id : 0);
                        }
                        continue;
                    }
                    row.model = QString::fromStdString(r.model.kind);
                    row.result = std::move(r);
                    stored.push_back(id);
                } catch (const std::exception &e) {
                    row.error = m_job.cancelled() ? tr("cancelled") : RequestError::forScreen(e);
                    stored.push_back(0);
                }
                rows.push_back(std::move(row));
            }
        } catch (const std::exception &e) {
            ModelRow row;
            row.error = RequestError::forScreen(e);
            rows.push_back(row);
            stored.push_back(0);
        }
        const bool cancelled = m_job.cancelled();
        QMetaObject::invokeMethod(this, [this, rows = std::move(rows), stored = std::move(stored), rule, cancelled]() mutable {
            finishWorker();
            m_rows = std::move(rows);
            m_stored = std::move(stored);
            m_results->showModels(m_rows, rule);
            bool ok = !cancelled && !m_rows.empty();
            bool any = false;
            for (const ModelRow &r : m_rows) {
                any = any || r.result.has_value();
                ok = ok && (r.result.has_value() || (r.comparison && !r.comparison->chosen));
            }
            ok = ok && any;
            m_lastError = cancelled ? tr("Cancelled") : (ok ? QString() : tr("some models could not be fitted (see the table)"));
            if (!ok && !cancelled && m_rows.size() == 1 && !m_rows.front().error.isEmpty())
                m_lastError = m_rows.front().error;
            m_progress->setValue(cancelled ? m_progress->value() : 100);
            m_stage->setText(cancelled ? tr("Cancelled: the models fitted before are shown")
                                       : (ok ? tr("done: stored with session %1").arg(trainingSessions().value(0)) : m_lastError));
            emit fitsFinished(ok);
        }, Qt::QueuedConnection);
    });
    return true;
}

void AnalysisPanel::cancel()
{
    m_job.cancel();
    m_stage->setText(tr("Cancelling..."));
}

bool AnalysisPanel::saveModel(int row, const QString &path)
{
    if (row < 0 || row >= static_cast<int>(m_rows.size()) || !m_rows[static_cast<std::size_t>(row)].result) {
        m_lastError = tr("row %1 holds no fitted model").arg(row);
        return false;
    }
    try {
        DataDrivenModelJson::write(m_rows[static_cast<std::size_t>(row)].result->document, path);
        return true;
    } catch (const std::exception &e) {
        m_lastError = RequestError::forScreen(e);
        return false;
    }
}

} // namespace driftlab

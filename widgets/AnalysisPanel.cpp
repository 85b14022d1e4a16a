#include "AnalysisPanel.h"

#include "AnalysisPlots.h"
#include "DataDrivenModelJson.h"
#include "PointSelection.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"

#include <qwt_plot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <limits>
#include <utility>

namespace driftlab {

namespace {

QDoubleSpinBox *hoursBox(const QString &special, QWidget *parent)
{
    auto *b = new QDoubleSpinBox(parent);
    b->setRange(-1.0, 100000.0);
    b->setDecimals(2);
    b->setSuffix(QStringLiteral(" h"));
    b->setSpecialValueText(special); // shown at the minimum: the start / the end of the session
    b->setValue(-1.0);
    return b;
}

double hours(const QDoubleSpinBox *b, double open)
{
    return b->value() <= b->minimum() ? open : b->value();
}

QTableWidgetItem *item(const QString &text)
{
    auto *i = new QTableWidgetItem(text);
    i->setFlags(i->flags() & ~Qt::ItemIsEditable);
    return i;
}

QString number(double v, int decimals = 3)
{
    return std::isfinite(v) ? QString::number(v, 'f', decimals) : QStringLiteral("-");
}

} // namespace

AnalysisPanel::AnalysisPanel(QWidget *parent)
    : QWidget(parent),
      m_session(new QComboBox(this)),
      m_target(new QComboBox(this)),
      m_kMin(new QSpinBox(this)),
      m_kMax(new QSpinBox(this)),
      m_trainFrom(hoursBox(tr("start"), this)),
      m_trainTo(hoursBox(tr("end"), this)),
      m_holdout(new QComboBox(this)),
      m_holdoutFrom(hoursBox(tr("start"), this)),
      m_holdoutTo(hoursBox(tr("end"), this)),
      m_points(new QComboBox(this)),
      m_select(new QPushButton(tr("Select points"), this)),
      m_fit(new QPushButton(tr("Fit models"), this)),
      m_cancel(new QPushButton(tr("Cancel"), this)),
      m_save(new QPushButton(tr("Save model..."), this)),
      m_progress(new QProgressBar(this)),
      m_stage(new QLabel(this)),
      m_tabs(new QTabWidget(this)),
      m_silhouettes(new QTableWidget(0, 2, this)),
      m_channels(new QTableWidget(0, 5, this)),
      m_selectionPlots(new QTabWidget(this)),
      m_table(new QTableWidget(0, 10, this)),
      m_prediction(new TimeSeriesPlot(this)),
      m_residual(new TimeSeriesPlot(this))
{
    m_kMin->setRange(2, 64);
    m_kMax->setRange(2, 64);
    m_kMin->setValue(2);
    m_kMax->setValue(8);
    m_points->addItem(tr("model default"), QString());
    m_points->addItem(tr("sensitive points (auto)"), QStringLiteral("auto"));
    auto *form = new QFormLayout();
    form->addRow(tr("Session"), m_session);
    form->addRow(tr("Target"), m_target);
    auto *k = new QHBoxLayout();
    k->addWidget(m_kMin);
    k->addWidget(new QLabel(tr("to"), this));
    k->addWidget(m_kMax);
    form->addRow(tr("K range"), k);
    auto *train = new QHBoxLayout();
    train->addWidget(m_trainFrom);
    train->addWidget(m_trainTo);
    form->addRow(tr("Training hours"), train);
    form->addRow(tr("Validate on"), m_holdout);
    auto *held = new QHBoxLayout();
    held->addWidget(m_holdoutFrom);
    held->addWidget(m_holdoutTo);
    form->addRow(tr("Held-out hours"), held);
    form->addRow(tr("Temperature inputs"), m_points);
    auto *models = new QGroupBox(tr("Models"), this);
    auto *modelGrid = new QGridLayout(models);
    const QStringList names = DataDrivenFit::models();
    for (int i = 0; i < names.size(); ++i) {
        auto *box = new QCheckBox(names[i], models);
        box->setChecked(names[i] != QLatin1String("synthetic"));
        modelGrid->addWidget(box, i / 3, i % 3);
        m_modelBoxes.push_back(box);
    }
    auto *buttons = new QGridLayout();
    buttons->addWidget(m_select, 0, 0);
    buttons->addWidget(m_fit, 0, 1);
    buttons->addWidget(m_cancel, 1, 0);
    buttons->addWidget(m_save, 1, 1);
    auto *left = new QVBoxLayout();
    left->addLayout(form);
    left->addWidget(models);
    left->addLayout(buttons);
    left->addWidget(m_progress);
    m_stage->setWordWrap(true);
    left->addWidget(m_stage);
    left->addStretch(1);

    m_silhouettes->setHorizontalHeaderLabels({tr("K"), tr("silhouette")});
    m_channels->setHorizontalHeaderLabels({tr("channel"), tr("cluster"), tr("grey grade"), tr("correlation"), tr("chosen")});
    for (QTableWidget *t : {m_silhouettes, m_channels, m_table}) {
        t->verticalHeader()->hide();
        t->horizontalHeader()->setStretchLastSection(true);
        t->setSelectionBehavior(QAbstractItemView::SelectRows);
        t->setSelectionMode(QAbstractItemView::SingleSelection);
    }
    m_silhouettes->setMinimumHeight(160);
    m_channels->setMinimumHeight(160);
    auto *tables = new QSplitter(Qt::Horizontal, this);
    tables->addWidget(m_silhouettes);
    tables->addWidget(m_channels);
    tables->setStretchFactor(1, 2);
    auto *selectionPage = new QSplitter(Qt::Vertical, this);
    selectionPage->addWidget(tables);
    selectionPage->addWidget(m_selectionPlots);
    selectionPage->setStretchFactor(1, 3);
    // Two-line headers keep the numeric columns narrow enough for a 1366-pixel screen.
    m_table->setHorizontalHeaderLabels({tr("model"), tr("inputs"), tr("training\nRMSE (µm)"), tr("CV\nRMSE (µm)"),
                                        tr("held-out\nRMSE (µm)"), tr("held-out\nMAE (µm)"), tr("held-out\nmax |e| (µm)"),
                                        tr("held-out fitting\ndegree (%)"), tr("fit\ntime (s)"), tr("note")});
    m_prediction->setTitle(tr("Measured and predicted"));
    m_residual->setTitle(tr("Residual"));
    auto *modelsPage = new QSplitter(Qt::Vertical, this);
    modelsPage->addWidget(m_table);
    modelsPage->addWidget(m_prediction);
    modelsPage->addWidget(m_residual);
    modelsPage->setStretchFactor(1, 2);
    modelsPage->setStretchFactor(2, 1);
    m_tabs->addTab(selectionPage, tr("Sensitive points"));
    m_tabs->addTab(modelsPage, tr("Model comparison"));
    auto *layout = new QHBoxLayout(this);
    layout->addLayout(left, 0);
    layout->addWidget(m_tabs, 1);

    m_progress->setRange(0, 100);
    m_progress->setValue(0);
    setBusy(false);
    connect(m_session, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this] { refreshTargets(); });
    connect(m_select, &QPushButton::clicked, this, [this] {
        if (!startSelection())
            m_stage->setText(m_lastError);
    });
    connect(m_fit, &QPushButton::clicked, this, [this] {
        if (!startFits())
            m_stage->setText(m_lastError);
    });
    connect(m_cancel, &QPushButton::clicked, this, &AnalysisPanel::cancel);
    connect(m_save, &QPushButton::clicked, this, [this] {
        const int row = m_table->currentRow();
        if (row < 0 || row >= static_cast<int>(m_rows.size()) || !m_rows[static_cast<std::size_t>(row)].result) {
            m_stage->setText(tr("Choose a fitted model in the comparison table first"));
            return;
        }
        const QString path = QFileDialog::getSaveFileName(this, tr("Save model"), m_rows[static_cast<std::size_t>(row)].model + QStringLiteral(".json"),
                                                          tr("DriftLab model (*.json)"));
        if (!path.isEmpty())
            m_stage->setText(saveModel(row, path) ? tr("saved %1").arg(path) : m_lastError);
    });
    connect(m_table, &QTableWidget::currentCellChanged, this, [this](int row) { showModel(row); });
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
    m_trainTo->setValue(std::isfinite(trainTo_h) ? trainTo_h : m_trainTo->minimum());
    m_holdout->setCurrentIndex(std::isfinite(trainTo_h) ? 1 : 0);
    m_holdoutFrom->setValue(std::isfinite(trainTo_h) ? trainTo_h : m_holdoutFrom->minimum());
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
    return m_tabs;
}

void AnalysisPanel::setBusy(bool busy)
{
    // Cancel enabled (and focused) before the buttons go: the focus must not wander down the
    // dock and scroll progress and Cancel out of view.
    m_cancel->setEnabled(busy);
    if (busy && (m_select->hasFocus() || m_fit->hasFocus()))
        m_cancel->setFocus();
    m_select->setEnabled(!busy && m_store);
    m_fit->setEnabled(!busy && m_store);
    m_session->setEnabled(!busy);
}

void AnalysisPanel::setStore(const SessionStore *store)
{
    m_store = store;
    m_session->blockSignals(true);
    m_session->clear();
    m_holdout->clear();
    m_holdout->addItem(tr("nothing"), QVariant());
    m_holdout->addItem(tr("held-out hours of this session"), QStringLiteral("range"));
    if (store)
        for (const SessionInfo &s : store->sessions()) {
            const QString label = QStringLiteral("#%1  %2").arg(s.id).arg(s.name);
            m_session->addItem(label, s.id);
            m_holdout->addItem(tr("session %1").arg(label), s.id);
        }
    m_session->setCurrentIndex(m_session->count() - 1);
    m_session->blockSignals(false);
    refreshTargets();
    setBusy(running());
}

void AnalysisPanel::refreshTargets()
{
    const QString previous = m_target->currentText();
    m_target->clear();
    if (!m_store || m_session->currentIndex() < 0)
        return;
    const qint64 session = m_session->currentData().toLongLong();
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
    const int i = m_session->findData(session);
    if (i < 0)
        return false;
    m_session->setCurrentIndex(i);
    if (target.isEmpty())
        return true;
    const int t = m_target->findText(target);
    if (t >= 0)
        m_target->setCurrentIndex(t);
    return t >= 0;
}

DataDrivenFitRequest AnalysisPanel::request(const QString &model) const
{
    DataDrivenFitRequest q;
    q.session = m_session->currentData().toLongLong();
    q.model = model;
    q.target = m_target->currentText();
    q.train = {hours(m_trainFrom, -std::numeric_limits<double>::infinity()), hours(m_trainTo, std::numeric_limits<double>::infinity())};
    q.kMin = m_kMin->value();
    q.kMax = m_kMax->value();
    q.autoPoints = m_points->currentData().toString() == QLatin1String("auto");
    const QVariant holdout = m_holdout->currentData();
    if (holdout.toString() == QLatin1String("range"))
        q.holdoutRange = HourRange{hours(m_holdoutFrom, -std::numeric_limits<double>::infinity()),
                                   hours(m_holdoutTo, std::numeric_limits<double>::infinity())};
    else if (holdout.isValid())
        q.holdoutSession = holdout.toLongLong();
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
    if (!m_store || m_target->currentText().isEmpty() || m_target->currentText() == QLatin1String("interferometer")) {
        m_lastError = tr("Choose a session and a displacement channel as the target");
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
            selection.sessions = {q.session};
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
            error = m_job.cancelled() ? tr("Cancelled: no selection was made") : QString::fromUtf8(e.what());
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
            m_selectionSession = session;
            showSelection();
            m_progress->setValue(100);
            m_stage->setText(tr("chosen points: %1").arg(result.value(QStringLiteral("chosen")).toVariant().toStringList().join(QStringLiteral(", "))));
            emit selectionFinished(true);
        }, Qt::QueuedConnection);
    });
    return true;
}

bool AnalysisPanel::startFits(const QStringList &models)
{
    if (running()) {
        m_lastError = tr("An analysis is already running");
        return false;
    }
    QStringList chosen = models;
    if (chosen.isEmpty())
        for (QCheckBox *b : m_modelBoxes)
            if (b->isChecked())
                chosen << b->text();
    if (!m_store || m_target->currentText().isEmpty() || chosen.isEmpty()) {
        m_lastError = tr("Choose a session, a target and at least one model");
        return false;
    }
    std::vector<DataDrivenFitRequest> requests;
    for (const QString &m : chosen)
        requests.push_back(request(m));
    const QString path = m_store->path();
    m_tabs->setCurrentIndex(1);
    runInBackground([this, path, requests] {
        std::vector<ModelRow> rows;
        try {
            SessionStore store(path);
            const DataDrivenFit fit(store);
            for (std::size_t i = 0; i < requests.size() && !m_job.cancelled(); ++i) {
                ModelRow row;
                row.model = requests[i].model;
                try {
                    row.result = fit.fit(requests[i], [this, i, n = requests.size(), model = row.model](double f, const QString &stage) {
                        QMetaObject::invokeMethod(this, [this, i, n, f, stage, model] {
                            m_progress->setValue(static_cast<int>(100.0 * (static_cast<double>(i) + f) / static_cast<double>(n)));
                            m_stage->setText(QStringLiteral("%1: %2").arg(model, stage));
                        }, Qt::QueuedConnection);
                        return !m_job.cancelled();
                    });
                } catch (const std::exception &e) {
                    row.error = m_job.cancelled() ? tr("cancelled") : QString::fromUtf8(e.what());
                }
                rows.push_back(std::move(row));
            }
        } catch (const std::exception &e) {
            ModelRow row;
            row.error = QString::fromUtf8(e.what());
            rows.push_back(row);
        }
        const bool cancelled = m_job.cancelled();
        QMetaObject::invokeMethod(this, [this, rows = std::move(rows), cancelled]() mutable {
            finishWorker();
            m_rows = std::move(rows);
            showModels();
            bool ok = !cancelled;
            for (const ModelRow &r : m_rows)
                ok = ok && r.result.has_value();
            m_lastError = cancelled ? tr("Cancelled") : (ok ? QString() : tr("some models could not be fitted (see the table)"));
            m_progress->setValue(cancelled ? m_progress->value() : 100);
            m_stage->setText(cancelled ? tr("Cancelled: the models fitted before are shown") : (ok ? tr("done") : m_lastError));
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

void AnalysisPanel::showSelection()
{
    const QJsonArray perK = m_selection.value(QStringLiteral("silhouettes")).toArray();
    m_silhouettes->setRowCount(perK.size());
    const int chosenK = m_selection.value(QStringLiteral("k")).toInt();
    for (int i = 0; i < perK.size(); ++i) {
        const QJsonObject e = perK[i].toObject();
        const int k = e.value(QStringLiteral("k")).toInt();
        m_silhouettes->setItem(i, 0, item(k == chosenK ? QStringLiteral("%1 (chosen)").arg(k) : QString::number(k)));
        m_silhouettes->setItem(i, 1, item(number(e.value(QStringLiteral("silhouette")).toDouble())));
    }
    const QJsonArray channels = m_selection.value(QStringLiteral("channels")).toArray();
    m_channels->setRowCount(channels.size());
    for (int i = 0; i < channels.size(); ++i) {
        const QJsonObject c = channels[i].toObject();
        m_channels->setItem(i, 0, item(c.value(QStringLiteral("channel")).toString()));
        m_channels->setItem(i, 1, item(QString::number(c.value(QStringLiteral("cluster")).toInt())));
        m_channels->setItem(i, 2, item(number(c.value(QStringLiteral("grade")).toDouble())));
        m_channels->setItem(i, 3, item(number(c.value(QStringLiteral("correlation")).toDouble())));
        m_channels->setItem(i, 4, item(c.value(QStringLiteral("chosen")).toBool() ? tr("yes") : QString()));
    }
    m_silhouettes->resizeColumnsToContents();
    m_channels->resizeColumnsToContents();
    while (m_selectionPlots->count() > 0) {
        QWidget *w = m_selectionPlots->widget(0);
        m_selectionPlots->removeTab(0);
        delete w;
    }
    const QStringList titles{tr("Grades"), tr("Clusters"), tr("Chosen points over time")};
    const QStringList views = AnalysisPlots::selectionViews();
    for (int i = 0; i < views.size(); ++i) {
        try {
            m_selectionPlots->addTab(AnalysisPlots::selectionPlot(views[i], m_selection, m_store, m_selectionSession).release(), titles[i]);
        } catch (const std::exception &e) {
            m_selectionPlots->addTab(new QLabel(QString::fromUtf8(e.what())), titles[i]);
        }
    }
    m_tabs->setCurrentIndex(0);
}

void AnalysisPanel::showModels()
{
    m_table->setRowCount(static_cast<int>(m_rows.size()));
    int best = -1;
    double bestRmse = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(m_rows.size()); ++i) {
        const ModelRow &r = m_rows[static_cast<std::size_t>(i)];
        m_table->setItem(i, 0, item(r.model));
        if (!r.result) {
            for (int c = 1; c < 9; ++c)
                m_table->setItem(i, c, item(QString()));
            m_table->setItem(i, 9, item(r.error));
            continue;
        }
        const DataDrivenFitResult &f = *r.result;
        QStringList inputs;
        for (const ModelChannel &c : f.model.inputs)
            inputs << QString::fromStdString(c.id);
        m_table->setItem(i, 1, item(inputs.join(QStringLiteral(", "))));
        m_table->item(i, 1)->setToolTip(inputs.join(QStringLiteral(", ")));
        m_table->setItem(i, 2, item(number(f.training.metrics.rmse)));
        m_table->setItem(i, 3, item(number(f.cvRmse)));
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const ErrorMetrics *h = f.holdout ? &f.holdout->metrics : nullptr;
        m_table->setItem(i, 4, item(number(h ? h->rmse : nan)));
        m_table->setItem(i, 5, item(number(h ? h->mae : nan)));
        m_table->setItem(i, 6, item(number(h ? h->maxAbs : nan, 2)));
        m_table->setItem(i, 7, item(number(h ? h->fittingDegree_pct : nan, 1)));
        m_table->setItem(i, 8, item(number(f.wallTime_s, 2)));
        m_table->setItem(i, 9, item(f.selection ? tr("sensitive points: %1").arg(inputs.join(QStringLiteral(", "))) : QString()));
        const double score = h ? h->rmse : f.cvRmse;
        if (std::isfinite(score) && score < bestRmse) {
            bestRmse = score;
            best = i;
        }
    }
    m_table->resizeColumnsToContents();
    // A long input list is elided (the full list is the cell's tooltip), not widening the table.
    m_table->setColumnWidth(1, std::min(m_table->columnWidth(1), m_table->fontMetrics().horizontalAdvance(QLatin1Char('x')) * 28));
    if (best >= 0)
        m_table->selectRow(best);
    showModel(best);
}

void AnalysisPanel::showModel(int row)
{
    if (row < 0 || row >= static_cast<int>(m_rows.size()) || !m_rows[static_cast<std::size_t>(row)].result) {
        m_prediction->clearCurves();
        m_residual->clearCurves();
        return;
    }
    const DataDrivenFitResult &f = *m_rows[static_cast<std::size_t>(row)].result;
    const ValidationSeries *holdout = f.holdout ? &*f.holdout : nullptr;
    AnalysisPlots::showPrediction(*m_prediction, f.training, holdout);
    AnalysisPlots::showResidual(*m_residual, f.training, holdout);
    m_prediction->setTitle(tr("%1 model of %2: measured and predicted").arg(m_rows[static_cast<std::size_t>(row)].model,
                                                                           QString::fromStdString(f.model.target.id)));
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
        m_lastError = QString::fromUtf8(e.what());
        return false;
    }
}

} // namespace driftlab

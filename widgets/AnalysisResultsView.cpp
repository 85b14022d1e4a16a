#include "AnalysisResultsView.h"

#include "AnalysisPlots.h"
#include "ExtrapolationWarning.h"
#include "TimeSeriesPlot.h"

#include <qwt_plot.h>

#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <limits>

namespace driftlab {

namespace {

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

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
const QSize kPlotMinimum(300, 200);

} // namespace

AnalysisResultsView::AnalysisResultsView(QWidget *parent)
    : QTabWidget(parent),
      m_silhouettes(new QTableWidget(0, 2, this)),
      m_channels(new QTableWidget(0, 5, this)),
      m_selectionPlots(new QTabWidget(this)),
      m_rule(new QLabel(this)),
      m_warning(new QLabel(this)),
      m_table(new QTableWidget(0, Columns, this)),
      m_sessions(new QTableWidget(0, 7, this)),
      m_prediction(new TimeSeriesPlot(this)),
      m_residual(new TimeSeriesPlot(this)),
      m_lower(new QTabWidget(this))
{
    m_silhouettes->setHorizontalHeaderLabels({tr("K"), tr("silhouette")});
    m_channels->setHorizontalHeaderLabels({tr("channel"), tr("cluster"), tr("grey grade"), tr("correlation"), tr("chosen")});
    // Two-line headers keep the numeric columns narrow enough for a 1366-pixel screen.
    m_table->setHorizontalHeaderLabels({tr("model"), tr("CV\nRMSE (µm)"), tr("nested CV\nRMSE (µm)"), tr("paired\nSE (µm)"),
                                        tr("para-\nmeters"), tr("reference"), tr("training\nRMSE (µm)"),
                                        tr("held-out\nRMSE (µm)"), tr("note")});
    m_sessions->setHorizontalHeaderLabels({tr("data"), tr("RMSE\n(µm)"), tr("MAE\n(µm)"), tr("max |e|\n(µm)"),
                                           tr("fitting\ndegree (%)"), tr("samples"), tr("extrapolated\ninputs")});
    for (QTableWidget *t : {m_silhouettes, m_channels, m_table, m_sessions}) {
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

    m_rule->setWordWrap(true);
    m_rule->hide();
    // The warning is text on the page, not a tooltip: it stays in view with the table.
    m_warning->setWordWrap(true);
    m_warning->setObjectName(QStringLiteral("extrapolationWarning"));
    m_warning->setStyleSheet(QStringLiteral("QLabel { color: #8a1c00; background: #fff1d6; padding: 3px; }"));
    m_warning->hide();
    m_prediction->setTitle(tr("Measured and predicted"));
    m_residual->setTitle(tr("Residual"));
    auto *top = new QWidget(this);
    auto *topLayout = new QVBoxLayout(top);
    topLayout->setContentsMargins(0, 0, 0, 0);
    topLayout->addWidget(m_rule);
    topLayout->addWidget(m_warning);
    // The family table at the full width of the page, six rows in view (every family of auto).
    m_table->setMinimumHeight(m_table->verticalHeader()->defaultSectionSize() * 6 + 2 * m_table->fontMetrics().height() + 16);
    m_table->horizontalHeaderItem(HeldOutRmse)->setToolTip(tr("Shown, never used to choose"));
    // The note takes the width the numbers leave: sized to its text (up to 24 x-widths) it made
    // the table 12 px wider than its viewport with the Analysis dock open at 1366 x 768.
    m_table->horizontalHeader()->setSectionResizeMode(Note, QHeaderView::Stretch);
    topLayout->addWidget(m_table, 1);
    // Below it, tabs at the full width: the metrics per session, and the plots (side by side
    // on a laptop screen the tables needed sideways scrolling and the time ticks ran together).
    m_lower->addTab(m_sessions, tr("Per session"));
    m_lower->addTab(m_prediction, tr("Measured and predicted"));
    m_lower->addTab(m_residual, tr("Residual"));
    auto *modelsPage = new QSplitter(Qt::Vertical, this);
    modelsPage->addWidget(top);
    modelsPage->addWidget(m_lower);
    modelsPage->setStretchFactor(0, 2);
    modelsPage->setStretchFactor(1, 3);
    addTab(selectionPage, tr("Sensitive points"));
    addTab(modelsPage, tr("Model comparison"));
    connect(m_table, &QTableWidget::currentCellChanged, this, [this](int row) { showModel(row); });
    connect(m_sessions, &QTableWidget::currentCellChanged, this, [this](int row) { showSeries(row); });
}

void AnalysisResultsView::showSelection(const QJsonObject &selection, const SessionStore *store, qint64 session)
{
    const QJsonArray perK = selection.value(QStringLiteral("silhouettes")).toArray();
    m_silhouettes->setRowCount(perK.size());
    const int chosenK = selection.value(QStringLiteral("k")).toInt();
    for (int i = 0; i < perK.size(); ++i) {
        const QJsonObject e = perK[i].toObject();
        const int k = e.value(QStringLiteral("k")).toInt();
        m_silhouettes->setItem(i, 0, item(k == chosenK ? tr("%1 (chosen)").arg(k) : QString::number(k)));
        m_silhouettes->setItem(i, 1, item(number(e.value(QStringLiteral("silhouette")).toDouble())));
    }
    const QJsonArray channels = selection.value(QStringLiteral("channels")).toArray();
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
            std::unique_ptr<QwtPlot> plot = AnalysisPlots::selectionPlot(views[i], selection, store, session);
            // The page gives the plot its room: the plots' own minimum heights (up to 551 px with
            // the channel names on the axis) made the filled view 789 px high, and the main
            // window 975 px on a 768 px screen (tst_layout1366::analysisResultsFit).
            plot->setMinimumSize(kPlotMinimum);
            m_selectionPlots->addTab(plot.release(), titles[i]);
        } catch (const std::exception &e) {
            m_selectionPlots->addTab(new QLabel(QString::fromUtf8(e.what())), titles[i]);
        }
    }
    setCurrentIndex(0);
}

void AnalysisResultsView::showModels(const std::vector<ModelRow> &rows, const QString &rule)
{
    m_series.clear(); // they point into the rows replaced here
    m_rangeFit = nullptr;
    m_rows = rows;
    m_table->blockSignals(true);
    m_table->setRowCount(static_cast<int>(m_rows.size()));
    int chosen = -1;
    for (int i = 0; i < static_cast<int>(m_rows.size()); ++i) {
        const ModelRow &r = m_rows[static_cast<std::size_t>(i)];
        const FamilyComparison *c = r.comparison ? &*r.comparison : nullptr;
        const DataDrivenFitResult *f = r.result ? &*r.result : nullptr;
        if (c && c->chosen)
            chosen = i;
        QString name = r.model;
        if (c && c->plainReference)
            name += tr(" (ref)");
        m_table->setItem(i, Model, item(name));
        if (f) {
            QStringList inputs;
            for (const ModelChannel &ch : f->model.inputs)
                inputs << QString::fromStdString(ch.id);
            m_table->item(i, Model)->setToolTip(tr("inputs: %1").arg(inputs.join(QStringLiteral(", "))));
        }
        m_table->setItem(i, CvRmse, item(number(c ? c->cvRmse : f ? f->cvRmse : kNan)));
        m_table->setItem(i, NestedCv, item(number(c ? c->nestedCvRmse : f ? f->nestedCvRmse : kNan)));
        m_table->setItem(i, PairedSe, item(number(c ? c->pairedStandardError : kNan)));
        const int parameters = c ? c->parameters : f ? f->parameters : 0;
        m_table->setItem(i, Parameters, item(parameters > 0 ? QString::number(parameters) : QStringLiteral("-")));
        QString reference = c ? c->reference : QString();
        if (!c && f)
            reference = f->model.usesRises() ? QString::fromStdString(f->model.reference.label()) : QStringLiteral("absolute");
        m_table->setItem(i, Reference, item(reference.isEmpty() ? QStringLiteral("-") : reference));
        m_table->setItem(i, TrainingRmse, item(number(f ? f->training.metrics.rmse : kNan)));
        const double held = c && c->holdout ? c->holdout->rmse : (f && f->holdout ? f->holdout->metrics.rmse : kNan);
        m_table->setItem(i, HeldOutRmse, item(number(held)));
        QString note = r.error;
        if (c && c->chosen)
            note = tr("chosen by the rule");
        else if (!c && f && f->selection)
            note = tr("sensitive points");
        if (!r.error.isEmpty())
            note = tr("not fitted: %1").arg(r.error);
        m_table->setItem(i, Note, item(note));
        m_table->item(i, Note)->setToolTip(note);
    }
    for (int c = 0; c < Note; ++c) // the note stretches into what is left (its full text in the tooltip)
        m_table->resizeColumnToContents(c);
    m_table->blockSignals(false);
    QString chosenName;
    for (const ModelRow &r : m_rows)
        if (r.comparison && r.comparison->chosen)
            chosenName = r.model;
    m_rule->setText(rule.isEmpty() ? tr("Each checked family fitted on its own; none is chosen (Auto chooses as fit --model auto "
                                        "does). Held-out numbers are shown, never used to choose.")
                                   : tr("Auto chose %1: nested CV, paired one-standard-error rule, plain references (ref) "
                                        "first. Held-out numbers are shown, never used to choose.")
                                         .arg(chosenName));
    m_rule->setToolTip(rule); // the rule in full, as fit stores it
    m_rule->setVisible(!rows.empty());
    int shown = chosen;
    if (shown < 0)
        for (int i = 0; i < static_cast<int>(m_rows.size()) && shown < 0; ++i)
            if (m_rows[static_cast<std::size_t>(i)].result)
                shown = i;
    if (shown >= 0)
        m_table->selectRow(shown);
    showModel(shown);
    setCurrentIndex(1);
}

int AnalysisResultsView::currentModel() const
{
    return m_table->currentRow();
}

void AnalysisResultsView::showModel(int row)
{
    m_series.clear();
    m_seriesLabels.clear();
    m_rangeFit = nullptr;
    m_sessions->blockSignals(true);
    m_sessions->setRowCount(0);
    const DataDrivenFitResult *f = row >= 0 && row < static_cast<int>(m_rows.size()) && m_rows[static_cast<std::size_t>(row)].result
                                       ? &*m_rows[static_cast<std::size_t>(row)].result
                                       : nullptr;
    if (!f) {
        m_sessions->blockSignals(false);
        m_warning->hide();
        m_prediction->clearCurves();
        m_residual->clearCurves();
        return;
    }
    auto add = [&](const ValidationSeries &s, const QString &label) {
        const int r = m_sessions->rowCount();
        m_sessions->insertRow(r);
        m_sessions->setItem(r, 0, item(label));
        m_sessions->setItem(r, 1, item(number(s.metrics.rmse)));
        m_sessions->setItem(r, 2, item(number(s.metrics.mae)));
        m_sessions->setItem(r, 3, item(number(s.metrics.maxAbs, 2)));
        m_sessions->setItem(r, 4, item(number(s.metrics.fittingDegree_pct, 1)));
        m_sessions->setItem(r, 5, item(QString::number(s.metrics.n)));
        m_sessions->setItem(r, 6, item(s.extrapolated.join(QStringLiteral(", "))));
        m_series.push_back(&s);
        m_seriesLabels.push_back(label);
    };
    const bool several = f->trainingSessions.size() > 1;
    for (const ValidationSeries &s : f->trainingSessions)
        add(s, tr("training #%1").arg(s.session));
    if (several)
        add(f->training, tr("training (pooled)"));
    const bool range = f->holdout && f->holdoutSessions.size() == 1 && !f->trainingSessions.empty() &&
                       f->holdoutSessions.front().session == f->trainingSessions.front().session;
    if (range)
        m_rangeFit = f;
    for (const ValidationSeries &s : f->holdoutSessions)
        add(s, range ? tr("held-out time of #%1").arg(s.session) : tr("held-out #%1").arg(s.session));
    if (f->holdoutSessions.size() > 1 && f->holdout)
        add(*f->holdout, tr("held-out (pooled)"));
    m_sessions->resizeColumnsToContents();
    m_sessions->blockSignals(false);
    // The CLI's lines, word for word (fit prints the same for held-out hours of its session).
    const QStringList warnings = ExtrapolationWarning::lines(f->holdoutSessions, QStringLiteral("held-out session"));
    m_warning->setText(warnings.join(QLatin1Char('\n')));
    m_warning->setVisible(!warnings.isEmpty());
    // The first held-out session, else the first training session.
    const int first = f->holdoutSessions.empty() ? 0 : static_cast<int>(f->trainingSessions.size()) + (several ? 1 : 0);
    m_sessions->selectRow(first);
    showSeries(first);
    m_prediction->setTitle(tr("%1 model of %2: measured and predicted").arg(m_rows[static_cast<std::size_t>(row)].model,
                                                                           QString::fromStdString(f->model.target.id)));
}

void AnalysisResultsView::showSeries(int sessionRow)
{
    if (sessionRow < 0 || sessionRow >= static_cast<int>(m_series.size()))
        return;
    const ValidationSeries &s = *m_series[static_cast<std::size_t>(sessionRow)];
    if (s.session == 0)
        return; // pooled: sessions one after another, each on its own clock; the plots show one session
    if (m_rangeFit) { // held-out hours of the training session: both parts on the session's clock
        AnalysisPlots::showPrediction(*m_prediction, m_rangeFit->trainingSessions.front(), &m_rangeFit->holdoutSessions.front());
        AnalysisPlots::showResidual(*m_residual, m_rangeFit->trainingSessions.front(), &m_rangeFit->holdoutSessions.front());
        return;
    }
    const QString label = m_seriesLabels[static_cast<std::size_t>(sessionRow)];
    AnalysisPlots::showSeries(*m_prediction, s, label);
    AnalysisPlots::showSeriesResidual(*m_residual, s, label);
}

} // namespace driftlab

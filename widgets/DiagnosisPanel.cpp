#include "DiagnosisPanel.h"

#include "DiagnosisSwitchLabels.h"
#include "SessionDiagnosis.h"
#include "ErrorSurfacePlot.h"
#include "ModelsPanel.h"
#include "UnitLabels.h"
#include "SessionStore.h"
#include "Workbench.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSplitter>
#include <QSignalBlocker>
#include <QTableWidget>
#include <QVBoxLayout>

#include <memory>

namespace driftlab {

DiagnosisPanel::DiagnosisPanel(QWidget *parent)
    : QWidget(parent),
      m_train(new QComboBox(this)),
      m_validate(new QComboBox(this)),
      m_priors(new QCheckBox(DiagnosisSwitchLabels::priors(), this)),
      m_chain(new QCheckBox(DiagnosisSwitchLabels::measurementChain(), this)),
      m_triples(new QCheckBox(DiagnosisSwitchLabels::triples(), this)),
      m_housingContact(new QCheckBox(DiagnosisSwitchLabels::housingContact(), this)),
      m_run(new QPushButton(tr("Diagnose"), this)),
      m_cancel(new QPushButton(tr("Cancel"), this)),
      m_progress(new QProgressBar(this)),
      m_stage(new QLabel(this)),
      m_answer(new QLabel(this)),
      m_candidates(new QTableWidget(0, 6, this)),
      m_before(new ErrorSurfacePlot(this)),
      m_after(new ErrorSurfacePlot(this))
{
    // The controls take four rows: the dock is about 190 px high at 1366 x 768, and the
    // progress bar once lay below its fold (tst_diagnosisdock). The answer stands beside them,
    // above the candidates' detail, in its own vertical scroll area: below the controls it lay
    // under the fold at 1366 x 768 (tst_diagnosispanel answerInViewAt1366).
    auto *controls = new QWidget(this);
    auto *left = new QVBoxLayout(controls);
    left->setContentsMargins(0, 0, 0, 0);
    auto *sessions = new QFormLayout();
    sessions->addRow(tr("Training session"), m_train);
    sessions->addRow(tr("Validation session"), m_validate);
    // The opt-in switches of `driftlab-cli diagnose`, as a default request has them.
    const DiagnosisRequest defaults;
    const DiagnosisOptions engine;
    m_priors->setChecked(defaults.priors);
    m_priors->setToolTip(tr("Anchor the screw's conductivity λ and the fixed-end position P_f by priors from steel "
                            "(%1 ± %2 W/(m K)) and the drawing (± %3 mm).")
                             .arg(engine.steelConductivity_W_mK)
                             .arg(engine.lambdaPriorSigma_W_mK)
                             .arg(engine.fixedEndPriorSigma_mm));
    m_chain->setChecked(defaults.checkMeasurementChain);
    m_chain->setToolTip(tr("Check the sensors against each other first (PT100 steps, interferometer against the air "
                           "temperature, screw-end probe against interferometer): a faulty sensor is named and corrected, "
                           "not charged to the machine."));
    m_triples->setChecked(defaults.tryTriples);
    m_triples->setToolTip(tr("When no single effect and no pair passes, also try the best pair plus one "
                             "(named wrong effects on the third simulator, see docs/diagnosis.md)."));
    m_housingContact->setChecked(defaults.housingContact);
    m_housingContact->setToolTip(tr("The machine as built in the baseline: the screw touches the recorded fixed-bearing "
                                    "and nut housings through contact conductances of at most %1 W/K (needs the "
                                    "fixed_bearing and nut channels).")
                                     .arg(engine.asBuiltContactMax_W_K));
    m_priors->setObjectName(QStringLiteral("diagnosisPriors"));
    m_chain->setObjectName(QStringLiteral("diagnosisMeasurementChain"));
    m_triples->setObjectName(QStringLiteral("diagnosisTriples"));
    m_housingContact->setObjectName(QStringLiteral("diagnosisHousingContact"));
    // Two by two: in one row they made the controls 690 px wide and left the answer beside
    // them 180 px at 1366 x 768.
    auto *options = new QGridLayout();
    int k = 0;
    for (QCheckBox *box : {m_priors, m_chain, m_triples, m_housingContact}) {
        options->addWidget(box, k / 2, k % 2);
        ++k;
    }
    options->setColumnStretch(2, 1);
    sessions->addRow(tr("Options"), options);
    left->addLayout(sessions);
    auto *buttons = new QHBoxLayout();
    buttons->addWidget(m_run);
    buttons->addWidget(m_cancel);
    buttons->addWidget(m_progress, 1);
    left->addLayout(buttons);
    left->addWidget(m_stage);
    left->addStretch(1);
    m_stage->setWordWrap(true);

    m_answer->setObjectName(QStringLiteral("diagnosisAnswer"));
    m_answer->setWordWrap(true);
    m_answer->setAlignment(Qt::AlignLeft | Qt::AlignTop);
    m_answer->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_answer->setMinimumWidth(1); // wraps to the area, however narrow (no sideways scrolling)
    m_answerArea = new QScrollArea(this);
    m_answerArea->setObjectName(QStringLiteral("diagnosisAnswerArea"));
    m_answerArea->setWidgetResizable(true);
    m_answerArea->setFrameShape(QFrame::NoFrame);
    m_answerArea->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff); // wrapped, never read sideways
    m_answerArea->setWidget(m_answer);
    m_answerArea->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Ignored);
    m_candidates->setHorizontalHeaderLabels(
        {tr("effect"), tr("accepted"), tr("score"), tr("held-out RMS (µm)"), tr("ΔAICc"), tr("evidence")});
    m_candidates->horizontalHeader()->setStretchLastSection(true);
    m_candidates->verticalHeader()->hide();
    m_candidates->resizeColumnsToContents(); // the headings whole before the first result
    // The controls as wide as they need (the session boxes at 20 characters), the answer the
    // rest, a splitter between them; the answer as high as the controls (its own scroll bar).
    for (QComboBox *box : {m_train, m_validate}) {
        box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
        box->setMinimumContentsLength(20);
    }
    auto *work = new QSplitter(Qt::Horizontal, this);
    work->setObjectName(QStringLiteral("diagnosisWork"));
    work->addWidget(controls);
    work->addWidget(m_answerArea);
    work->setStretchFactor(0, 0);
    work->setStretchFactor(1, 1);
    work->setChildrenCollapsible(false);
    // The result beside the controls: the residual maps and, below them, the candidates'
    // detail at the full width of the view (in the dock at 1366 x 768 the table had room for
    // one row). MainWindow takes the view into the central area.
    m_before->setTitle(tr("Validation residual, baseline"));
    m_after->setTitle(tr("Validation residual, corrected model"));
    for (ErrorSurfacePlot *p : {m_before, m_after})
        p->showEmpty(tr("Diagnose a training and a validation session (Diagnosis dock): the validation residual over "
                        "position and time appears here, before and after the correction."));
    m_plots = new QSplitter(Qt::Vertical, this);
    m_plots->setObjectName(QStringLiteral("DiagnosisPlots"));
    m_plots->addWidget(m_before);
    m_plots->addWidget(m_after);
    m_plots->setChildrenCollapsible(false);
    m_results = new QSplitter(Qt::Vertical, this);
    m_results->setObjectName(QStringLiteral("DiagnosisView"));
    m_results->addWidget(m_plots);
    m_results->addWidget(m_candidates);
    m_results->setStretchFactor(0, 2);
    m_results->setStretchFactor(1, 1);
    m_results->setSizes({2000, 1000}); // two thirds for the maps, a third (4 rows at 1366 x 768) for the table
    m_results->setChildrenCollapsible(false);
    auto *layout = new QHBoxLayout(this);
    layout->addWidget(work, 1);
    layout->addWidget(m_results, 1);
    // 3 px above and below (with the style's 9-11 px the controls, and the answer beside them,
    // were 200 px high in a dock whose viewport is 194 px at 1366 x 768).
    const QMargins m = layout->contentsMargins();
    layout->setContentsMargins(m.left(), 3, m.right(), 3);

    m_progress->setRange(0, 100);
    m_progress->setValue(0);
    m_cancel->setEnabled(false);
    connect(m_run, &QPushButton::clicked, this, [this] {
        if (!start(m_train->currentData().toLongLong(), m_validate->currentData().toLongLong()))
            m_stage->setText(m_lastError);
    });
    connect(m_cancel, &QPushButton::clicked, this, &DiagnosisPanel::cancel);
    // Choosing another pair than the one on screen says so above the result.
    for (QComboBox *box : {m_train, m_validate})
        connect(box, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &DiagnosisPanel::updateHeading);
}

DiagnosisPanel::DiagnosisPanel(Workbench *workbench, QWidget *parent) : DiagnosisPanel(parent)
{
    connect(workbench, &Workbench::storeChanged, this, [this](SessionStore *store) { setStore(store); });
    connect(workbench, &Workbench::sessionsChanged, this, [this, workbench] {
        if (!running())
            setStore(workbench->store());
    });
    workbench->addGuard(this, [this](qint64) { return running() ? tr("A diagnosis is running on the open database; cancel it first") : QString(); });
}

DiagnosisPanel::~DiagnosisPanel()
{
    m_job.cancel();
    m_job.finish();
}

namespace {
void selectSession(QComboBox *box, qint64 id)
{
    const int index = box->findData(id);
    if (index >= 0)
        box->setCurrentIndex(index);
}
} // namespace

void DiagnosisPanel::setStore(const SessionStore *store)
{
    if (store != m_store) { // another database: the result on screen is not about it
        m_resultTrain = m_resultValidate = 0;
        m_resultText.clear();
        m_answer->clear();
    }
    m_store = store;
    const QSignalBlocker blockTrain(m_train), blockValidate(m_validate);
    m_train->clear();
    m_validate->clear();
    if (!store) {
        updateHeading();
        return;
    }
    for (const SessionInfo &s : store->sessions()) {
        const QString label = QStringLiteral("#%1  %2").arg(s.id).arg(s.name);
        m_train->addItem(label, s.id);
        m_validate->addItem(label, s.id);
    }
    m_validate->setCurrentIndex(m_validate->count() - 1);
    // A refresh of the same database keeps showing the pair of the result on screen.
    if (m_resultTrain) {
        selectSession(m_train, m_resultTrain);
        selectSession(m_validate, m_resultValidate);
    }
    updateHeading();
}

void DiagnosisPanel::updateHeading()
{
    if (!m_resultTrain) {
        m_heading.clear();
        return;
    }
    m_heading = tr("Result for training #%1 and validation #%2").arg(m_resultTrain).arg(m_resultValidate);
    const qint64 train = m_train->currentData().toLongLong(), validate = m_validate->currentData().toLongLong();
    QString html = QStringLiteral("<b>%1</b>").arg(m_heading.toHtmlEscaped());
    if (train != m_resultTrain || validate != m_resultValidate) {
        const QString warning = tr("The boxes select #%1 and #%2, which have not been diagnosed: press Diagnose to run them.")
                                    .arg(train)
                                    .arg(validate);
        m_heading += QStringLiteral(". ") + warning;
        html += QStringLiteral("<br><span style='color:#c05000'>%1</span>").arg(warning.toHtmlEscaped());
    }
    m_answer->setText(html + QStringLiteral("<br>") + m_resultText);
}

bool DiagnosisPanel::start(qint64 trainSession, qint64 validationSession)
{
    if (running()) {
        m_lastError = tr("A diagnosis is already running");
        return false;
    }
    if (!m_store) {
        m_lastError = tr("Open a database first");
        return false;
    }
    if (trainSession == validationSession) {
        m_lastError = tr("Training and validation must be different sessions");
        return false;
    }
    {
        const QSignalBlocker blockTrain(m_train), blockValidate(m_validate);
        selectSession(m_train, trainSession);
        selectSession(m_validate, validationSession);
    }
    m_runTrain = trainSession;
    m_runValidate = validationSession;
    // Reads both sessions here (a SessionStore belongs to the thread that opened it); the
    // settings are those of `driftlab-cli diagnose` because it is the same use case.
    DiagnosisRequest request;
    request.train = trainSession;
    request.validate = validationSession;
    request.trainLabel = QStringLiteral("#%1").arg(trainSession);
    request.validateLabel = QString::number(validationSession); // stored as `diagnose --validate ID` stores it
    request.priors = m_priors->isChecked();
    request.checkMeasurementChain = m_chain->isChecked();
    request.tryTriples = m_triples->isChecked();
    request.housingContact = m_housingContact->isChecked();
    std::shared_ptr<const SessionDiagnosis> diagnosis;
    try {
        SessionDiagnosis::checkWritable(*m_store);
        diagnosis = std::make_shared<const SessionDiagnosis>(*m_store, request);
    } catch (const std::exception &e) {
        m_lastError = QString::fromStdString(e.what());
        return false;
    }
    // Cancel first, and the focus with it: a disabled focused button hands the focus down
    // the chain, and the dock's scroll area followed it away from progress and Cancel.
    m_cancel->setEnabled(true);
    if (m_run->hasFocus())
        m_cancel->setFocus();
    m_run->setEnabled(false);
    m_progress->setValue(0);
    m_answer->clear();
    m_candidates->setRowCount(0);
    m_job.start([this, diagnosis, path = m_store->path()] {
        DiagnosisReport report;
        QString error;
        bool ok = true;
        try {
            report = diagnosis->run([this](double fraction, const std::string &stage) {
                const QString text = QString::fromStdString(stage);
                QMetaObject::invokeMethod(this, [this, fraction, text] {
                    m_progress->setValue(static_cast<int>(100.0 * fraction));
                    m_stage->setText(text);
                }, Qt::QueuedConnection);
                return !m_job.cancelled();
            });
            if (report.cancelled) {
                ok = false;
                error = tr("Cancelled: no diagnosis was made");
            } else {
                SessionStore store(path); // this thread's own connection
                diagnosis->store(store, report); // with the training session, for its test report
            }
        } catch (const std::exception &e) {
            ok = false;
            error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(this, [this, ok, error, report] {
            m_report = report;
            finish(ok, error);
        }, Qt::QueuedConnection);
    });
    return true;
}

void DiagnosisPanel::cancel()
{
    m_job.cancel();
    m_stage->setText(tr("Cancelling..."));
}

void DiagnosisPanel::residualGrid(const std::vector<DiagnosisPrediction> &predictions, bool corrected,
                                  std::vector<double> &x, std::vector<double> &y, std::vector<double> &z)
{
    std::vector<ObservationFit> points;
    for (const DiagnosisPrediction &p : predictions) {
        if (p.reference)
            continue;
        ObservationFit o;
        o.t_s = p.t_s;
        o.position_mm = p.position_mm;
        o.measured_um = p.measured_um;
        o.predicted_um = corrected ? p.corrected_um : p.baseline_um;
        points.push_back(o);
    }
    ModelsPanel::grid(points, 0, 2, x, y, z);
}

void DiagnosisPanel::finish(bool ok, const QString &error)
{
    m_job.finish();
    m_run->setEnabled(true);
    m_cancel->setEnabled(false);
    m_lastError = error;
    if (!ok) {
        m_stage->setText(error);
        emit finished(false);
        return;
    }
    m_progress->setValue(100);
    const DiagnosisReport &r = m_report;
    m_resultTrain = m_runTrain;
    m_resultValidate = m_runValidate;
    // Several effects: the steps of the forward selection, each with its gain over the model
    // before it; one effect: its explanation.
    // Analysis text is ASCII (um, degC, as in the CLI and JSON); on screen µm and °C.
    auto text = [](const std::string &s) { return UnitLabels::inText(QString::fromStdString(s)); };
    QString what = text(r.explanation).toHtmlEscaped();
    if (r.steps.size() > 1) {
        what = tr("several effects, accepted one after another:") + QStringLiteral("<ol>");
        for (const DiagnosisStep &s : r.steps)
            what += tr("<li><b>%1</b>: held-out RMS %2 → %3 µm (%4 % better than the model before it) — %5</li>")
                        .arg(QString::fromStdString(s.effect))
                        .arg(s.heldoutBefore_um, 0, 'f', 2)
                        .arg(s.heldoutAfter_um, 0, 'f', 2)
                        .arg(100.0 * s.heldoutImprovement, 0, 'f', 0)
                        .arg(text(s.explanation).toHtmlEscaped());
        what += QStringLiteral("</ol>");
    }
    m_resultText = (tr("<b>%1</b> — %2<br>Held-out RMS %3 µm → %4 µm (%5 s).<br>%6")
                          .arg(QString::fromStdString(r.effect), what)
                          .arg(r.baseline.heldoutRms_um, 0, 'f', 2)
                          .arg(r.corrected.heldoutRms_um, 0, 'f', 2)
                          .arg(r.wallTime_s, 0, 'f', 1)
                          .arg(text(r.location.summary).toHtmlEscaped()));
    // The switches the diagnosis ran with, as the engine recorded them (stored with the answer).
    m_resultText += tr("<br>Options: %1.").arg(DiagnosisSwitchLabels::summary(r.switches).toHtmlEscaped());
    if (r.advice.given) {
        // Which added measurement would decide (issue 36 item 5): the summary and the ranking.
        QString tests;
        for (const ProposedTestEvidence &t : r.advice.tests)
            tests += tr("<li><b>%1</b>: expected χ² %2 (z %3), difference up to %4 %5, expected held-out gain %6 % — %7</li>")
                         .arg(QString::fromStdString(t.code))
                         .arg(t.expectedChi2, 0, 'f', 1)
                         .arg(t.expectedZ, 0, 'f', 1)
                         .arg(t.maxDifference, 0, 'f', 2)
                         .arg(text(t.unit))
                         .arg(100.0 * t.expectedHeldoutGain, 0, 'f', 0)
                         .arg(text(t.description).toHtmlEscaped());
        m_resultText += tr("<br><b>Which test would decide</b> (%1): %2<ol>%3</ol>")
                            .arg(text(r.advice.trigger).toHtmlEscaped(), text(r.advice.summary).toHtmlEscaped(), tests);
    }
    updateHeading();
    m_candidates->setRowCount(static_cast<int>(r.candidates.size()));
    for (int i = 0; i < static_cast<int>(r.candidates.size()); ++i) {
        const CandidateOutcome &c = r.candidates[static_cast<size_t>(i)];
        QStringList reasons;
        for (const std::string &s : c.reasons)
            reasons << text(s);
        m_candidates->setItem(i, 0, new QTableWidgetItem(QString::fromStdString(c.effect)));
        m_candidates->setItem(i, 1, new QTableWidgetItem(c.accepted ? tr("yes") : (c.applicable ? tr("no") : tr("n/a"))));
        m_candidates->setItem(i, 2, new QTableWidgetItem(QString::number(c.score, 'f', 3)));
        m_candidates->setItem(i, 3, new QTableWidgetItem(c.applicable ? QString::number(c.evaluation.heldoutRms_um, 'f', 2) : QString()));
        m_candidates->setItem(i, 4, new QTableWidgetItem(c.applicable ? QString::number(c.deltaIc, 'f', 1) : QString()));
        auto *why = new QTableWidgetItem(c.applicable ? reasons.join(QStringLiteral("; ")) : text(c.notApplicableReason));
        why->setToolTip(text(c.explanation));
        m_candidates->setItem(i, 5, why);
    }
    m_candidates->resizeColumnsToContents();
    std::vector<double> x, y, z;
    const QString noMap = tr("The validation session has fewer than two interferometer runs (or targets) besides the "
                             "reference: no residual map. The answer and the candidates' evidence stand.");
    residualGrid(r.predictions, false, x, y, z);
    if (x.size() >= 2 && y.size() >= 2)
        m_before->setGrid(x, y, z);
    else
        m_before->showEmpty(noMap);
    residualGrid(r.predictions, true, x, y, z);
    if (x.size() >= 2 && y.size() >= 2)
        m_after->setGrid(x, y, z);
    else
        m_after->showEmpty(noMap);
    for (ErrorSurfacePlot *p : {m_before, m_after})
        p->setAxisTitle(QwtPlot::yRight, tr("residual (µm)"));
    m_stage->setText(tr("done"));
    emit finished(true);
}

} // namespace driftlab

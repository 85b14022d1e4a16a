#include "SessionDiagnosis.h"

#include "AnalysisResultKind.h"
#include "CandidateEffect.h"
#include "DiagnosisResultJson.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"

#include <QStringList>

#include <algorithm>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message) { throw std::invalid_argument(message.toStdString()); }

DiagnosisRecording load(const SessionStore &store, qint64 id, const QString &what, const QString &label, QString &note)
{
    DiagnosisRecording out;
    QString read;
    try {
        out = SessionAnalysis(store, id).diagnosisRecording(&read);
    } catch (const std::exception &e) {
        bad(QStringLiteral("%1 '%2': %3").arg(what, label, QString::fromUtf8(e.what())));
    }
    if (out.screw.interferometer.empty())
        bad(QStringLiteral("%1 '%2': no interferometer runs besides the reference run (the diagnosis needs thermal errors)")
                .arg(what, label));
    QStringList roles;
    for (const auto &c : out.channelsByRole)
        roles << QString::fromStdString(c.first);
    note = QStringLiteral("%1; auxiliary roles: %2").arg(read, roles.join(QStringLiteral(", ")));
    return out;
}

} // namespace

void SessionDiagnosis::check(const DiagnosisRequest &request)
{
    if (!(request.dt_s > 0) || request.dt_s > 600)
        bad(QStringLiteral("--dt must be a time step in (0, 600] s, got %1").arg(request.dt_s));
    const std::vector<std::string> known = CandidateEffectLibrary::grammarCodes();
    for (const std::string &e : request.effects)
        if (std::find(known.begin(), known.end(), e) == known.end())
            bad(QStringLiteral("--effects: unknown effect '%1'").arg(QString::fromStdString(e)));
}

SessionDiagnosis::SessionDiagnosis(const SessionStore &store, const DiagnosisRequest &request)
    : SessionDiagnosis(store, request, store)
{
}

SessionDiagnosis::SessionDiagnosis(const SessionStore &trainStore, const DiagnosisRequest &request,
                                   const SessionStore &validateStore)
    : m_request(request)
{
    if (m_request.trainLabel.isEmpty())
        m_request.trainLabel = QString::number(request.train);
    if (m_request.validateLabel.isEmpty())
        m_request.validateLabel = QString::number(request.validate);
    check(request);
    const SessionInfo a = trainStore.session(request.train), b = validateStore.session(request.validate);
    if (a.uuid == b.uuid || (!a.contentSha256.isEmpty() && a.contentSha256 == b.contentSha256))
        bad(QStringLiteral("--train '%1' and --validate '%2' are the same recording (session UUID %3): "
                           "held-out numbers need a recording that was not fitted")
                .arg(m_request.trainLabel, m_request.validateLabel, a.uuid));
    m_train = load(trainStore, request.train, QStringLiteral("--train"), m_request.trainLabel, m_trainNote);
    m_validate = load(validateStore, request.validate, QStringLiteral("--validate"), m_request.validateLabel, m_validateNote);

    // The one set of diagnosis settings of both faces.
    const SessionAnalysis first(trainStore, request.train);
    m_geometry = first.geometry();
    m_options.fitScrewTemperatures = request.fitScrewTemperatures;
    m_options.effects = request.effects;
    m_options.priors = request.priors;
    m_options.checkMeasurementChain = request.checkMeasurementChain;
    m_options.tryTriples = request.tryTriples;
    m_options.housingContactBaseline = request.housingContact;
    m_options.identification.simulator.grid.dt_s = request.dt_s;
    m_options.identification.simulator.driveSample_s = 1.0;
    m_options.identification.maxIterations = 60;
    m_options.identification.initial = first.defaultParameters();
}

void SessionDiagnosis::checkWritable(const SessionStore &store)
{
    if (store.isReadOnly())
        bad(QStringLiteral("%1 is read-only: the diagnosis is stored with the training session (open a writable copy)")
                .arg(store.path()));
}

DiagnosisReport SessionDiagnosis::run(const Progress &progress) const
{
    DiagnosisEngine engine(m_geometry, m_options);
    return engine.run(m_train, m_validate, progress);
}

qint64 SessionDiagnosis::store(SessionStore &store, const DiagnosisReport &report) const
{
    if (report.cancelled)
        throw std::logic_error("SessionDiagnosis::store: a cancelled diagnosis is not stored");
    return store.addAnalysisResult(m_request.train, AnalysisResultKind::diagnosis(),
                                   DiagnosisResultJson::storedResult(report, m_request.validateLabel));
}

} // namespace driftlab

#include "ScrewModelFit.h"

#include "FdmModelJson.h"
#include "ParameterPlausibility.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"
#include "StoreTransaction.h"

#include <algorithm>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message) { throw std::invalid_argument(message.toStdString()); }

bool hasSession(const SessionStore &store, qint64 id)
{
    const QVector<SessionInfo> all = store.sessions();
    return std::any_of(all.begin(), all.end(), [id](const SessionInfo &s) { return s.id == id; });
}

} // namespace

ScrewModelFit::ScrewModelFit(SessionStore &store) : m_store(store) {}

void ScrewModelFit::check(const SessionStore &store, const ScrewFitRequest &q)
{
    if (q.sessions.empty())
        bad(QStringLiteral("name at least one session to fit"));
    if (store.isReadOnly())
        bad(QStringLiteral("%1 is read-only: the fitted model is stored with its sessions (open a writable copy)").arg(store.path()));
    if (!(q.dt_s > 0) || q.dt_s > 600)
        bad(QStringLiteral("--dt must be a time step in (0, 600] s, got %1").arg(q.dt_s));
    for (qint64 id : q.sessions)
        if (!hasSession(store, id))
            bad(QStringLiteral("%1 has no session %2").arg(store.path()).arg(id));
    if (q.holdout != 0 && !hasSession(store, q.holdout))
        bad(QStringLiteral("--holdout: %1 has no session %2").arg(store.path()).arg(q.holdout));
    if (q.holdout != 0 && std::find(q.sessions.begin(), q.sessions.end(), q.holdout) != q.sessions.end())
        bad(QStringLiteral("--holdout %1 is also a fitted session: a held-out session must not be fitted").arg(q.holdout));
}

ScrewFitResult ScrewModelFit::run(const ScrewFitRequest &q, const Progress &progress, const Notes &notes) const
{
    check(m_store, q);
    const auto note = [&notes](const QString &line) {
        if (notes)
            notes(line);
    };
    ScrewFitResult out;
    out.sessions = q.sessions;
    out.holdout = q.holdout;
    std::vector<ScrewRecording> recordings;
    for (qint64 id : q.sessions) {
        QString text;
        recordings.push_back(SessionAnalysis(m_store, id).recording(&text));
        out.interferometer = out.interferometer || !recordings.back().interferometer.empty();
        note(QStringLiteral("session %1: %2").arg(id).arg(text));
    }
    const SessionAnalysis first(m_store, q.sessions.front());
    out.geometry = first.geometry();
    IdentificationOptions options;
    options.simulator.grid.dt_s = q.dt_s;
    options.initial = first.defaultParameters(); // Table 3 (X) start, P_f from the machine block
    options.fitFixedEnd = !q.holdFixedEnd;
    if (!out.interferometer) {
        options.fitFixedEnd = false;
        note(QStringLiteral("no interferometer runs in the fitted sessions: fitting on the screw_elongation channel alone; "
                            "P_f (which only the positioning error reveals) is held at %1 mm from the machine block")
                 .arg(options.initial.fixedEndPosition_mm));
    }
    std::vector<ScrewRecording> held;
    if (q.holdout != 0) {
        QString text;
        held.push_back(SessionAnalysis(m_store, q.holdout).recording(&text));
        note(QStringLiteral("held-out session %1: %2").arg(q.holdout).arg(text));
    }
    note(QStringLiteral("fitting k1, k2, lambda%1 (k3, k4 by linear least squares)...")
             .arg(options.fitFixedEnd ? QStringLiteral(", P_f") : QString()));
    out.options = options;
    options.progress = progress;
    ScrewModelIdentifier identifier(out.geometry, options);
    out.identification = identifier.fit(recordings);
    if (!held.empty()) {
        out.validation = identifier.predict(out.identification, held);
        out.hasValidation = true;
    }
    out.implausible = ParameterPlausibility::implausible(out.identification, out.options, first.drawingFixedEnd_mm());
    out.poorlyIdentified = ParameterPlausibility::poorlyIdentified(out.identification);
    out.feedNote = QString::fromStdString(ParameterPlausibility::feedCoverageNote(recordings));
    out.document = FdmModelJson::document(out);
    out.stored = FdmModelJson::storedModel(out.document);

    StoreTransaction transaction(m_store); // one model row per fitted session, all or none (a kill in between leaves none)
    for (qint64 id : q.sessions)
        m_store.addFittedModel(id, out.stored);
    transaction.commit();
    return out;
}

} // namespace driftlab

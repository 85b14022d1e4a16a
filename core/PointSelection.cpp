#include "PointSelection.h"

#include "FitRequestCheck.h"

#include "AnalysisResultKind.h"
#include "DataDrivenSelection.h"
#include "SessionStore.h"

#include <QJsonArray>

#include <stdexcept>

namespace driftlab {

namespace {
[[noreturn]] void bad(const QString &message)
{
    throw std::invalid_argument(message.toStdString());
}
} // namespace

PointSelection::PointSelection(SessionStore &store) : m_store(store) {}

void PointSelection::check(const SessionStore &store, const PointSelectionRequest &q)
{
    if (q.sessions.isEmpty() || q.sessions.contains(0))
        bad(QStringLiteral("give at least one SESSION"));
    for (int i = 0; i < q.sessions.size(); ++i)
        if (q.sessions.indexOf(q.sessions[i]) != i)
            bad(QStringLiteral("session %1 is given twice").arg(q.sessions[i]));
    if (q.target.trimmed().isEmpty())
        bad(QStringLiteral("--target: give a displacement channel"));
    if (q.kMin < 2 || q.kMax < q.kMin || q.kMax > 64)
        bad(QStringLiteral("--k-range must be K_MIN:K_MAX with 2 <= K_MIN <= K_MAX <= 64, got '%1:%2'").arg(q.kMin).arg(q.kMax));
    // The target and the range are checked as fit checks them, before any sample is read.
    for (qint64 id : q.sessions) {
        FitRequestCheck::checkTarget(store, id, q.target);
        FitRequestCheck::checkRange(store, id, q.hours, QStringLiteral("--range"));
    }
    if (store.isReadOnly())
        bad(QStringLiteral("%1 is read-only: the selection could not be stored").arg(store.path()));
}

QJsonObject PointSelection::record(const SelectionResult &selection, const QList<qint64> &sessions)
{
    QJsonObject o = DataDrivenFit::selectionJson(selection);
    o.insert(QStringLiteral("session"), sessions.value(0));
    QJsonArray ids;
    for (qint64 id : sessions)
        ids.append(id);
    o.insert(QStringLiteral("sessions"), ids);
    return o;
}

PointSelection::Result PointSelection::run(const PointSelectionRequest &q, const Progress &progress) const
{
    check(m_store, q);
    Result r;
    r.selection = DataDrivenSelection(m_store).select(q.sessions, q.target, q.hours, q.kMin, q.kMax, q.channels, progress);
    r.session = q.sessions.front();
    r.record = record(r.selection, q.sessions);
    m_store.addAnalysisResult(r.session, AnalysisResultKind::sensitivePoints(), r.record);
    return r;
}

} // namespace driftlab

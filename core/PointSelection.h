#pragma once
// Sensitive-point selection (seed 003 Algorithm 1: z-scored rises, K-means for every K in the
// range, K by silhouette, in each cluster the channel with the highest grey relational grade)
// as one use case, run the same way by `driftlab-cli select-points` and the GUI's Analysis
// workspace: checks the request, selects (DataDrivenSelection), and stores the record with the
// first session as AnalysisResultKind::sensitivePoints() (the same bytes whichever face ran it).
//
// A request that cannot run (no session, a session given twice, no target, a K range outside
// 2 <= min <= max <= 64, a read-only store, a session or channel the store lacks) throws
// std::invalid_argument naming the option before any work; a cancelled selection (progress
// returned false) throws std::runtime_error("cancelled") and stores nothing.
// A SessionStore belongs to the thread that opened it: run() on the thread of `store`.

#include "DataDrivenFit.h"
#include "PointSelectionRequest.h"

#include <QJsonObject>

namespace driftlab {

class SessionStore;

class PointSelection {
public:
    using Progress = DataDrivenFit::Progress; // fraction 0..1 and stage; return false to cancel

    struct Result {
        SelectionResult selection;
        QJsonObject record; // what was stored
        qint64 session = 0; // stored with this session
    };

    explicit PointSelection(SessionStore &store);

    static void check(const SessionStore &store, const PointSelectionRequest &request);
    // The stored record: DataDrivenFit::selectionJson plus "session" and "sessions".
    static QJsonObject record(const SelectionResult &selection, const QList<qint64> &sessions);
    Result run(const PointSelectionRequest &request, const Progress &progress = {}) const;

private:
    SessionStore &m_store;
};

} // namespace driftlab

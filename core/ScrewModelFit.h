#pragma once
// The seed-000 screw-model fit as one use case, run the same way by `driftlab-cli fit
// --model fdm` and the GUI's Models workspace: reads the sessions (drive channels by role,
// interferometer thermal errors, screw-end probe), identifies k1..k4, lambda and P_f with
// ScrewModelIdentifier, predicts a held-out session, judges the parameters
// (ParameterPlausibility), and stores the fitted model with every fitted session in one
// transaction (FdmModelJson's record: the same bytes whichever face ran it).
//
// Bad requests (no session, a read-only store, a session the store lacks, a held-out session that is also
// fitted, a time step outside (0, 600] s) throw std::invalid_argument naming the option
// before any work; a cancelled fit throws IdentificationCancelled and stores nothing.
// A SessionStore belongs to the thread that opened it: run() on the thread of `store`.

#include "ScrewFitTypes.h"

#include <QString>

#include <functional>

namespace driftlab {

class SessionStore;

class ScrewModelFit {
public:
    // Solver iterations (from the fitting thread); return false to cancel.
    using Progress = std::function<bool(int iteration, double cost)>;
    // What was read and decided, one line each (sessions used, P_f held, ...).
    using Notes = std::function<void(const QString &line)>;

    explicit ScrewModelFit(SessionStore &store);

    // Throws std::invalid_argument for a request that cannot run (see above).
    static void check(const SessionStore &store, const ScrewFitRequest &request);
    // Reads, fits, predicts the held-out session, stores; returns what was stored.
    ScrewFitResult run(const ScrewFitRequest &request, const Progress &progress = {}, const Notes &notes = {}) const;

private:
    SessionStore &m_store;
};

} // namespace driftlab

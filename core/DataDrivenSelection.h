#pragma once
// Sensitive-point selection (seed 003, Algorithm 1; SensitivePointSelector) on stored
// sessions: one session's samples in a range, or several sessions' one after another with every
// temperature as a rise from its session's start (SignalTable::concatenate). Bad requests throw
// std::invalid_argument naming the option, session or channel.

#include "DataDrivenFit.h"

namespace driftlab {

class SessionStore;

class DataDrivenSelection {
public:
    explicit DataDrivenSelection(const SessionStore &store);

    SelectionResult select(const QList<qint64> &sessions, const QString &target, const HourRange &range, int kMin, int kMax,
                           const QStringList &channels = {}, const DataDrivenFit::Progress &progress = {}) const;
    // The select-points JSON (docs/datadriven.md).
    static QJsonObject json(const SelectionResult &selection);

private:
    const SessionStore &m_store;
};

} // namespace driftlab

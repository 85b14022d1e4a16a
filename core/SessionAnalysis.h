#pragma once
// Bridges a stored session to analysis/: reads the channels the seed-000 model needs
// by their role (axis_position, feed_rate, ambient, screw_elongation) and the screw
// description from the session's machine block, and runs the model against them.

#include "FdmSimulation.h"
#include "DiagnosisTypes.h"
#include "IdentificationTypes.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>

namespace driftlab {

class SessionStore;

struct ElongationCheck {
    ElongationComparison comparison;
    FdmParameters parameters;
    ScrewGeometry geometry;
    double duration_s = 0.0;
};

class SessionAnalysis {
public:
    SessionAnalysis(const SessionStore &store, qint64 sessionId);

    // Screw geometry from the machine block (missing keys keep the Table-1 defaults).
    ScrewGeometry geometry() const;
    // Model parameters: Table 3 (X) with P_f from the machine block when present.
    FdmParameters defaultParameters() const;
    // The drawing's P_f (machine block fixed_end_position_mm), NaN when the block has none.
    double drawingFixedEnd_mm() const;
    // Throws std::runtime_error naming the missing role if a needed channel is absent.
    ScrewDrive drive() const;
    // The session as an identification recording: drive channels by role, thermal errors
    // from the interferometer runs (deviation minus the reference run's at the same target
    // and direction), the screw_elongation channel if present (relative to its first
    // sample). `note` receives what was used. Throws std::runtime_error for a missing drive channel.
    ScrewRecording recording(QString *note = nullptr) const;
    // The interferometer thermal errors alone (no drive channels needed); empty without runs.
    std::vector<PositioningErrorPoint> interferometerErrors(int *referenceRun = nullptr) const;
    // recording() plus every temperature channel by role (the candidates' drivers) and the
    // drawing's P_f from the machine block: the input of the mismatch diagnosis.
    DiagnosisRecording diagnosisRecording(QString *note = nullptr) const;
    TimeSeries channelByRole(const QString &role) const;

    // Runs the model with `parameters` over the session and compares with the probe.
    ElongationCheck checkElongation(const FdmParameters &parameters) const;
    // The model's free-end elongation (um) at the probe's times, from cold at the first drive
    // time (the series checkElongation compares); `probe` receives the screw_elongation channel.
    // Throws std::runtime_error for a missing drive or probe channel.
    std::vector<double> predictedElongation(const FdmParameters &parameters, TimeSeries &probe) const;
    static QJsonObject toJson(const ElongationCheck &check);

private:
    // Table 1's dt (0.1 s), shortened where the parameters (e.g. a fitted large lambda) need it
    // for the explicit scheme to stay stable at the drive's fastest feed.
    static FdmSettings stableSettings(const ScrewGeometry &geometry, const FdmParameters &parameters, const ScrewDrive &drive);

    const SessionStore &m_store;
    qint64 m_sessionId;
    SessionInfo m_info;
    QVector<ChannelInfo> m_channels;
};

} // namespace driftlab

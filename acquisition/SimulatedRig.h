#pragma once
// First simulated test rig: a fixed-free ball-screw feed axis driven by a feed
// programme, with PT100 channels, an eddy-current probe on the screw end and the
// CNC's position and feed. For now its screw physics is the seed-000 model itself;
// the acquisition issue replaces it with an independent truth model.

#include "FdmScrewModel.h"
#include "FeedProgram.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QVector>

#include <memory>
#include <random>

namespace driftlab {

struct RigConfig {
    ScrewGeometry screw;
    FdmParameters truth;            // the rig's physics parameters
    FeedProgram program = FeedProgram::seed000Table2(6000.0);
    double travelLow_mm = 0.0;
    double travelHigh_mm = 600.0;
    double ambientMean_C = 20.0;
    double ambientDriftAmplitude_K = 0.3;  // slow sinusoidal drift
    double ambientDriftPeriod_s = 4 * 3600.0;
    double temperatureNoise_K = 0.02;      // PT100 noise (before 0.01 K quantisation)
    double probeNoise_um = 0.1;            // eddy-current probe noise
    double slowRate_Hz = 1.0;              // temperatures and probe
    double fastRate_Hz = 10.0;             // CNC position and feed
    unsigned seed = 1;
};

class SimulatedRig {
public:
    explicit SimulatedRig(const RigConfig &config);

    // Channel descriptions in the order of the blocks advance() fills.
    const QVector<ChannelInfo> &channels() const { return m_channels; }
    // Manifest-style machine description (screw, fixed_end_position_mm, travel_mm).
    QJsonObject machineDescription() const;
    double time_s() const { return m_time; }
    // Simulates up to `until_s` and appends the samples acquired to blocks[i] for channel i.
    void advance(double until_s, QVector<SampleBlock> &blocks);

    // Noise-free truth for tests: screw-end elongation now (um), ambient at t.
    double trueElongation_um() const { return m_screw.elongation_um(); }
    double ambientAt(double t) const;

private:
    double quantised(double value, double step) const;
    void sampleSlow(double t, QVector<SampleBlock> &blocks);
    void sampleFast(double t, QVector<SampleBlock> &blocks);

    RigConfig m_config;
    FdmScrewModel m_screw;
    QVector<ChannelInfo> m_channels;
    std::mt19937 m_rng;
    std::normal_distribution<double> m_unitNormal{0.0, 1.0};
    double m_time = 0.0;
    long long m_steps = 0;
    double m_nextSlow = 0.0;
    double m_nextFast = 0.0;
    double m_bearingHousing_C = 20.0; // lumped housing nodes, first-order lag
    double m_nutHousing_C = 20.0;
};

} // namespace driftlab

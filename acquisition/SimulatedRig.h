#pragma once
// The simulated test rig: one truth model (ScrewTruthModel, independent of analysis/)
// driven by a feed programme, a drifting ambient and an optional coolant circuit, and
// the instruments observing it: PT100 channels (noise, 0.01 K quantisation, dropouts
// as missing samples), an eddy-current probe on the screw's free end, the CNC's axis
// position and feed, a laser interferometer making runs at programmed targets (cold
// reference run first, fixed geometric pitch error, noise) and an infrared camera.
//
// Axis sign (seed 000 eq. 15/16): the nut sits d = |X - P_f| from the fixed end; a
// positive thermal expansion gives a positive positioning error when P_f lies below
// the travel and a negative one when it lies above. Structure effects add
// c_off dT_bed and c_lin dT_bed (X - X_ref) to every positioning deviation.

#include "InfraredRenderer.h"
#include "OffsetRegisterMap.h"
#include "RigConfig.h"
#include "StorageTypes.h"
#include "ScrewTruthModel.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QVector>

#include <random>

namespace driftlab {

class SimulatedRig {
public:
    // Throws std::invalid_argument for an inconsistent configuration.
    explicit SimulatedRig(const RigConfig &config);

    const RigConfig &config() const { return m_config; }
    // The recording ends at end_s: no interferometer run is started that cannot finish by then.
    void setRecordingEnd_s(double end_s) { m_config.recordingEnd_s = end_s; }
    // Scalar channels in the order of the blocks advance() fills: PT100s, probe, X, F.
    const QVector<ChannelInfo> &channels() const { return m_channels; }
    // Manifest-style machine description (screw, fixed_end_position_mm, travel_mm).
    QJsonObject machineDescription() const;
    // Manifest-style "infrared" block (screw line, width, scale/offset).
    QJsonObject infraredDescription() const;
    double time_s() const { return m_time; }        // model time (multiple of screw.dt_s)
    double sampledUntil_s() const { return m_sampled_s; } // instruments have delivered up to here

    // Simulates up to `until_s` and appends the scalar samples acquired to blocks[i].
    void advance(double until_s, QVector<SampleBlock> &blocks);
    // Non-scalar records acquired so far (moved out, so memory stays flat).
    QVector<InterferometerPoint> takeInterferometerPoints();
    QVector<IrFrame> takeIrFrames();
    QVector<EventRecord> takeEvents();

    // Noise-free truth for tests.
    const ScrewTruthModel &truth() const { return m_model; }
    double trueElongation_um() const { return m_model.elongation_um(); }
    double trueFixedEnd_mm() const { return m_fixedEndTrue_mm; }
    double axisSign() const { return m_sign; }
    double nutDistance_m(double axis_mm) const;
    // Positioning deviation now at X relative to the initial state (no pitch error, no noise).
    double trueThermalError_um(double axis_mm) const;
    double ambient_C() const { return m_ambient_C; }
    double coolant_C(double t_s) const;
    double bedRise_K() const { return m_model.nodeTemperature_C(ScrewTruthModel::Bed) - m_bed0_C; }
    double pitchError_um(double axis_mm) const;
    // External offsets applied to the axis (a compensation loop writing to the CNC): one value
    // per entry of `map` (entries of other axes are ignored; support points are interpolated
    // at the position, OffsetRegisterMap::offsetAt). The axis stands that far beyond its
    // commanded position, so every interferometer reading from now on adds it; the CNC's
    // position channel keeps the commanded position.
    void setAxisOffsets(const OffsetRegisterMap &map, const QVector<double> &entryOffsets_um);
    double axisOffsetAt_um(double axis_mm) const;

private:
    void sampleDue(double t, QVector<SampleBlock> &blocks);
    void stepModel(double dt);
    double ambientTarget(double t) const;

    RigConfig m_config;
    ScrewTruthModel m_model;
    InfraredRenderer m_ir;
    QVector<ChannelInfo> m_channels;
    std::mt19937 m_rngSensors, m_rngAmbient, m_rngIr, m_rngLaser;
    std::normal_distribution<double> m_unit{0.0, 1.0};
    std::uniform_real_distribution<double> m_uniform{0.0, 1.0};
    double m_fixedEndTrue_mm = 0.0;
    double m_sign = 1.0;
    double m_time = 0.0;
    long long m_steps = 0;
    double m_sampled_s = 0.0;
    double m_walk_K = 0.0;
    double m_unitRise_K = 0.0; // neighbouring unit above ambient
    double m_ambient_C = 20.0;
    OffsetRegisterMap m_offsetMap;
    QVector<double> m_entryOffsets_um; // empty: no offset applied
    double m_bed0_C = 20.0;
    QVector<double> m_nextPt100;
    QVector<int> m_dropoutLeft;
    double m_nextProbe = 0.0;
    double m_nextCnc = 0.0;
    double m_nextIr = 0.0;
    int m_nextRun = 0;
    int m_nextTarget = 0;
    QVector<double> m_targets;
    double m_pitchSlope = 0.0;
    double m_pitchAmp[3] = {0, 0, 0};
    double m_pitchPhase[3] = {0, 0, 0};
    int m_lastPhase = -2;
    QVector<InterferometerPoint> m_laser;
    QVector<IrFrame> m_frames;
    QVector<EventRecord> m_events;
    std::vector<double> m_nutSamples;
};

} // namespace driftlab

#pragma once
// Where a live compensation loop writes each axis's thermal offset on a controller: a pair of
// 16-bit holding registers per axis holding the offset as a signed 32-bit integer in steps of
// `resolution_um`, with a sign and a word order. The Mitsubishi M80 scheme of seed 003 is the
// preset "m80" (X R5700/R5701, Y R5702/R5703, Z R5704/R5705, 1 um steps, low word first;
// docs/export.md). fromJson() reads a map file or a rig/loop settings object; errors name the
// field (overlapping registers, a non-positive resolution, an unknown axis).
// A live compensation table: an axis may be mapped several times, each entry a support point
// with its "position_mm"; the controller interpolates the offset linearly between the support
// points at the axis's actual position (constant beyond the outer ones), so a
// position-dependent thermal error is compensated wherever the axis stands.

#include "JsonFields.h"

#include <QString>
#include <QVector>

#include <functional>
#include <limits>

namespace driftlab {

class OffsetRegisterMap {
public:
    struct Axis {
        QString name;     // "X", "Y", "Z", ...
        int address = 0;  // first register of the pair (0-based PDU address)
        double position_mm = std::numeric_limits<double>::quiet_NaN(); // support point; NaN: one offset
        bool isSupportPoint() const { return position_mm == position_mm; }
        QString label() const; // "X", or "X@104 mm" for a support point
    };
    QString preset;            // "m80", or empty for a map given register by register
    QVector<Axis> axes;
    int unitId = 1;
    double resolution_um = 1.0; // one count of the register pair
    int sign = 1;               // +1: the register holds the offset; -1: its negation
    bool lowWordFirst = true;

    static QStringList presetNames();
    static OffsetRegisterMap fromPreset(const QString &name); // throws std::invalid_argument
    // {"preset": "m80"} with optional overrides, or {"axes": [{"axis": "X", "address": 5700}],
    //  "unit_id", "resolution_um", "sign", "word_order": "low-first"|"high-first"}.
    static OffsetRegisterMap fromJson(JsonFields &f);
    static OffsetRegisterMap fromFile(const QString &path); // a map file; errors name it

    int axisIndex(const QString &name) const; // first entry of the axis, -1 if not mapped
    QVector<int> entriesOf(const QString &name) const; // every entry of the axis, in map order
    // What a loop requests for every entry (NaN: hold): for the entries of `name`, `here` (the
    // offset at the axis's current position) or, at a support point, offsetAt(its position).
    QVector<double> requests(const QString &name, double here, const std::function<double(double)> &offsetAt) const;
    // The offset a controller applies at `position_mm` from each entry's offset (interpolated
    // between the support points of `name`; one entry without a position: that offset).
    double offsetAt(const QString &name, double position_mm, const QVector<double> &entryOffsets_um) const;
    // The register pair for an offset in um: rounded to the resolution, signed 32-bit, in the
    // map's word order. Throws std::out_of_range beyond 32 bits.
    QVector<quint16> words(double offset_um) const;
    // The offset the controller applies for a register pair (the inverse of words()).
    double offsetOf(quint16 first, quint16 second) const;
    // Offsets rounded to what the registers can hold.
    double quantised(double offset_um) const;
};

} // namespace driftlab

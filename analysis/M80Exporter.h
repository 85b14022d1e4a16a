#pragma once
// Mitsubishi M80 as seed 003 compensates it: the PC writes the thermal offset of each axis in
// 1 um steps into a pair of 16-bit R registers (X R5700/R5701, Y R5702/R5703, Z R5704/R5705,
// low word first), which the ladder adds to the axis. The export writes that register map and
// the register contents over the temperature and position grid (what the live loop writes):
// rounding to 1 um is the approximation error.

#include "ModelExporter.h"

#include <cstdint>

namespace driftlab {

class M80Exporter : public ModelExporter {
public:
    std::string name() const override { return "m80"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;
    // First (low-word) register of the axis: 5700, 5702, 5704 for X, Y, Z.
    static int lowRegister(const std::string &axis);
    // A value in 1 um steps as the two 16-bit words (low, high) of a signed 32-bit integer.
    static void split(std::int32_t value, std::uint16_t &low, std::uint16_t &high);
};

} // namespace driftlab

#pragma once
// LinuxCNC: a screw-compensation COMP_FILE for the joint of the axis in both formats of the
// INI reference ([JOINT_n] COMP_FILE / COMP_FILE_TYPE: type 0 = nominal, forward and reverse
// positions actually reached; type 1 = nominal, forward and reverse trim), which LinuxCNC
// interpolates linearly between the rows, at one temperature; and the INI / HAL settings for
// external offsets ([AXIS_L] OFFSET_AV_RATIO, axis.L.eoffset-enable / -scale / -counts, one
// count = 1 um) through which a live loop adds the temperature-dependent part. The COMP_FILE
// is fixed at its temperature: the approximation error is how far the model moves over the
// temperature grid from that table.

#include "ModelExporter.h"

namespace driftlab {

class LinuxCncExporter : public ModelExporter {
public:
    std::string name() const override { return "linuxcnc"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;
};

} // namespace driftlab

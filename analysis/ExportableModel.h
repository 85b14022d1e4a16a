#pragma once
// A fitted model as the exporters see it (standard library only): either the seed-000 FDM
// screw model ("fdm-seed000" MODEL.json from 'fit --model fdm --json') or a data-driven model
// ("driftlab-model" v1). core/ExportableModelJson reads both.

#include "DataDrivenModel.h"
#include "ScrewModelTypes.h"

#include <string>

namespace driftlab {

struct ExportableModel {
    bool physics = false;      // true: fdm-seed000 (geometry, parameters, grid); false: dataDriven
    ScrewGeometry geometry;
    FdmParameters parameters;
    FdmSettings grid;          // explicit-scheme grid of the exported physics model
    DataDrivenModel dataDriven;
    std::string source;        // file name, for headers and messages

    std::string kind() const { return physics ? std::string("fdm-seed000") : dataDriven.kind; }
};

} // namespace driftlab

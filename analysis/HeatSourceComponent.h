#pragma once
// A heat input of the screw model as a separately coded, parameterised component. Its
// heat is amplitude x unit heat: the temperature field is linear in the amplitudes, so the
// identification solves them by linear least squares (variable projection) and only the
// component's nonlinear parameters (if any) enter the nonlinear search.
//
// To add a physical effect (motor heat into the fixed end, free-end bearing, nonlinear
// feed law, lagged heat path, coolant...) derive from this class, describe the amplitude
// and any nonlinear parameters, and distribute the unit heat over the cells in
// addUnitHeat(). See BearingHeatSource and NutHeatSource for the seed-000 terms.

#include "IdentificationTypes.h"
#include "ScrewCellLayout.h"

#include <memory>
#include <string>
#include <vector>

namespace driftlab {

// What happened during one time step of the simulation (all averages over the step).
struct HeatStepInput {
    double dt_s = 0.0;
    double meanFeed_mm_min = 0.0;          // mean |v|
    const double *nutOccupancy = nullptr;  // per cell: fraction of the step under the nut
    const double *nutFeed = nullptr;       // per cell: mean of |v| while under the nut (|v| x occupancy)
    const double *fineFeed_mm_min = nullptr; // |v| at the drive samples inside the step
    int fineCount = 0;
    double ambientDeviation_K = 0.0;       // mean T_a - T_a(start) over the step
    const ScrewCellLayout *layout = nullptr;
    const ScrewGeometry *geometry = nullptr;
};

class HeatSourceComponent {
public:
    virtual ~HeatSourceComponent() = default;
    // A copy with the same parameters (the simulator runs recordings on parallel threads,
    // each with its own copies, so stateful components stay thread-confined).
    virtual std::shared_ptr<HeatSourceComponent> clone() const = 0;
    // Amplitude description (name, unit, bounds, initial guess for reporting).
    virtual ParameterSpec amplitude() const = 0;
    // Nonlinear parameters of the component (default: none).
    virtual std::vector<ParameterSpec> nonlinearParameters() const { return {}; }
    virtual void setNonlinearParameters(const double * /*values*/) {}
    // Called before the first step of each recording (reset lag states).
    virtual void beginRecording() {}
    // Adds the mean heat flow (W) into each cell over the step for amplitude 1.
    virtual void addUnitHeat(const HeatStepInput &step, double *watts) = 0;
    // Adds a conductance (W/K) from each cell to the ambient over the step: a contact through
    // which the screw also gives heat back, -G (T_cell - T_a). Set by the nonlinear parameters,
    // independent of the amplitude, so the field stays linear in the amplitudes. Called before
    // addUnitHeat() in every step. Default: none.
    virtual void addConductance(const HeatStepInput & /*step*/, double * /*wattsPerKelvin*/) const {}
};

} // namespace driftlab

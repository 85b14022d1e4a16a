#pragma once
// Cell layout of the seed-000 screw grid (eq. 4 and the cell ranges of eq. 10): how many
// cells, which lie under the fixed-end bearing, which under the nut for a nut centre.
// Shared by the implicit model and the identification simulator. Standard library only.

#include "ScrewModelTypes.h"

namespace driftlab {

class ScrewCellLayout {
public:
    // Throws std::invalid_argument for a non-positive length or dx.
    ScrewCellLayout(const ScrewGeometry &geometry, const FdmSettings &settings);

    int cellCount() const { return m_cells; }
    int bearingCells() const { return m_bearingCells; }
    double dx_m() const { return m_dx; }
    // eq. (10): (X_N - L_N/2)/dx < n <= (X_N + L_N/2)/dx, 1-based n -> 0-based [first, last];
    // empty when last < first. Same 1e-9 guard as FdmScrewModel::heatedCells.
    void nutCells(double nutCentre_m, int &first, int &last) const;

private:
    int m_cells = 0;
    int m_bearingCells = 0;
    double m_dx = 0.0;
    double m_nutLength = 0.0;
};

} // namespace driftlab

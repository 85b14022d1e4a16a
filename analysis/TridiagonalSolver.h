#pragma once
// Thomas algorithm for a tridiagonal system, factor once, solve several right-hand sides.
// For the diagonally dominant matrices of the implicit heat-conduction schemes (no pivoting).
// Standard library only.

#include <vector>

namespace driftlab {

class TridiagonalSolver {
public:
    // Row i: lower[i] x[i-1] + diag[i] x[i] + upper[i] x[i+1] = rhs[i]; lower[0] and
    // upper[n-1] are ignored. Throws std::invalid_argument on a zero pivot.
    void factor(const double *lower, const double *diag, const double *upper, int n);
    // Solves in place: rhs becomes x. Must follow factor() with the same n.
    void solve(double *rhs) const;
    // Solves `columns` right-hand sides stored interleaved (x[i * columns + c]) in place:
    // the independent recurrences run side by side (instruction-level parallelism).
    void solveInterleaved(double *x, int columns) const;
    int size() const { return m_n; }

private:
    int m_n = 0;
    std::vector<double> m_lower;    // sub-diagonal
    std::vector<double> m_invPivot; // 1 / modified diagonal
    std::vector<double> m_upperMod; // modified super-diagonal c'_i
};

} // namespace driftlab

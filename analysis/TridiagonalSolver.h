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
    // Factors `count` (1..kMaxSystems) systems that share lower and upper, with diagonals
    // diag[s * n + i], side by side: their recurrences are independent, so the divisions of
    // one overlap those of the others (a single factorisation waits on each division). Each
    // system's factors are bit for bit those factor() computes for it. select(s) then makes
    // system s the one solve() and solveInterleaved() use (system 0 after factoring).
    static constexpr int kMaxSystems = 4;
    void factorSeveral(const double *lower, const double *diag, const double *upper, int n, int count);
    void select(int system);
    // Solves in place: rhs becomes x. Must follow factor() with the same n.
    void solve(double *rhs) const;
    // Solves `columns` right-hand sides stored interleaved (x[i * columns + c]) in place:
    // the independent recurrences run side by side (instruction-level parallelism).
    void solveInterleaved(double *x, int columns) const;
    int size() const { return m_n; }

private:
    template <int K>
    void factorSide(const double *diag, const double *upper);

    int m_n = 0;
    int m_count = 1;
    int m_active = 0;               // offset of the selected system's factors: system x n
    std::vector<double> m_lower;    // sub-diagonal
    std::vector<double> m_invPivot; // 1 / modified diagonal, count x n
    std::vector<double> m_upperMod; // modified super-diagonal c'_i, count x n
};

} // namespace driftlab

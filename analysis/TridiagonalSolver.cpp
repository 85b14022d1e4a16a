#include "TridiagonalSolver.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

void TridiagonalSolver::factor(const double *lower, const double *diag, const double *upper, int n)
{
    if (n < 1)
        throw std::invalid_argument("TridiagonalSolver::factor: size must be >= 1");
    m_n = n;
    m_lower.assign(lower, lower + n);
    m_invPivot.resize(static_cast<size_t>(n));
    m_upperMod.resize(static_cast<size_t>(n));
    double cPrev = 0.0;
    for (int i = 0; i < n; ++i) {
        const double pivot = diag[i] - (i > 0 ? lower[i] * cPrev : 0.0);
        if (pivot == 0.0 || !std::isfinite(pivot))
            throw std::invalid_argument("TridiagonalSolver::factor: zero or non-finite pivot");
        m_invPivot[static_cast<size_t>(i)] = 1.0 / pivot;
        cPrev = i < n - 1 ? upper[i] / pivot : 0.0;
        m_upperMod[static_cast<size_t>(i)] = cPrev;
    }
}

void TridiagonalSolver::solve(double *x) const
{
    const int n = m_n;
    const double *a = m_lower.data();
    const double *inv = m_invPivot.data();
    const double *c = m_upperMod.data();
    x[0] *= inv[0];
    for (int i = 1; i < n; ++i)
        x[i] = (x[i] - a[i] * x[i - 1]) * inv[i];
    for (int i = n - 2; i >= 0; --i)
        x[i] -= c[i] * x[i + 1];
}

void TridiagonalSolver::solveInterleaved(double *x, int columns) const
{
    const int n = m_n;
    const int C = columns;
    const double *a = m_lower.data();
    const double *inv = m_invPivot.data();
    const double *c = m_upperMod.data();
    for (int k = 0; k < C; ++k)
        x[k] *= inv[0];
    for (int i = 1; i < n; ++i) {
        double *xi = x + static_cast<size_t>(i) * C;
        const double *xp = xi - C;
        const double ai = a[i], ii = inv[i];
        for (int k = 0; k < C; ++k)
            xi[k] = (xi[k] - ai * xp[k]) * ii;
    }
    for (int i = n - 2; i >= 0; --i) {
        double *xi = x + static_cast<size_t>(i) * C;
        const double *xn = xi + C;
        const double ci = c[i];
        for (int k = 0; k < C; ++k)
            xi[k] -= ci * xn[k];
    }
}

} // namespace driftlab

#include "TridiagonalSolver.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace driftlab {

void TridiagonalSolver::factor(const double *lower, const double *diag, const double *upper, int n)
{
    if (n < 1)
        throw std::invalid_argument("TridiagonalSolver::factor: size must be >= 1");
    m_n = n;
    m_count = 1;
    m_active = 0;
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

template <int K>
void TridiagonalSolver::factorSide(const double *diag, const double *upper)
{
    const int n = m_n;
    const double *lower = m_lower.data();
    double cPrev[K] = {};
    for (int i = 0; i < n; ++i)
        for (int s = 0; s < K; ++s) {
            // factor()'s operations, in its order, for each system
            const double pivot = diag[static_cast<size_t>(s) * n + i] - (i > 0 ? lower[i] * cPrev[s] : 0.0);
            if (pivot == 0.0 || !std::isfinite(pivot))
                throw std::invalid_argument("TridiagonalSolver::factor: zero or non-finite pivot");
            m_invPivot[static_cast<size_t>(s) * n + i] = 1.0 / pivot;
            cPrev[s] = i < n - 1 ? upper[i] / pivot : 0.0;
            m_upperMod[static_cast<size_t>(s) * n + i] = cPrev[s];
        }
}

void TridiagonalSolver::factorSeveral(const double *lower, const double *diag, const double *upper, int n, int count)
{
    if (n < 1)
        throw std::invalid_argument("TridiagonalSolver::factor: size must be >= 1");
    if (count < 1 || count > kMaxSystems)
        throw std::invalid_argument("TridiagonalSolver::factorSeveral: 1 to " + std::to_string(kMaxSystems) + " systems");
    m_n = n;
    m_count = count;
    m_active = 0;
    m_lower.assign(lower, lower + n);
    m_invPivot.resize(static_cast<size_t>(n) * count);
    m_upperMod.resize(static_cast<size_t>(n) * count);
    switch (count) {
    case 1: factorSide<1>(diag, upper); break;
    case 2: factorSide<2>(diag, upper); break;
    case 3: factorSide<3>(diag, upper); break;
    default: factorSide<4>(diag, upper); break;
    }
}

void TridiagonalSolver::select(int system)
{
    if (system < 0 || system >= m_count)
        throw std::invalid_argument("TridiagonalSolver::select: no system " + std::to_string(system));
    m_active = system * m_n;
}

void TridiagonalSolver::solve(double *x) const
{
    const int n = m_n;
    const double *a = m_lower.data();
    const double *inv = m_invPivot.data() + m_active;
    const double *c = m_upperMod.data() + m_active;
    x[0] *= inv[0];
    for (int i = 1; i < n; ++i)
        x[i] = (x[i] - a[i] * x[i - 1]) * inv[i];
    for (int i = n - 2; i >= 0; --i)
        x[i] -= c[i] * x[i + 1];
}

namespace {

// The sweeps of solveInterleaved; C > 0 fixes the column count at compile time (the inner
// loops unrolled: the same operations in the same order), C == 0 takes it at run time.
template <int C>
void sweeps(double *x, int columns, int n, const double *a, const double *inv, const double *c)
{
    const int cols = C > 0 ? C : columns;
    for (int k = 0; k < cols; ++k)
        x[k] *= inv[0];
    for (int i = 1; i < n; ++i) {
        double *xi = x + static_cast<size_t>(i) * cols;
        const double *xp = xi - cols;
        const double ai = a[i], ii = inv[i];
        for (int k = 0; k < cols; ++k)
            xi[k] = (xi[k] - ai * xp[k]) * ii;
    }
    for (int i = n - 2; i >= 0; --i) {
        double *xi = x + static_cast<size_t>(i) * cols;
        const double *xn = xi + cols;
        const double ci = c[i];
        for (int k = 0; k < cols; ++k)
            xi[k] -= ci * xn[k];
    }
}

} // namespace

void TridiagonalSolver::solveInterleaved(double *x, int columns) const
{
    const double *a = m_lower.data();
    const double *inv = m_invPivot.data() + m_active;
    const double *c = m_upperMod.data() + m_active;
    switch (columns) {
    case 1: sweeps<1>(x, columns, m_n, a, inv, c); break;
    case 2: sweeps<2>(x, columns, m_n, a, inv, c); break;
    case 3: sweeps<3>(x, columns, m_n, a, inv, c); break;
    case 4: sweeps<4>(x, columns, m_n, a, inv, c); break;
    case 5: sweeps<5>(x, columns, m_n, a, inv, c); break;
    case 6: sweeps<6>(x, columns, m_n, a, inv, c); break;
    default: sweeps<0>(x, columns, m_n, a, inv, c); break;
    }
}

} // namespace driftlab

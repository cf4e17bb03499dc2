#pragma once
/// \internal
/// \file Tridiagonal.h
/// Many tridiagonal systems at once, stored level-major so that the inner loops run along
/// contiguous memory: the column-implicit steps of the surface-layer stresses and of the
/// k-epsilon transport (sim/MomentumStressStep.cpp, sim/KEpsilon.cpp).

#include <cstddef>

namespace gale::sim::detail {

/// Solves `count` tridiagonal systems at once, sub[e] x[e - count] + diag[e] x[e] + sup[e]
/// x[e + count] = rhs[e] with e = k count + i for system i in [0, count) and row k in [0, n), by
/// the Thomas algorithm (stable without pivoting for the diagonally dominant systems of the
/// stress step), level by level so that the inner loop runs along contiguous memory. Overwrites
/// sup and rhs; the solutions land in rhs.
inline void solveTridiagonalRows(int count, int n, const double* sub, const double* diag,
                                 double* sup, double* rhs) {
    const size_t m = size_t(count);
    for (size_t i = 0; i < m; ++i) {
        rhs[i] /= diag[i];
        sup[i] /= diag[i];
    }
    for (size_t k = 1; k < size_t(n); ++k)
        for (size_t i = 0; i < m; ++i) {
            const size_t e = k * m + i;
            const double beta = diag[e] - sub[e] * sup[e - m];
            sup[e] /= beta;
            rhs[e] = (rhs[e] - sub[e] * rhs[e - m]) / beta;
        }
    for (size_t k = size_t(n) - 1; k-- > 0;)
        for (size_t i = 0; i < m; ++i) rhs[k * m + i] -= sup[k * m + i] * rhs[(k + 1) * m + i];
}

}  // namespace gale::sim::detail

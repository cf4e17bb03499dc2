#pragma once
/// \file Interpolation.h
/// The one linear blend of gale's samplers, and the one bilinear interpolation of heights.
///
/// Fields (the MAC sampler of GridLayout, its uniform fast path UniformLattice, the grass
/// sampler's planned reads, coupling's blend of neighbouring groups in GroupGrid.h) blend one
/// axis at a time as a + (b - a) t, x first, then y, then z: linearBlend and trilinearBlend. The
/// grass sampler's answers equal WindField::velocityAt_mps's bit for bit because both call
/// trilinearBlend on the same eight values in the same order.
///
/// Heights (Heightfield::sample, the value noise of fractal terrain, and coupling's reads of a
/// heightfield or a render mesh) weigh the four corners instead:
/// (v00 (1 - tx) + v10 tx) (1 - ty) + (v01 (1 - tx) + v11 tx) ty, bilinearWeighted. The two forms
/// agree to round-off, not bit for bit, and the terrain's open fractions (and so every solved
/// field) were built on the weighted form, so each keeps its own arithmetic.

namespace gale::sim {

/// a + (b - a) t: a at t = 0, b at t = 1 (exactly), linear between. Any units; t dimensionless.
inline double linearBlend(double a, double b, double t) { return a + (b - a) * t; }

/// Trilinear blend of the 8 corners of a cell, c[i + 2 j + 4 k] for corner (i, j, k) (x fastest),
/// with tx, ty, tz the weights of the upper corners: along x, then y, then z (linearBlend each).
inline double trilinearBlend(const double (&c)[8], double tx, double ty, double tz) {
    const double c00 = linearBlend(c[0], c[1], tx), c10 = linearBlend(c[2], c[3], tx);
    const double c01 = linearBlend(c[4], c[5], tx), c11 = linearBlend(c[6], c[7], tx);
    const double c0 = linearBlend(c00, c10, ty), c1 = linearBlend(c01, c11, ty);
    return linearBlend(c0, c1, tz);
}

/// Bilinear interpolation of the corners v00, v10, v01, v11 (vij at corner (i, j)) with upper
/// weights tx, ty, in the weighted form the heightfields use (see the file comment). T is float
/// or double; the arithmetic is T's.
template <class T>
inline T bilinearWeighted(T v00, T v10, T v01, T v11, T tx, T ty) {
    return (v00 * (1 - tx) + v10 * tx) * (1 - ty) + (v01 * (1 - tx) + v11 * tx) * ty;
}

}  // namespace gale::sim

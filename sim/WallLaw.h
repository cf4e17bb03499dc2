#pragma once
/// \internal
/// \file WallLaw.h
/// The wall faces' geometry and the log law's tangent plane on sloping ground, shared by the
/// surface-layer stresses' set-up (sim/MomentumTurbulence.cpp) and their step
/// (sim/MomentumStressStep.cpp): docs/solver.md, "The wall law on slopes".

#include <array>
#include <cmath>
#include <cstddef>

#include "sim/GridLayout.h"
#include "sim/SurfaceLayer.h"

namespace gale::sim::detail {

/// The control-volume height (m) of the wall face of a column whose lowest unknown face sits in
/// layer kl over ground at ground_m (world z): surface::wallControlHeight_m of the layer's open
/// height (the one definition the grass sampler shares; on stretched layers the first layer's
/// own thickness, not h). The wall sample sits at half of it (surface::wallSampleHeight_m).
inline double wallHeight_m(const GridLayout& L, int kl, double ground_m) {
    return surface::wallControlHeight_m(L.zFace_m(kl + 1) - ground_m, L.dz_m(kl));
}

/// A wall face's velocity against the terrain's tangent plane (the wall law on slopes): the
/// tangential speed |U_t| (m/s), the wetted-area factor q = sqrt(1 + |grad h|^2), and its own
/// component c of U_t written as implicitShare * U_c + explicitPart (the other components'
/// contribution, m/s).
struct WallSample {
    double tangentialSpeed = 0.0, q = 1.0, implicitShare = 1.0, explicitPart = 0.0;
};

/// U_t = U - (U.n) n for the unit normal n = (-g_x, -g_y, 1) / q of a surface with gradient g.
inline WallSample wallSample(const std::array<double, 2>& g, const std::array<double, 3>& U,
                             int c) {
    const double n[3] = {-g[0], -g[1], 1.0};  // the normal times q
    const double q2 = 1.0 + g[0] * g[0] + g[1] * g[1];
    const double un = (U[0] * n[0] + U[1] * n[1] + U[2] * n[2]) / q2;  // (U.n) / q
    const double t[3] = {U[0] - un * n[0], U[1] - un * n[1], U[2] - un * n[2]};
    WallSample s;
    s.tangentialSpeed = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    s.q = std::sqrt(q2);
    s.implicitShare = 1.0 - n[c] * n[c] / q2;
    s.explicitPart = t[c] - U[size_t(c)] * s.implicitShare;
    return s;
}

}  // namespace gale::sim::detail

#pragma once
/// \file Viscosity.h
/// \internal Included only by sim/ and tests/sim (docs/architecture.md lists sim's public headers).
/// Implicit viscosity of the unsteady wind (docs/unsteady.md): one backward-Euler step of
/// du/dt = nu Laplacian(u) per velocity component,
///   (M + nu dt K) u^{n+1} = M u^n,
/// in the finite-volume flux form of Patankar 1980 ("Numerical Heat Transfer and Fluid Flow",
/// the conductance of a face is the diffusivity times its area over the distance between the two
/// values it joins). Each sample of a component owns a control volume h x h x e (e: its layer's
/// thickness dz_k for u, v; the distance between the two layer centres it separates for w, see
/// GridLayout::centreGap_m), M holds the volumes and K the conductances: h e / h to a horizontal
/// neighbour, h^2 / d to a vertical one at distance d (the centre-to-centre gap for u, v, the
/// layer thickness for w). On cubic cells this is the 7-point Laplacian with spacing h. Faces
/// outside the mask (closed by the terrain or next to rock) and the box sides are zero-gradient
/// (no viscous flux). K is symmetric (a face's conductance is the same seen from either side)
/// and positive semi-definite, M is positive diagonal, so M + nu dt K is symmetric positive
/// definite and every generalised eigenvalue lambda of (M + nu dt K, M) is >= 1: backward Euler
/// is unconditionally stable (every mode decays, none grows) for any nu, dt and layer heights.
/// Solved by conjugate gradients with a Jacobi preconditioner, warm-started from u^n; a solve
/// stopped by its iteration cap is still a CG iterate (bounded in the energy norm), and the
/// report says so.

#include <array>
#include <cstdint>
#include <vector>

#include "sim/Advection.h"

namespace gale::sim {

struct ViscosityReport {
    bool converged = true;
    int iterations = 0;           ///< largest count over the three components
    double relativeResidual = 0;  ///< largest final ||r||_2 / ||b||_2 over the components
};

/// Diffuses u, v, w in place. masks[c] marks the faces of component c that take part (must not
/// be null). nu_m2ps >= 0, dt_s >= 0; nothing happens when nu dt is 0. Cubic cells or stretched
/// layers (the grid's GridLayout). Throws std::logic_error on a negative nu or dt or a
/// missing or mis-sized mask (callers validate the scene's values first).
ViscosityReport diffuseImplicit(const MacGrid& g, double nu_m2ps, double dt_s,
                                const std::array<const std::vector<uint8_t>*, 3>& masks,
                                std::vector<double>& u, std::vector<double>& v,
                                std::vector<double>& w, double relativeTolerance = 1e-8,
                                int maxIterations = 400);

}  // namespace gale::sim

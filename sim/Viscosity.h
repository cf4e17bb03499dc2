#pragma once
/// \file Viscosity.h
/// Implicit viscosity of the unsteady wind (docs/design.md 4.2): one backward-Euler step of
/// du/dt = nu Laplacian(u) per velocity component,
///   (I - nu dt L) u^{n+1} = u^n,
/// with L the 7-point Laplacian over the component's faces (spacing h). Faces outside the mask
/// (closed by the terrain or next to rock) and the box sides are zero-gradient (no viscous flux),
/// so the operator is symmetric positive definite with eigenvalues in [1, 1 + 12 nu dt / h^2]:
/// backward Euler is unconditionally stable (every eigenmode decays, none grows) for any nu and
/// dt. Solved by conjugate gradients with a Jacobi preconditioner, warm-started from u^n; a solve
/// stopped by its iteration cap is still a CG iterate (bounded in the energy norm), and the report
/// says so.

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
/// be null). nu_m2ps >= 0, dt_s >= 0; nothing happens when nu dt is 0.
ViscosityReport diffuseImplicit(const MacGrid& g, double nu_m2ps, double dt_s,
                                const std::array<const std::vector<uint8_t>*, 3>& masks,
                                std::vector<double>& u, std::vector<double>& v,
                                std::vector<double>& w, double relativeTolerance = 1e-8,
                                int maxIterations = 400);

}  // namespace gale::sim

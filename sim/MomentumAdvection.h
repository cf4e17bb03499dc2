#pragma once
/// \file MomentumAdvection.h
/// Eulerian advection of the MAC velocity for the steady momentum model's pseudo-time step
/// (sim/MomentumWind.h, MomentumAdvection::Eulerian; docs/solver.md and docs/validation.md,
/// "Pseudo-time step and its error").
///
/// Why. The fixed point of a semi-Lagrangian step carries a numerical viscosity that grows with
/// the step, so the momentum model's steady state depended on its pseudo-time step. This step is
/// q^{n+1} = q^n - dt (a . grad) q^n with the convective term a steady residual that contains no
/// dt: at a fixed point the term itself balances the stresses and the pressure, whatever dt was.
///
/// Scheme. Advective form, dimension by dimension, for each face value q (u on x-faces, v on
/// y-faces, w on z-faces) with the frozen velocity a of the previous iterate at that face (its own
/// component there; the others averaged from the four nearest faces of their placement, weighted
/// by layer thickness across a z-level). Along each axis the derivative is the difference of two
/// reconstructed interface values over the distance between the interfaces (the midpoints
/// between samples), each interface value taken from its upwind side with a van Leer limited
/// slope (MUSCL: van Leer 1979; the limiter of van Leer 1974, in the harmonic-mean form of
/// Sweby 1984). Second order in smooth flow, first-order upwind at extrema and steep fronts, no
/// new extrema. On stretched layers the samples' world heights set the slopes and interfaces.
///
/// Stability (explicit Euler in pseudo-time). Along one axis, with the limiter's bounds 0 <= phi
/// <= 2 and 0 <= phi(r) / r <= 2, the update is q_i - nu C_i (q_i - q_{i-1}) with 0 <= C_i <= 2
/// and nu = |a| dt / dx; Harten's (1983) incremental form is then bounded (TVD) for nu <= 1/2
/// (Sweby 1984 draws the same region). Three axes add as a convex combination when
/// dt (|a_x| / h + |a_y| / h + |a_z| / dz) <= 1/2 at every face: EULERIAN_MAX_CFL, the rate
/// eulerianRate_ps() measures.
///
/// Boundaries. A neighbour outside the box through an x or y side or the top reads `outside`
/// (the far field: the inflow's values where air enters). On an outflow side the upwind stencil
/// needs no value from outside; only the limiter's downstream slope reads the far field there
/// (the momentum model's start field held at the box side), so an outflow face is advected by
/// its own upwind values and needs no boundary condition. Below the box's bottom the lowest sample
/// is repeated. Faces the solver does not update (mask 0: inside the terrain, or between a solid
/// and an air cell) hold the values the solver extrapolates into them after every projection (the
/// face above's), so the stencil sees zero gradient into the ground; the ground's stress is the
/// wall function's, not the advection's, and no velocity crosses a closed face because closed faces
/// are never updated here.

#include <array>
#include <cstdint>
#include <vector>

#include "sim/Advection.h"

namespace gale::sim {

/// Largest stable dt (|a_x| / h + |a_y| / h + |a_z| / dz) of the explicit Eulerian step (see the
/// file comment: Harten 1983 with van Leer's limiter).
inline constexpr double EULERIAN_MAX_CFL = 0.5;

/// The largest dt-free rate of the Eulerian step, 1/s: max over the samples of every face
/// placement of |a_x| / h + |a_y| / h + |a_z| / dz (a the frozen velocity at the face, dz the
/// distance between the interfaces around it along z). Times dt it must stay <=
/// EULERIAN_MAX_CFL. mask (optional, per placement): faces that count. No throws; NaN
/// propagates.
double eulerianRate_ps(const MacGrid& g, const MacVelocity& vel,
                       const std::array<const std::vector<uint8_t>*, 3>& masks = {});

/// One explicit Eulerian advection step of q (placement p: FaceX, FaceY or FaceZ; m/s) through
/// the frozen velocity vel over dt_s seconds: out = q - dt_s (a . grad) q on every sample with
/// mask[idx] != 0 (all when mask is null); other samples are copied. `outside` gives q at world
/// points outside the box (x, y sides and top; empty: the nearest sample, zero gradient).
/// Returns the largest dt_s (|a_x| / h + |a_y| / h + |a_z| / dz) over the updated samples (stable
/// when <= EULERIAN_MAX_CFL; the caller chooses dt). TBB-parallel over k. Throws
/// std::logic_error on wrong sizes or a Cell placement (a caller's bug).
double advectEulerian(const MacGrid& g, Placement p, const std::vector<double>& q,
                      const MacVelocity& vel, const OutsideValue& outside, double dt_s,
                      std::vector<double>& out, const std::vector<uint8_t>* mask = nullptr);

}  // namespace gale::sim

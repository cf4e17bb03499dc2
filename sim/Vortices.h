#pragma once
/// \file Vortices.h
/// Whirlwinds of the unsteady wind (docs/design.md 4.2): vertical-axis vortices with a finite core,
/// seeded into the flow, carried by it, optionally kept alive by forcing during their lifetime; and
/// vorticity confinement against numerical dissipation. Compiled always, run only when a scene
/// has whirlwinds or asks for confinement (UnsteadyWindSolver skips the code path otherwise).
///
/// Tangential speed v(r), r the horizontal distance from the axis, Gamma the circulation (m^2/s,
/// > 0 counter-clockwise seen from above), r_c the core radius:
///  - Rankine (solid-body core): v = Gamma r / (2 pi r_c^2) for r <= r_c, Gamma / (2 pi r) outside;
///    peak Gamma / (2 pi r_c) at r_c.
///  - Lamb-Oseen: v = Gamma / (2 pi r) (1 - exp(-r^2 / r_c^2)); peak 0.6382 Gamma / (2 pi r_c) at
///    r = 1.1209 r_c. Under viscosity nu it spreads as r_c^2(t) = r_c^2(0) + 4 nu t.
///  - Burgers: the Lamb-Oseen profile, which Burgers' vortex holds steady by an axial strain
///    a (r_c^2 = 4 nu / a). We seed the strain as the core updraft, updraft_mps, or when that is
///    0 the w = a z of a strain a = v_peak / r_c (one core turnover) taken at mid-column,
///    a min(column, 4 r_c) / 2; the projection supplies the radial inflow at the ground.
/// Optional updraft: w = updraft_mps exp(-r^2 / r_c^2) inside the column.
/// The seeded field is windowed: full out to outerRadiusFactor r_c, then a smoothstep to zero at
/// 1.5 times that (a 1/r tail over the whole domain would fight the open boundaries); vertically
/// full up to height_m above the ground, then a smoothstep to zero over height_m / 2.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/Advection.h"

namespace gale::sim {

enum class VortexProfile { Rankine, LambOseen, Burgers };

/// "rankine", "lamb_oseen", "burgers" and back; fromName throws gale::ParameterError
/// (wind.whirlwinds.profile).
const char* vortexProfileName(VortexProfile p);
VortexProfile vortexProfileFromName(const std::string& name);

struct Whirlwind {
    std::array<double, 2> wsPosition_m{0.0, 0.0};  ///< axis (x, y) when seeded, world metres
    double coreRadius_m = 3.0;      ///< r_c, metres, > 0 (may be smaller than a cell)
    double circulation_m2ps = 0.0;  ///< Gamma; used when peakSpeed_mps is 0
    double peakSpeed_mps =
        0.0;  ///< if != 0: Gamma is set so the profile's peak is this (sign: sense)
    VortexProfile profile = VortexProfile::LambOseen;
    double updraft_mps = 0.0;  ///< core updraft, m/s (>= 0)
    double start_s = 0.0;      ///< seeding time, seconds
    /// Forcing (if forced) stops at start_s + lifetime_s, seconds, > 0; unset: never stops.
    std::optional<double> lifetime_s;
    bool forced = false;    ///< relax the circulation back to the seeded one during the lifetime
    double height_m = 0.0;  ///< column height above the ground, metres; 0: up to the top
    double outerRadiusFactor = 4.0;  ///< seeded out to this many core radii (then tapered), >= 1

    /// Throws gale::ParameterError naming the scene key without the whirlwind's index
    /// ("wind.whirlwinds.core_radius_m"; ParameterError::inElement adds it) for a value out of
    /// range or not finite; std::logic_error for outerRadiusFactor < 1 (no scene key sets it).
    void validate() const;
    /// Gamma, m^2/s (from peakSpeed_mps when it is non-zero).
    double circulation() const;
    /// v(r), m/s, without the window.
    double tangentialSpeed_mps(double r_m) const;
    /// Circulation of the (unwindowed) profile inside radius r: 2 pi r v(r), m^2/s.
    double circulationWithin_m2ps(double r_m) const;
};

/// v_peak / (Gamma / (2 pi r_c)) of a profile (1 for Rankine, 0.6382 for Lamb-Oseen and Burgers).
double peakSpeedFactor(VortexProfile p);

/// The narrowest core the grid carries, in cells. A core far below a cell puts the whole swirl
/// between the velocity samples: seeded as it is, a whirlwind with a 0.04-cell core vanished.
/// Narrower cores are seeded as this wide, with the same circulation (a smoothed core): the
/// flow outside the core, Gamma / (2 pi r), is unchanged; the peak speed is what the grid can
/// resolve rather than the one asked for.
inline constexpr double MIN_SMOOTHED_CORE_CELLS = 1.0;

/// `given` with coreRadius_m raised to MIN_SMOOTHED_CORE_CELLS * voxelSize_m (metres) when it is
/// below that, keeping its circulation (then held in circulation_m2ps, peakSpeed_mps = 0);
/// otherwise `given` as it is. Throws nothing.
Whirlwind withMinimumCore(const Whirlwind& given, double voxelSize_m);

/// Ground height under a world (x, y), metres.
using GroundHeight = std::function<double(double wsX_m, double wsY_m)>;

/// Adds scale * (the whirlwind's windowed velocity, axis at wsAxis_m = (x, y)) to the MAC arrays,
/// a core below the grid smoothed to MIN_SMOOTHED_CORE_CELLS (withMinimumCore);
/// only samples with mask != 0 (if given) change. zTop_m is the domain top (column height when
/// height_m is 0).
void addWhirlwind(const MacGrid& g, const Whirlwind& ww, std::array<double, 2> wsAxis_m,
                  double scale, const GroundHeight& ground, double zTop_m, std::vector<double>& u,
                  std::vector<double>& v, std::vector<double>& w,
                  const std::array<const std::vector<uint8_t>*, 3>& masks = {});

/// Circulation, m^2/s, of the velocity along the horizontal circle of radius r_m around
/// (x, y) at height z (64 points, trapezoidal rule); counter-clockwise positive.
double circulationAround(const MacGrid& g, const MacVelocity& vel, std::array<double, 2> wsAxis_m,
                         double r_m, double wsZ_m);

/// Vertical vorticity omega_z = dv/dx - du/dy at the cell centre, 1/s, from the faces around it.
double verticalVorticity(const MacGrid& g, const MacVelocity& vel, int i, int j, int k);

/// Vorticity confinement (Fedkiw, Stam, Jensen 2001): f = epsilon h (N x omega),
/// N = grad|omega| / |grad|omega||, cell-centred, averaged to faces and added as dt_s * f.
/// Only cells with air[c] != 0 take part; epsilon >= 0 (dimensionless). h is the horizontal
/// spacing; on stretched layers the vertical derivatives divide by the distances between the
/// layer centres.
void addVorticityConfinement(const MacGrid& g, const std::vector<uint8_t>& air, double epsilon,
                             double dt_s, std::vector<double>& u, std::vector<double>& v,
                             std::vector<double>& w);

}  // namespace gale::sim

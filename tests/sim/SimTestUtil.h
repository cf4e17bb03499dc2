#pragma once
/// \file SimTestUtil.h
/// Ambient winds and solver settings shared by the steady and unsteady wind tests.

#include <cstdint>
#include <vector>

#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"

namespace gale::sim::test {

/// n reproducible values in [-0.5, 0.5) from a linear congruential generator (Numerical Recipes'
/// constants): the same vector on every machine and run.
inline std::vector<double> randomVector(size_t n, uint32_t seed) {
    std::vector<double> v(n);
    for (double& x : v) {
        seed = seed * 1664525u + 1013904223u;
        x = double(seed >> 8) / double(1u << 24) - 0.5;
    }
    return v;
}

/// A height-independent wind of speed_mps (m/s) blowing towards direction_deg (degrees
/// counter-clockwise from +x, as AmbientWind; 0 blows along +x).
inline AmbientWind uniformWind(double speed_mps, double direction_deg = 0.0) {
    AmbientWind a;
    a.profile = WindProfile::Uniform;
    a.speed_mps = speed_mps;
    a.direction_deg = direction_deg;
    return a;
}

/// A Gaussian hill of height_m and Gaussian sigma radius_m (metres) in the middle of a square of
/// size_m with samples every spacing_m.
inline Heightfield centredGaussianHill(double size_m, double spacing_m, double height_m,
                                       double radius_m) {
    TerrainSpec s;
    s.kind = TerrainKind::GaussianHill;
    s.sizeX_m = s.sizeY_m = size_m;
    s.spacing_m = spacing_m;
    s.height_m = height_m;
    s.radius_m = radius_m;
    s.centerX_m = s.centerY_m = 0.5 * size_m;
    return makeTerrain(s);
}

/// The hemisphere benchmark's terrain: radius radius_m centred in a square of 2 centre_m, sampled
/// every radius_m / 128 (fine enough that the sampled surface is not what the tests measure).
inline Heightfield centredHemisphere(double radius_m, double centre_m) {
    TerrainSpec s;
    s.kind = TerrainKind::Hemisphere;
    s.sizeX_m = s.sizeY_m = 2 * centre_m;
    s.spacing_m = radius_m / 128;
    s.radius_m = radius_m;
    s.centerX_m = s.centerY_m = centre_m;
    return makeTerrain(s);
}

/// Steady solve to 1e-9 relative residual in at most 200 iterations (the defaults are 1e-6 and
/// 100), so the solve's own error stays well below what the tests compare.
inline SolverSettings tight() {
    SolverSettings s;
    s.relativeTolerance = 1e-9;
    s.maxIterations = 200;
    return s;
}

}  // namespace gale::sim::test

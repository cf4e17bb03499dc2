#pragma once
/// \file MomentumTestCases.h
/// The inflow and terrains the momentum model's tests share (tests/sim/MomentumWindTest.cpp,
/// tests/sim/MomentumStretchedTest.cpp).

#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"

namespace gale::sim::testcases {

/// The neutral log law, speed_mps at 10 m over roughness z0_m (m).
inline AmbientWind logWind(double speed_mps, double z0_m = 0.03) {
    AmbientWind a;
    a.profile = WindProfile::LogLaw;
    a.speed_mps = speed_mps;
    a.referenceHeight_m = 10.0;
    a.roughness_m = z0_m;
    return a;
}

/// Flat ground at groundZ_m under a 120 m x 8 m box (2 m cells: 60 x 4 columns).
inline Heightfield flatGround(double groundZ_m) {
    TerrainSpec t;
    t.kind = TerrainKind::Flat;
    t.sizeX_m = 120, t.sizeY_m = 8, t.spacing_m = 2.0;
    Heightfield hf = makeTerrain(t);
    for (float& z : hf.height_m) z = float(groundZ_m);
    return hf;
}

/// A two-dimensional Gaussian ridge across the wind (axis along y): height H, e-folding
/// half-width sigma (maximum slope 0.607 H / sigma), crest at x = 150 m, in a 500 m long box
/// three cells wide.
inline Heightfield ridge(double height_m, double sigma_m, double cell_m) {
    TerrainSpec t;
    t.kind = TerrainKind::Ridge;
    t.axis_deg = 90;
    t.sizeX_m = 500, t.sizeY_m = 3 * cell_m, t.spacing_m = cell_m / 2;
    t.height_m = height_m, t.radius_m = sigma_m, t.centerX_m = 150, t.centerY_m = 0;
    return makeTerrain(t);
}

}  // namespace gale::sim::testcases

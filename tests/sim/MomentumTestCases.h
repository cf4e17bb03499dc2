#pragma once
/// \file MomentumTestCases.h
/// The inflow, terrains and the log-law check the momentum model's tests share
/// (tests/sim/MomentumWindTest.cpp, MomentumStretchedTest.cpp, MomentumEulerianTest.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/WindField.h"

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

/// Expects u at each open x-face of the middle column, 1 m to 50 m above flat ground at
/// groundZ_m, within 2 % (the bound) of the neutral log law of logWind(speed_mps):
/// u(z) = U_ref ln(z / z0) / ln(z_ref / z0), the lowest face at its open part's centroid. At
/// least minFaces faces must be checked; `what` labels the failures.
inline void expectLogLawColumn(const AirDomain& domain, const WindField& field, double speed_mps,
                               double groundZ_m, const std::string& what, int minFaces = 15) {
    constexpr double LOG_TOLERANCE = 0.02;         // the bound the issue sets
    constexpr double Z0_M = 0.03, Z_REF_M = 10.0;  // logWind's defaults
    const GridLayout& L = domain.layout();
    const int i = domain.nx() / 2, j = domain.ny() / 2;
    int checked = 0;
    for (int k = 0; k < domain.nz(); ++k) {
        const double theta = domain.openFractionX(i, j, k);
        if (theta == 0.0) continue;
        const double z = L.zFace_m(k + 1) - 0.5 * theta * L.dz_m(k) - groundZ_m;
        if (z < 1.0 || z > 50.0) continue;
        const double exact = speed_mps * std::log(z / Z0_M) / std::log(Z_REF_M / Z0_M);
        EXPECT_NEAR(field.u(i, j, k) / exact, 1.0, LOG_TOLERANCE) << what << ", z = " << z << " m";
        ++checked;
    }
    EXPECT_GE(checked, minFaces) << what;
}

}  // namespace gale::sim::testcases

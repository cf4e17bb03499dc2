// The turbulence a user reads (coupling/Turbulence.h): k at a point from the momentum model's
// cells, against the neutral log layer's k = u*^2 / sqrt(C_mu) computed here from the formulas;
// the sampler's own contract (constant below a column's first air centre, linear between
// centres, solid columns left out); the intensity and gust formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "coupling/Turbulence.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/MomentumWind.h"
#include "sim/SurfaceLayer.h"

using namespace gale;

namespace {

constexpr double KAPPA = 0.41;     // von Karman's constant, as the surface layer uses it
constexpr double C_MU = 0.09;      // the standard k-epsilon C_mu (Launder and Spalding 1974)
constexpr double U_REF_MPS = 5.0;  // ambient speed at 10 m
constexpr double Z_REF_M = 10.0, Z0_M = 0.03;

// Flat ground at groundZ_m under a 120 m x 8 m box of 2 m cells.
sim::Heightfield flat(double groundZ_m) {
    sim::Heightfield t;
    t.nx = 61, t.ny = 5, t.spacing_m = 2.0;
    t.height_m.assign(size_t(t.nx) * t.ny, float(groundZ_m));
    return t;
}

}  // namespace

// The log layer's k, through the sampler gale probe and the rasters use: near the ground, where
// Blackadar's length is within a few % of kappa z, the mixing length's local-equilibrium k is
// u*^2 / sqrt(C_mu) (Pope 2000, section 10.3), with u* = kappa U_ref / ln(z_ref / z0) of the
// ambient wind, for flat ground on a cell face (at 0 m and at 2 m). Ground that cuts the first
// cell is left out here: with the mixing length's first edge taking its wall sample at the cell
// centre while the wall function holds it at the open part's centroid (issue 24, "Why" 3), the
// edge carries only part of u*^2, and this sampler measured k at 0.38 of the log layer's at
// 0.25 m, 0.48 at 1 m and 0.55 at 1.5 m for ground 0.7 m into 2 m cells. Once the first edge
// takes the centroid, 0.7 belongs in the list below.
TEST(TurbulenceSampling, FlatGroundLogLayerGivesUStarSquaredOverRootCmuNearTheGround) {
    // The first two faces above the ground (2 m and 4 m up) carry Blackadar's factor
    // (1 + l / l_max)^-2 with l <= 0.41 x 4 m: k at most 8 % below the log layer's at 1.5 m, at
    // most 4 % below it under the first centre; the converged solve adds well under 1 %.
    constexpr double BELOW_FIRST_CENTRE_TOLERANCE = 0.05;
    constexpr double BETWEEN_CENTRES_TOLERANCE = 0.09;
    const double uStar = KAPPA * U_REF_MPS / std::log(Z_REF_M / Z0_M);
    const double exact = uStar * uStar / std::sqrt(C_MU);
    for (double ground : {0.0, 2.0}) {
        const sim::AirDomain domain(flat(ground), sim::DomainSpec{2.0, 62.0, 2e9});
        sim::AmbientWind wind;
        wind.speed_mps = U_REF_MPS, wind.referenceHeight_m = Z_REF_M, wind.roughness_m = Z0_M;
        const sim::MomentumWindResult res = sim::solveMomentumWind(domain, wind, {});
        ASSERT_TRUE(res.report.converged) << res.report.message;
        ASSERT_EQ(res.tke_m2ps2.size(), domain.layout().cellCount());
        for (double x : {30.0, 61.0, 90.0}) {
            const double y = 4.0;
            double firstCentre = 0.0;
            for (double height : {0.25, 0.5, 1.0, 1.5}) {
                const double k =
                    coupling::sampleTke_m2ps2(res.field, res.tke_m2ps2, x, y, ground + height);
                const bool below = height <= 1.0;  // the first air centre, 1 m up
                EXPECT_NEAR(k / exact, 1.0,
                            below ? BELOW_FIRST_CENTRE_TOLERANCE : BETWEEN_CENTRES_TOLERANCE)
                    << "ground " << ground << " m, x " << x << " m, height " << height << " m";
                // Constant below the first centre: the log layer's k does not depend on height.
                if (below && firstCentre == 0.0) firstCentre = k;
                if (below) {
                    EXPECT_EQ(k, firstCentre) << "height " << height;
                }
            }
        }
    }
}

// The sampler's contract on a field it can be checked on by hand: linear in z between centres,
// the lowest air cell's value below its centre, solid columns left out of the horizontal blend.
TEST(TurbulenceSampling, BlendsCentresLinearlyHoldsTheFirstAirValueAndSkipsSolidColumns) {
    constexpr double EXACT = 1e-12;  // sums of a few doubles
    auto terrain = std::make_shared<sim::Heightfield>();
    terrain->nx = terrain->ny = 3, terrain->spacing_m = 1.0;
    terrain->height_m.assign(9, 0.0f);
    // 2 x 1 columns of 4 cells of 1 m: column 0 all air, column 1 rock in its lowest cell.
    const std::vector<uint8_t> air = {1, 0, 1, 1, 1, 1, 1, 1};  // i fastest: (0,0,k), (1,0,k)
    const sim::WindField f(2, 1, 4, 1.0, {0.0, 0.0, 0.0}, terrain, air);
    std::vector<double> tke(8);
    for (int k = 0; k < 4; ++k) tke[size_t(2 * k)] = 1.0 + k, tke[size_t(2 * k + 1)] = 10.0 + k;
    // Column 0 alone (x at its centre): 1.0 below z = 0.5, linear up to 4.0 at z = 3.5.
    EXPECT_NEAR(coupling::sampleTke_m2ps2(f, tke, 0.5, 0.5, 0.2), 1.0, EXACT);
    EXPECT_NEAR(coupling::sampleTke_m2ps2(f, tke, 0.5, 0.5, 1.25), 1.75, EXACT);
    EXPECT_NEAR(coupling::sampleTke_m2ps2(f, tke, 0.5, 0.5, 3.9), 4.0, EXACT);
    // Column 1: its first air cell is k = 1 (value 11), held below its centre z = 1.5.
    EXPECT_NEAR(coupling::sampleTke_m2ps2(f, tke, 1.5, 0.5, 0.7), 11.0, EXACT);
    // Half way between the columns, at z = 2: the mean of 2.5 and 11.5.
    EXPECT_NEAR(coupling::sampleTke_m2ps2(f, tke, 1.0, 0.5, 2.0), 7.0, EXACT);
    EXPECT_THROW(coupling::sampleTke_m2ps2(f, std::vector<double>(7), 0.5, 0.5, 1.0),
                 std::invalid_argument);
    // No air in any column around the point: NaN, not a made-up k.
    const sim::WindField rock(2, 1, 4, 1.0, {0.0, 0.0, 0.0}, terrain, std::vector<uint8_t>(8, 0));
    EXPECT_TRUE(std::isnan(coupling::sampleTke_m2ps2(rock, tke, 1.0, 0.5, 2.0)));
}

// The derived columns: I = sqrt(2k/3) / U, gust = U + 3.5 sqrt(2k/3), from their definitions.
TEST(TurbulenceSampling, IntensityAndGustFollowTheirDefinitions) {
    constexpr double EXACT = 1e-12;
    const double k = 1.5, speed = 6.0, sigma = std::sqrt(2.0 * k / 3.0);
    EXPECT_NEAR(coupling::turbulenceIntensity(k, speed), sigma / speed, EXACT);
    EXPECT_NEAR(coupling::gustSpeed_mps(speed, k), speed + 3.5 * sigma, EXACT);
    EXPECT_TRUE(std::isnan(coupling::turbulenceIntensity(k, 0.0)));  // calm: undefined
    EXPECT_EQ(coupling::gustSpeed_mps(speed, 0.0), speed);
}

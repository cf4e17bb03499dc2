// The turbulent flutter of the grass (coupling/Flutter.h): the amplitude from k, the shear
// stand-in on a log law, and the resolved fluctuation, against their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "base/Numbers.h"
#include "coupling/Flutter.h"

namespace gale::coupling {
namespace {

// Float results of double formulas.
constexpr double FLOAT_TOLERANCE = 1e-6;

TEST(Flutter, AmplitudeIsTheTiltOfTheDragsRmsFluctuationAndZeroInCalmAir) {
    // sigma_u = 1 m/s is k = 3/2. In a mean wind of 3 m/s the drag V^2 fluctuates by
    // sqrt(4 9 1 + 2 1) = sqrt(38) m^2/s^2; at a bend speed of 20 m/s the tilt is that over 400,
    // times pi/2.
    EXPECT_NEAR(flutterFromTke(1.5, 3.0, 20.0), 0.5 * PI * std::sqrt(38.0) / 400.0,
                FLOAT_TOLERANCE);
    // In a strong mean wind the drag's fluctuation is linear in sigma_u: four times the energy,
    // twice the amplitude (below the cap).
    EXPECT_NEAR(flutterFromTke(6.0, 100.0, 200.0), 2.0 * flutterFromTke(1.5, 100.0, 200.0),
                1e-3 * flutterFromTke(6.0, 100.0, 200.0));
    // The same turbulence in a slower mean wind flutters less: shelter reads as stillness.
    EXPECT_LT(flutterFromTke(1.5, 1.0, 20.0), flutterFromTke(1.5, 5.0, 20.0));
    EXPECT_EQ(flutterFromTke(0.0, 5.0, 8.0), 0.0f);
    EXPECT_EQ(flutterFromTke(-1.0, 5.0, 8.0), 0.0f);
    EXPECT_EQ(flutterFromTke(NAN, 5.0, 8.0), 0.0f);
    EXPECT_NEAR(flutterFromTke(1e6, 5.0, 8.0), MAX_FLUTTER_RAD, FLOAT_TOLERANCE);
    EXPECT_THROW(flutterFromTke(1.0, 5.0, 0.0), std::invalid_argument);
    const std::vector<float> v = flutterFromTke(std::vector<double>{0.0, 1.5},
                                                {glm::vec3(3, 0, 0), glm::vec3(0, 3, 0)}, 20.0);
    ASSERT_EQ(v.size(), 2u);
    EXPECT_EQ(v[0], 0.0f);
    EXPECT_NEAR(v[1], 0.5 * PI * std::sqrt(38.0) / 400.0, FLOAT_TOLERANCE);
    EXPECT_THROW(flutterFromTke(std::vector<double>{1.0}, {}, 8.0), std::logic_error);
}

TEST(Flutter, TheShearStandInGivesTheSurfaceLayersEquilibriumKOnALogLaw) {
    // U(z) = (u* / kappa) ln(z / z0): the surface layer's k = u*^2 / sqrt(C_mu) at any heights.
    const double uStar_mps = 0.4, z0_m = 0.03;
    const auto u = [&](double z) { return uStar_mps / KARMAN * std::log(z / z0_m); };
    const double expected = uStar_mps * uStar_mps / std::sqrt(C_MU);
    for (const auto& [lo, hi] : {std::pair{0.5, 1.0}, {0.2, 3.0}, {1.0, 1.1}})
        EXPECT_NEAR(shearTke_m2ps2(u(lo), u(hi), lo, hi), expected, 1e-12 * expected)
            << lo << " - " << hi << " m";
    EXPECT_EQ(shearTke_m2ps2(0.0, 0.0, 0.5, 1.0), 0.0);  // calm air
    EXPECT_THROW(shearTke_m2ps2(1.0, 2.0, 1.0, 1.0), std::invalid_argument);
    EXPECT_THROW(shearTke_m2ps2(1.0, 2.0, 0.0, 1.0), std::invalid_argument);
}

TEST(Flutter, TheResolvedFluctuationIsHalfTheSquaredDeviationFromTheMean) {
    const std::vector<glm::vec3> u = {{3.0f, 4.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
    const std::vector<glm::vec3> mean = {{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
    const std::vector<double> k = resolvedTke_m2ps2(u, mean);
    EXPECT_DOUBLE_EQ(k[0], 12.5);
    EXPECT_DOUBLE_EQ(k[1], 0.0);
    EXPECT_THROW(resolvedTke_m2ps2(u, {}), std::logic_error);
}

}  // namespace
}  // namespace gale::coupling

// V = W - (W.N)N (paper section 3): perpendicular to N, exact on hand-computed cases, zero when
// degenerate, never NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "base/Numbers.h"
#include "coupling/PointSourceWind.h"

using gale::coupling::tangentWindDirection;

namespace {

// The bound on |V.N| for a unit result.
constexpr float PERPENDICULAR_TOL = 1e-6f;
// Float arithmetic on unit vectors: a few ulps.
constexpr float VECTOR_TOL = 1e-6f;

void expectVecNear(const glm::vec3& a, const glm::vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Projection, FlatGroundKeepsTheHorizontalPart) {
    expectVecNear(tangentWindDirection({3.0f, 4.0f, 7.0f}, {0, 0, 1}), {0.6f, 0.8f, 0.0f},
                  VECTOR_TOL);
}

TEST(Projection, HandComputedSlope) {
    // N = (1, 0, 1)/sqrt2, W = (1, 0, 0): W.N = 1/sqrt2, V = (1,0,0) - (1/2)(1,0,1) = (1/2, 0,
    // -1/2).
    const glm::vec3 n = glm::normalize(glm::vec3(1, 0, 1));
    expectVecNear(tangentWindDirection({1, 0, 0}, n), glm::normalize(glm::vec3(1, 0, -1)),
                  VECTOR_TOL);
    // A non-unit normal is normalised first.
    expectVecNear(tangentWindDirection({1, 0, 0}, {2, 0, 2}), glm::normalize(glm::vec3(1, 0, -1)),
                  VECTOR_TOL);
}

TEST(Projection, ResultIsPerpendicularToTheNormalOnSteepSlopes) {
    for (float slope_deg : {0.0f, 30.0f, 60.0f, 85.0f, 89.9f}) {
        const float a = float(gale::radiansFromDegrees(slope_deg));
        const glm::vec3 n(std::sin(a), 0.1f * std::sin(a), std::cos(a));
        for (const glm::vec3& w :
             {glm::vec3(1, 0, 0), glm::vec3(0.3f, -2, 0.5f), glm::vec3(0.2f, 0.1f, -1)}) {
            const glm::vec3 v = tangentWindDirection(w, n);
            ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
            EXPECT_LT(std::abs(glm::dot(v, glm::normalize(n))), PERPENDICULAR_TOL) << slope_deg;
            EXPECT_NEAR(glm::length(v), 1.0f, VECTOR_TOL) << slope_deg;
        }
    }
}

TEST(Projection, WindAlongTheNormalGivesZeroNotNaN) {
    expectVecNear(tangentWindDirection({0, 0, 5}, {0, 0, 1}), glm::vec3(0.0f), 0.0f);
    expectVecNear(tangentWindDirection({0, 0, -5}, {0, 0, 1}), glm::vec3(0.0f), 0.0f);
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));
    expectVecNear(tangentWindDirection(7.0f * n, n), glm::vec3(0.0f), 0.0f);
}

TEST(Projection, DegenerateInputsGiveZero) {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    expectVecNear(tangentWindDirection({0, 0, 0}, {0, 0, 1}), glm::vec3(0.0f), 0.0f);
    expectVecNear(tangentWindDirection({1, 0, 0}, {0, 0, 0}), glm::vec3(0.0f), 0.0f);
    expectVecNear(tangentWindDirection({nan, 0, 0}, {0, 0, 1}), glm::vec3(0.0f), 0.0f);
    expectVecNear(tangentWindDirection({1, 0, 0}, {inf, 0, 1}), glm::vec3(0.0f), 0.0f);
    // Huge wind: normalisation must not overflow to Inf or NaN.
    const glm::vec3 v = tangentWindDirection({3e37f, 1e37f, 0}, {0, 0, 1});
    EXPECT_NEAR(glm::length(v), 1.0f, VECTOR_TOL);
}

}  // namespace

// The fast subset of the unsteady wind's stability suite (`gale bench stability` runs them all):
// no NaN/Inf, divergence-free after every projection, kinetic energy that does not grow without
// forcing and stays bounded by what is injected with it.
#include <gtest/gtest.h>

#include <cstdio>

#include "sim/UnsteadyStability.h"

namespace gale::sim {
namespace {

class Stability : public ::testing::TestWithParam<std::string> {};

TEST_P(Stability, StaysFiniteDivergenceFreeAndEnergyBounded) {
    const StabilityResult r = runStabilityCase(GetParam());
    std::printf("%-26s steps %3d  max speed %8.3f m/s  KE %.4g -> %.4g (max %.4g, bound %.4g, growth %.2e)  div %.2e%s\n",
                r.name.c_str(), r.steps, r.maxSpeed_mps, r.keStart_m5ps2, r.keEnd_m5ps2, r.keMax_m5ps2, r.keBound_m5ps2,
                r.maxGrowth, r.maxDivergenceScaled, r.refused ? ("  " + r.refusal).c_str() : "");
    EXPECT_TRUE(r.pass) << r.name << ": " << r.why;
    EXPECT_TRUE(r.finite);
}

INSTANTIATE_TEST_SUITE_P(FastSubset, Stability, ::testing::ValuesIn(stabilityCaseNames(/*fastOnly=*/true)),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(Stability, UnknownCaseNameThrows) { EXPECT_THROW(runStabilityCase("cfl_9000"), std::invalid_argument); }

}  // namespace
}  // namespace gale::sim

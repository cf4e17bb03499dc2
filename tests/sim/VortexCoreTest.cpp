// A whirlwind whose core is far below a cell still carries its circulation on the grid: the core
// is smoothed to MIN_SMOOTHED_CORE_CELLS (sim/Vortices.h) instead of vanishing between samples.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim/Vortices.h"

namespace gale::sim {
namespace {

/// Circulation on a ring of 3 cells' radius, by the 64-point trapezoidal rule on bilinearly
/// sampled faces: within 5 % of the seeded one for a smooth vortex that wide.
constexpr double RING_CIRCULATION_TOLERANCE = 0.05;

/// The circulation of a Lamb-Oseen whirlwind of core `core_cells` (in cells) seeded on a 33^2 x 4
/// grid, measured on a ring of 3 cells around its axis.
double measuredCirculation(double coreCells, double gamma_m2ps) {
    MacGrid g;
    g.nx = g.ny = 33;
    g.nz = 4;
    g.voxelSize_m = 1.0;
    std::vector<double> u(g.count(Placement::FaceX), 0.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), 0.0);
    Whirlwind ww;
    ww.coreRadius_m = coreCells * g.voxelSize_m;
    ww.circulation_m2ps = gamma_m2ps;
    // The default window (4 cores, then tapered): a core seeded as given would put the ring
    // outside it.
    addWhirlwind(g, ww, {16.5, 16.5}, 1.0, nullptr, 4.0, u, v, w);
    return circulationAround(g, MacVelocity{&u, &v, &w}, {16.5, 16.5}, 3.0, 2.0);
}

TEST(VortexCore, SubCellCoresKeepTheirCirculationOnTheGrid) {
    const double gamma = 10.0;
    for (const double coreCells : {1e-6, 0.04, 0.3, 1.0}) {
        SCOPED_TRACE(coreCells);
        const double measured = measuredCirculation(coreCells, gamma);
        ASSERT_TRUE(std::isfinite(measured));
        EXPECT_NEAR(measured, gamma, RING_CIRCULATION_TOLERANCE * gamma);
    }
}

TEST(VortexCore, MinimumCoreKeepsCirculationAndOnlyWidensNarrowCores) {
    Whirlwind narrow;
    narrow.coreRadius_m = 0.01;
    narrow.peakSpeed_mps = 5.0;
    const Whirlwind s = withMinimumCore(narrow, 2.0);
    EXPECT_EQ(s.coreRadius_m, MIN_SMOOTHED_CORE_CELLS * 2.0);
    EXPECT_DOUBLE_EQ(s.circulation(), narrow.circulation());
    Whirlwind wide;
    wide.coreRadius_m = 5.0;
    wide.circulation_m2ps = 3.0;
    EXPECT_EQ(withMinimumCore(wide, 2.0).coreRadius_m, 5.0);
}

}  // namespace
}  // namespace gale::sim

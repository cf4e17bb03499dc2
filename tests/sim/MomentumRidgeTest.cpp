/// \file MomentumRidgeTest.cpp
/// Two-dimensional ridges solved a few cells across (the Cao and Tamura case of
/// docs/validation.md, section 3): the box's y sides must be free-slip walls
/// (DomainSpec::closedSidesY) for the answer not to depend on the box's width, and the momentum
/// model's diagnostic switches are guarded.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "base/Numbers.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"

namespace gale::sim {
namespace {

constexpr double RIDGE_H_M = 8.0, RIDGE_B_M = 20.0;  // cos^2 ridge, steepest slope 0.63
constexpr double CREST_X_M = 80.0, BOX_LENGTH_M = 240.0, CELL_M = 2.0, TOP_M = 48.0;

double ridgeHeight_m(double x_m) {
    const double d = x_m - CREST_X_M;
    if (std::abs(d) > RIDGE_B_M) return 0.0;
    const double c = std::cos(gale::PI * d / (2 * RIDGE_B_M));
    return RIDGE_H_M * c * c;
}

/// The ridge, uniform along y, cellsAcross cells of CELL_M wide.
Heightfield ridge(int cellsAcross) {
    const double spacing = CELL_M / 2;
    const int nx = int(std::lround(BOX_LENGTH_M / spacing)) + 1, ny = 2 * cellsAcross + 1;
    std::vector<float> z(size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) z[size_t(j) * nx + i] = float(ridgeHeight_m(i * spacing));
    return makeHeightfield(nx, ny, spacing, std::move(z));
}

/// Potential flow (mass-consistent, a_h = a_v, uniform first guess of 10 m/s along x): u at
/// dz_m above the crest, on the box's centre line.
double crestSpeed_mps(int cellsAcross, bool closedSides, double dz_m) {
    const Heightfield hf = ridge(cellsAcross);
    DomainSpec spec;
    spec.voxelSize_m = CELL_M, spec.top_m = TOP_M, spec.closedSidesY = closedSides;
    const AirDomain domain(hf, spec);
    AmbientWind wind;
    wind.profile = WindProfile::Uniform, wind.speed_mps = 10.0;
    SolverSettings s;
    s.relativeTolerance = 1e-8, s.maxIterations = 200;
    const SteadyWindResult r = solveSteadyWind(domain, wind, MassConsistentWeights{}, s);
    EXPECT_TRUE(r.report.converged) << r.report.message;
    const auto u = r.field.velocityAt_mps(CREST_X_M, hf.sizeY_m() / 2, RIDGE_H_M + dz_m);
    EXPECT_TRUE(std::isfinite(u[0]) && std::isfinite(u[1]) && std::isfinite(u[2]));
    return u[0];
}

// A two-dimensional flow is the same whatever the box's width: with free-slip y sides, 3 and 9
// cells across give the same crest speed to the solver's tolerance. (With open sides, where the
// potential is held at 0 a cell and a half from the centre line, the flow went round the ridge
// sideways: the Cao and Tamura crest lost most of its speed-up.)
TEST(TwoDimensionalRidge, PotentialFlowOverTheCrestDoesNotDependOnTheBoxWidth) {
    // Both runs converge to a relative residual of 1e-8; the field differs by rounding only.
    constexpr double SAME_FLOW_REL = 1e-4;
    for (double dz : {0.5 * RIDGE_H_M, RIDGE_H_M}) {
        const double narrow = crestSpeed_mps(3, true, dz), wide = crestSpeed_mps(9, true, dz);
        EXPECT_NEAR(narrow, wide, SAME_FLOW_REL * wide) << "dz = " << dz << " m";
    }
}

// The same ridge with open sides (the old set-up): the narrow box loses more than half of the
// crest speed-up the side-walled one has at one ridge height up (on the Cao and Tamura set-up,
// 0.003 against 0.405), the defect the side walls remove.
TEST(TwoDimensionalRidge, OpenSidesLetTheFlowGoRoundAndLoseTheCrestSpeedUp) {
    const double walls = crestSpeed_mps(3, true, RIDGE_H_M) / 10.0 - 1.0;
    const double open = crestSpeed_mps(3, false, RIDGE_H_M) / 10.0 - 1.0;
    EXPECT_GT(walls, 0.0);
    EXPECT_LT(open, 0.5 * walls);
}

// The diagnostic switches (docs/validation.md, the crest experiments) are no scene keys: a wall
// stress without the eddy viscosity that carries it up is refused as a programming error.
TEST(MomentumDiagnostics, WallStressWithoutEddyViscosityIsALogicError) {
    MomentumSettings s;
    s.eddyViscosity = false;
    EXPECT_THROW(s.validate(), std::logic_error);
    s.wallStress = false;
    EXPECT_NO_THROW(s.validate());
}

}  // namespace
}  // namespace gale::sim

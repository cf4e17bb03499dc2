// Walls in the advection (sim/UnsteadyWind.h, step 2; sim/MomentumAdvection.h, "Boundaries"):
// the faces the terrain closes read as the ground at rest, so the first cells behind a lee riser
// import no momentum through the riser's face.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim/Advection.h"
#include "sim/AirDomain.h"
#include "sim/FaceExtrapolation.h"
#include "sim/MomentumAdvection.h"

namespace gale::sim {
namespace {

constexpr double H_M = 2.0;         // cell edge
constexpr double U_MPS = 1.0;       // the uniform flow along the wall
constexpr double DT_S = 0.2;        // 0.1 cells per step
constexpr double STEP_TOP_M = 6.0;  // the riser's top: three cells
constexpr double RISER_X_M = 20.0;  // on a cell boundary
/// Sums of a few terms of order 1 (the oracles below are closed forms of the same arithmetic).
constexpr double ROUND_OFF = 1e-12;

/// Ground at STEP_TOP_M up to RISER_X_M and at 0 behind it (the ramp of the bilinear surface is
/// 1/8 m wide, a sliver of rock in the first lee column, whose cells stay air), in a 48 m x 8 m
/// box of 2 m cells: the face at RISER_X_M is the riser, between solid and air.
struct Riser {
    Heightfield ground;
    std::unique_ptr<AirDomain> domain;
    std::vector<uint8_t> okX;  // x-faces between two air cells (or on the box at an air cell)
    Riser() {
        TerrainSpec t;
        t.kind = TerrainKind::Flat;
        t.sizeX_m = 48.0, t.sizeY_m = 8.0, t.spacing_m = 0.125;
        ground = makeTerrain(t);
        for (int j = 0; j < ground.ny; ++j)
            for (int i = 0; i < ground.nx; ++i)
                ground.height_m[size_t(j) * ground.nx + i] =
                    i * ground.spacing_m < RISER_X_M + 0.5 * ground.spacing_m ? float(STEP_TOP_M)
                                                                              : 0.0f;
        DomainSpec spec;
        spec.voxelSize_m = H_M;
        spec.top_m = 24.0;
        domain = std::make_unique<AirDomain>(ground, spec);
        const GridIndex& g = domain->layout();
        okX.assign(g.count(Placement::FaceX), 0);
        const int nx = domain->nx();
        for (int k = 0; k < domain->nz(); ++k)
            for (int j = 0; j < domain->ny(); ++j)
                for (int i = 0; i <= nx; ++i)
                    okX[g.faceXIndex(i, j, k)] =
                        i > 0 && i < nx ? domain->isAir(i - 1, j, k) && domain->isAir(i, j, k)
                        : i == 0        ? domain->isAir(0, j, k)
                                        : domain->isAir(nx - 1, j, k);
    }
};

/// Uniform flow U along +x on every open x-face, v = w = 0; the closed x-faces hold 0 (walls) or
/// the extrapolated values the solver keeps for sampling (the former treatment).
struct Flow {
    std::vector<double> u, v, w;
};

Flow uniformFlow(const Riser& r, bool walls) {
    const GridIndex& g = r.domain->layout();
    Flow f{std::vector<double>(g.count(Placement::FaceX), 0.0),
           std::vector<double>(g.count(Placement::FaceY), 0.0),
           std::vector<double>(g.count(Placement::FaceZ), 0.0)};
    for (size_t i = 0; i < f.u.size(); ++i)
        if (r.okX[i]) f.u[i] = U_MPS;
    if (walls)
        for (size_t i : detail::terrainClosedFaces(r.okX, g, Placement::FaceX)) f.u[i] = 0.0;
    else
        detail::extrapolateFaces(f.u, r.okX, g, Placement::FaceX, /*layers=*/3);
    return f;
}

/// The first open x-face behind the riser in each row below its top: (face index, k).
std::vector<size_t> firstLeeFaces(const Riser& r) {
    const GridIndex& g = r.domain->layout();
    const int iRiser = int(std::lround(RISER_X_M / H_M));  // the riser's own face: closed
    std::vector<size_t> faces;
    for (int k = 0; (k + 1) * H_M <= STEP_TOP_M; ++k) {
        EXPECT_FALSE(r.okX[g.faceXIndex(iRiser, 1, k)]) << "the riser's face is closed, k " << k;
        EXPECT_TRUE(r.okX[g.faceXIndex(iRiser + 1, 1, k)]) << "the lee face is open, k " << k;
        faces.push_back(g.faceXIndex(iRiser + 1, 1, k));
    }
    return faces;
}

TEST(AdvectionWalls, EulerianStepImportsNoMomentumThroughALeeRiser) {
    // Oracle: the riser's face and the one inside the rock hold the wall's 0, so the upwind
    // stencil of the first lee face is first order against a wall at rest: u' = U (1 - U dt / h)
    // (the limited slopes vanish: zero upstream inside the rock, uniform downstream). The
    // extrapolated ghost (the former treatment) holds U and leaves the face at U: crest-level
    // momentum that the riser handed on.
    const Riser r;
    const MacGrid grid(r.domain->layout(), &r.ground);
    for (bool walls : {true, false}) {
        const Flow f = uniformFlow(r, walls);
        std::vector<double> out;
        (void)advectEulerian(grid, Placement::FaceX, f.u, {&f.u, &f.v, &f.w}, {}, DT_S, out,
                             &r.okX);
        for (size_t face : firstLeeFaces(r)) {
            const double expected = walls ? U_MPS * (1.0 - U_MPS * DT_S / H_M) : U_MPS;
            EXPECT_NEAR(out[face], expected, ROUND_OFF) << (walls ? "walls" : "extrapolated");
        }
    }
}

TEST(AdvectionWalls, SemiLagrangianStepImportsNoMomentumThroughALeeRiser) {
    // Oracle: the midpoint trace of the first lee face, a sample h from the wall face at rest,
    // reads u between 0 (the riser) and U linearly: u_mid = U (1 - U dt / (2 h)); the departure
    // point dt u_mid upstream reads U (1 - dt u_mid / h). No face behind the riser gains speed.
    const Riser r;
    const MacGrid grid(r.domain->layout(), &r.ground);
    const Flow f = uniformFlow(r, /*walls=*/true);
    const double uMid = U_MPS * (1.0 - U_MPS * DT_S / (2.0 * H_M));
    for (AdvectionScheme s :
         {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack, AdvectionScheme::Bfecc}) {
        std::vector<double> out;
        advect(grid, Placement::FaceX, f.u, {&f.u, &f.v, &f.w}, {}, {}, DT_S, s, out, &r.okX);
        for (size_t face : firstLeeFaces(r)) {
            if (s == AdvectionScheme::SemiLagrangian) {
                EXPECT_NEAR(out[face], U_MPS * (1.0 - DT_S * uMid / H_M), ROUND_OFF);
            }
            EXPECT_LT(out[face], U_MPS) << advectionSchemeName(s);
        }
        for (size_t i = 0; i < out.size(); ++i)
            EXPECT_LE(out[i], U_MPS + ROUND_OFF) << advectionSchemeName(s) << " face " << i;
    }
}

TEST(AdvectionWalls, ClosedFacesListLeavesOutTheLidAndKeepsTheRock) {
    // terrainClosedFaces: every closed face below the top level, none open, and none of the
    // top level of z-faces (a lid's).
    const Riser r;
    const GridIndex& g = r.domain->layout();
    std::vector<uint8_t> okZ(g.count(Placement::FaceZ), 0);
    const int nx = r.domain->nx(), ny = r.domain->ny(), nz = r.domain->nz();
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            for (int k = 1; k < nz; ++k)
                okZ[g.faceZIndex(i, j, k)] =
                    r.domain->isAir(i, j, k - 1) && r.domain->isAir(i, j, k);
    const std::vector<size_t> closed = detail::terrainClosedFaces(okZ, g, Placement::FaceZ);
    size_t expected = 0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) expected += !okZ[g.faceZIndex(i, j, k)];
    EXPECT_EQ(closed.size(), expected);
    for (size_t f : closed) {
        EXPECT_FALSE(okZ[f]);
        EXPECT_LT(f, g.faceZIndex(0, 0, nz));
    }
}

}  // namespace
}  // namespace gale::sim

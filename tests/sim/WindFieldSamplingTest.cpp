// WindField's staggered trilinear sampling: exact on linear fields, the same numbers as OpenVDB's
// StaggeredBoxSampler inside the box, and the terrain test split off for callers that cache it.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <memory>
#include <random>

#include "sim/VdbIO.h"
#include "sim/WindField.h"

using namespace gale::sim;

namespace {

constexpr int NX = 9, NY = 7, NZ = 5;
constexpr double H = 0.75;  // cell edge, metres
constexpr std::array<double, 3> WS_MIN{-3.0, 2.0, 10.0};

std::shared_ptr<const Heightfield> slopedTerrain(double baseHeight_m) {
    auto t = std::make_shared<Heightfield>();
    t->nx = 20, t->ny = 20, t->spacing_m = 0.5, t->originX_m = -4.0, t->originY_m = 1.0;
    t->height_m.resize(size_t(t->nx) * t->ny);
    for (int j = 0; j < t->ny; ++j)
        for (int i = 0; i < t->nx; ++i)
            t->height_m[size_t(j) * t->nx + i] = float(baseHeight_m + 0.1 * i);
    return t;
}

WindField emptyField(std::shared_ptr<const Heightfield> terrain = nullptr) {
    return WindField(NX, NY, NZ, H, WS_MIN, std::move(terrain),
                     std::vector<uint8_t>(size_t(NX) * NY * NZ, 1));
}

// World position of a face of each kind (sim/WindField.h: x-face i of row (j, k) at wsMin + (i,
// j+1/2, k+1/2) h).
std::array<double, 3> facePosition(int axis, int i, int j, int k) {
    std::array<double, 3> p{WS_MIN[0] + (i + 0.5) * H, WS_MIN[1] + (j + 0.5) * H,
                            WS_MIN[2] + (k + 0.5) * H};
    p[axis] -= 0.5 * H;
    return p;
}

template <class F>
void fillFaces(WindField& f, F&& value) {
    for (int k = 0; k < NZ; ++k)
        for (int j = 0; j < NY; ++j)
            for (int i = 0; i <= NX; ++i)
                f.u_mps()[i + size_t(NX + 1) * (j + size_t(NY) * k)] =
                    value(0, facePosition(0, i, j, k));
    for (int k = 0; k < NZ; ++k)
        for (int j = 0; j <= NY; ++j)
            for (int i = 0; i < NX; ++i)
                f.v_mps()[i + size_t(NX) * (j + size_t(NY + 1) * k)] =
                    value(1, facePosition(1, i, j, k));
    for (int k = 0; k <= NZ; ++k)
        for (int j = 0; j < NY; ++j)
            for (int i = 0; i < NX; ++i)
                f.w_mps()[i + size_t(NX) * (j + size_t(NY) * k)] =
                    value(2, facePosition(2, i, j, k));
}

// A point whose every stencil lies inside the face grids (at least one cell from each side).
std::array<double, 3> interiorPoint(std::mt19937& rng) {
    std::uniform_real_distribution<double> ux(1.0, NX - 1.0), uy(1.0, NY - 1.0), uz(1.0, NZ - 1.0);
    return {WS_MIN[0] + ux(rng) * H, WS_MIN[1] + uy(rng) * H, WS_MIN[2] + uz(rng) * H};
}

}  // namespace

// Trilinear interpolation reproduces a linear field exactly, each component from its own faces.
TEST(WindFieldSampling, LinearFieldIsReproducedExactly) {
    WindField f = emptyField();
    auto linear = [](int c, const std::array<double, 3>& p) {
        const double a[3][4] = {
            {1.5, 0.3, -0.2, 0.1}, {-2.0, 0.05, 0.4, -0.3}, {0.25, -0.1, 0.2, 0.6}};
        return a[c][0] + a[c][1] * p[0] + a[c][2] * p[1] + a[c][3] * p[2];
    };
    fillFaces(f, linear);
    std::mt19937 rng(7);
    for (int n = 0; n < 500; ++n) {
        const auto p = interiorPoint(rng);
        const auto u = f.velocityAt_mps(p[0], p[1], p[2]);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(u[c], linear(c, p), 1e-12) << "component " << c;
    }
}

// Inside the box our sampler and OpenVDB's staggered box sampler read the same MAC grid the same
// way: voxel (i, j, k) of a staggered Vec3 grid holds the x-, y- and z-faces on cell (i, j, k)'s
// low sides, which is our face indexing. At the box sides they part on purpose: we hold the
// nearest face layer, OpenVDB falls back to the background value.
TEST(WindFieldSampling, MatchesOpenVdbStaggeredBoxSamplerInsideTheBox) {
    openvdb::initialize();
    WindField f = emptyField();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> value(-20.0, 20.0);
    fillFaces(f, [&](int, const std::array<double, 3>&) { return value(rng); });

    openvdb::Vec3DGrid::Ptr grid = openvdb::Vec3DGrid::create(openvdb::Vec3d(0.0));
    grid->setGridClass(openvdb::GRID_STAGGERED);
    auto acc = grid->getAccessor();
    for (int k = 0; k <= NZ; ++k)
        for (int j = 0; j <= NY; ++j)
            for (int i = 0; i <= NX; ++i) {
                openvdb::Vec3d faces(0.0);
                if (j < NY && k < NZ) faces.x() = f.u(i, j, k);
                if (i < NX && k < NZ) faces.y() = f.v(i, j, k);
                if (i < NX && j < NY) faces.z() = f.w(i, j, k);
                acc.setValue(openvdb::Coord(i, j, k), faces);
            }
    for (int n = 0; n < 2000; ++n) {
        const auto p = interiorPoint(rng);
        // Index space of a cell-centred grid: voxel (i, j, k)'s centre at wsMin + (i + 1/2) h.
        const openvdb::Vec3R index((p[0] - WS_MIN[0]) / H - 0.5, (p[1] - WS_MIN[1]) / H - 0.5,
                                   (p[2] - WS_MIN[2]) / H - 0.5);
        const openvdb::Vec3d vdb = openvdb::tools::StaggeredBoxSampler::sample(grid->tree(), index);
        const auto ours = f.velocityAt_mps(p[0], p[1], p[2]);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ours[c], vdb[c], 1e-11) << "component " << c << " sample " << n;
    }

    // The grid gale builds for OpenVDB (float faces, world transform) samples the same in world
    // space, to float precision (|u| <= 20 m/s: 2e-5 m/s).
    const openvdb::Vec3SGrid::Ptr faces = staggeredVelocityGrid(f);
    EXPECT_EQ(faces->getGridClass(), openvdb::GRID_STAGGERED);
    openvdb::tools::GridSampler<openvdb::Vec3SGrid, openvdb::tools::StaggeredBoxSampler> sampler(
        *faces);
    for (int n = 0; n < 2000; ++n) {
        const auto p = interiorPoint(rng);
        const openvdb::Vec3s vdb = sampler.wsSample(openvdb::Vec3d(p[0], p[1], p[2]));
        const auto ours = f.velocityAt_mps(p[0], p[1], p[2]);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ours[c], vdb[c], 2e-5) << "component " << c << " sample " << n;
    }
}

// The terrain test alone decides between velocityAt_mps and velocityAboveTerrainAt_mps; a
// geometry names the terrain it was made with.
TEST(WindFieldSampling, TerrainTestIsTheOnlyDifferenceFromTheUncheckedSampler) {
    WindField f =
        emptyField(slopedTerrain(11.0));  // ground from 11 m (x = -4) rising 0.2 m per metre
    fillFaces(f, [](int c, const std::array<double, 3>& p) { return 3.0 + c + 0.1 * p[2]; });
    std::mt19937 rng(3);
    int below = 0, above = 0;
    for (int n = 0; n < 1000; ++n) {
        const auto p = interiorPoint(rng);
        const auto checked = f.velocityAt_mps(p[0], p[1], p[2]);
        const auto unchecked = f.velocityAboveTerrainAt_mps(p[0], p[1], p[2]);
        if (f.belowTerrain(p[0], p[1], p[2])) {
            ++below;
            for (int c = 0; c < 3; ++c) EXPECT_EQ(checked[c], 0.0);
            EXPECT_NE(unchecked[0], 0.0);
        } else {
            ++above;
            for (int c = 0; c < 3; ++c) EXPECT_EQ(checked[c], unchecked[c]);
        }
    }
    EXPECT_GT(below, 50);
    EXPECT_GT(above, 50);
    // Outside the box both give zero.
    const auto outside =
        f.velocityAboveTerrainAt_mps(WS_MIN[0] - 1.0, WS_MIN[1] + 1.0, WS_MIN[2] + 1.0);
    for (double c : outside) EXPECT_EQ(c, 0.0);

    EXPECT_TRUE(f.geometry() != emptyField().geometry());
    const WindField same(NX, NY, NZ, H, WS_MIN, nullptr,
                         std::vector<uint8_t>(size_t(NX) * NY * NZ, 1));
    EXPECT_TRUE(emptyField().geometry() == same.geometry());
    EXPECT_TRUE(emptyField(slopedTerrain(11.0)).geometry() !=
                f.geometry());  // another terrain object
}

// Reading u and v at one point and w at another gives each component as the ordinary sampler
// reads it at that component's point.
TEST(WindFieldSampling, ComponentsAtTwoPointsMatchTheOrdinarySamplerAtEach) {
    WindField f = emptyField();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> value(-10.0, 10.0);
    fillFaces(f, [&](int, const std::array<double, 3>&) { return value(rng); });
    for (int n = 0; n < 500; ++n) {
        const auto a = interiorPoint(rng), b = interiorPoint(rng);
        const auto split = f.velocityComponentsAt_mps(a, b);
        const auto atA = f.velocityAboveTerrainAt_mps(a[0], a[1], a[2]);
        const auto atB = f.velocityAboveTerrainAt_mps(b[0], b[1], b[2]);
        EXPECT_EQ(split[0], atA[0]);
        EXPECT_EQ(split[1], atA[1]);
        EXPECT_EQ(split[2], atB[2]);
    }
    const auto outside = f.velocityComponentsAt_mps({WS_MIN[0] - 1.0, WS_MIN[1], WS_MIN[2]},
                                                    {WS_MIN[0], WS_MIN[1] - 1.0, WS_MIN[2]});
    for (double c : outside) EXPECT_EQ(c, 0.0);
}

// A face is solved when it carries flux and its centre is in the air; a point reads only solved
// faces well above the ground and not next to it, nor below the lowest cell centre (u, v).
TEST(WindFieldSampling, SolvedFacesAreFlowFacesWithTheirCentreAboveTheGround) {
    auto t = std::make_shared<Heightfield>();
    t->nx = t->ny = 20, t->spacing_m = 0.5, t->originX_m = -4.0, t->originY_m = 1.0;
    t->height_m.assign(size_t(t->nx) * t->ny,
                       float(WS_MIN[2] + 0.3 * H));  // ground cut 0.3 cells up
    const WindField f(NX, NY, NZ, H, WS_MIN, t, std::vector<uint8_t>(size_t(NX) * NY * NZ, 1));
    EXPECT_TRUE(f.isFlowFace(0, 3, 3, 0));    // both cells air
    EXPECT_TRUE(f.isSolvedFace(0, 3, 3, 0));  // centre 0.5 cells up, ground 0.3
    EXPECT_FALSE(f.isFlowFace(2, 3, 3, 0));   // the box bottom
    EXPECT_FALSE(f.isSolvedFace(2, 3, 3, 0));
    EXPECT_TRUE(f.isSolvedFace(2, 3, 3, 1));
    const double x = WS_MIN[0] + 4.2 * H, y = WS_MIN[1] + 3.1 * H;
    EXPECT_FALSE(f.readsOnlySolvedFaces(x, y, WS_MIN[2] + 0.4 * H));  // below the first centre
    EXPECT_TRUE(f.readsOnlySolvedFaces(x, y, WS_MIN[2] + 0.6 * H,
                                       WindField::COMPONENT_U | WindField::COMPONENT_V));
    EXPECT_FALSE(f.readsOnlySolvedFaces(x, y, WS_MIN[2] + 0.6 * H,
                                        WindField::COMPONENT_W));  // reads the bottom
    EXPECT_TRUE(f.readsOnlySolvedFaces(x, y, WS_MIN[2] + 1.6 * H));
    EXPECT_FALSE(
        f.readsOnlySolvedFaces(WS_MIN[0] - 1.0, y, WS_MIN[2] + 1.6 * H));  // outside the box
}

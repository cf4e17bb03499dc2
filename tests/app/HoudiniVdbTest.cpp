// gale solve --houdini: a .vdb Houdini reads as it expects: a "vel" grid and a terrain level set
// "surface", y-up (gale's (x, y, z) is Houdini's (x, z, -y)), numbered by the scene's frame.

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <string>

#include "AppTestSupport.h"

namespace gale::app {
namespace {

using test::TempDir;

/// vel is float32 of speeds of a few m/s.
constexpr double FLOAT_SPEED_TOLERANCE_MPS = 1e-5;

TEST(HoudiniVdb, SouthWindPointsAlongMinusZAndTheGroundIsTheZeroOfTheSurface) {
    TempDir dir;
    // From the south (180): gale +y, Houdini -z. Flat ground at z = 0, cells of 1 m.
    test::writeFile(
        dir / "s.toml",
        "[terrain]\nkind = \"flat\"\nsize_m = [12.0, 12.0]\nspacing_m = 1.0\n"
        "[wind]\nkind = \"solved\"\nfrom_deg = 180.0\nprofile = \"uniform\"\nspeed_mps = 4.0\n"
        "[solver]\nvoxel_size_m = 1.0\ntop_m = 8.0\n");
    const auto r = test::runGale({"solve", dir / "s.toml", "-o", dir / "out/w.vdb", "--houdini"});
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    const std::string path = dir / "out/w_houdini.0001.vdb";
    ASSERT_TRUE(test::fs::exists(path)) << r.describe();
    EXPECT_NE(test::readFile(dir / "out/w.json").find("w_houdini.0001.vdb"), std::string::npos);

    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    auto vel = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("vel"));
    auto surface = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("surface"));
    file.close();
    ASSERT_TRUE(vel && surface);
    EXPECT_EQ(surface->getGridClass(), openvdb::GRID_LEVEL_SET);
    // gale cell centre (6.5, 6.5, 3.5) is Houdini (6.5, 3.5, -6.5).
    const openvdb::Coord c =
        vel->transform().worldToIndexCellCentered(openvdb::Vec3d(6.5, 3.5, -6.5));
    const openvdb::Vec3s v = vel->getConstAccessor().getValue(c);
    EXPECT_NEAR(v.x(), 0.0, FLOAT_SPEED_TOLERANCE_MPS);
    EXPECT_NEAR(v.y(), 0.0, FLOAT_SPEED_TOLERANCE_MPS);
    EXPECT_NEAR(v.z(), -4.0, FLOAT_SPEED_TOLERANCE_MPS);
    // The first cell centre above the ground, 0.5 m up: the level set holds +0.5 m there.
    const openvdb::Coord g =
        surface->transform().worldToIndexCellCentered(openvdb::Vec3d(6.5, 0.5, -6.5));
    EXPECT_NEAR(surface->getConstAccessor().getValue(g), 0.5, 1e-6);
}

}  // namespace
}  // namespace gale::app

// The turbulent kinetic energy in the .vdb (sim/VdbIO.h): written as the "tke" float grid (its
// units, placement and class in the metadata) and read back to float precision, on cubic cells
// and on stretched layers ("tke_layers"); a file without it reads as no turbulence.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/VdbIO.h"
#include "sim/WindField.h"

namespace gale::sim {
namespace {

// Ground sloping across the box, so that some columns start with rock cells and some with cut
// ones.
Heightfield slope() {
    Heightfield t;
    t.nx = t.ny = 17, t.spacing_m = 1.0;
    t.height_m.resize(size_t(t.nx) * t.ny);
    for (int j = 0; j < t.ny; ++j)
        for (int i = 0; i < t.nx; ++i) t.height_m[size_t(j * t.nx + i)] = float(0.3 * i + 0.1 * j);
    return t;
}

// One value per cell, distinct and not representable as a float (so the round trip shows float
// rounding, and only that), 0 in rock as the closure leaves it.
std::vector<double> someTke(const AirDomain& d) {
    std::vector<double> tke(d.layout().cellCount(), 0.0);
    for (int k = 0; k < d.nz(); ++k)
        for (int j = 0; j < d.ny(); ++j)
            for (int i = 0; i < d.nx(); ++i)
                if (d.isAir(i, j, k))
                    tke[d.layout().cellIndex(i, j, k)] = 0.1 + 0.0123456789 * (i + 3 * j + 7 * k);
    return tke;
}

void expectRoundTrip(const AirDomain& d, const std::string& path, const char* gridName) {
    const WindField field(d.layout(), d.terrainShared(), d.airFlags());
    const std::vector<double> tke = someTke(d);
    field.writeVdb(path, {}, tke);
    EXPECT_NE(vdbGridStrings(path, gridName).count("units"), 0u);
    EXPECT_EQ(vdbGridStrings(path, gridName).at("units"), "m^2/s^2");
    EXPECT_EQ(vdbGridStrings(path, gridName).at("class"), "unknown");
    const std::vector<double> back = readCellTke(path, field);
    ASSERT_EQ(back.size(), tke.size());
    size_t air = 0;
    for (size_t c = 0; c < tke.size(); ++c) {
        // Float storage, exactly: the value read is the float nearest the value written.
        EXPECT_EQ(back[c], double(float(tke[c]))) << "cell " << c;
        air += d.airFlags()[c] != 0;
    }
    EXPECT_GT(air, 0u);
    EXPECT_LT(air, tke.size());  // rock cells too, which read 0
}

TEST(TkeVdb, RoundTripsToFloatPrecisionOnCubicCells) {
    const AirDomain d(slope(), DomainSpec{1.0, 12.0, 2e9});
    expectRoundTrip(d, std::string(GALE_BINARY_DIR) + "/tke_vdb_cubic.vdb", TKE_GRID);
}

TEST(TkeVdb, RoundTripsToFloatPrecisionOnStretchedLayers) {
    DomainSpec spec{1.0, 30.0, 2e9};
    spec.firstCell_m = 0.5;
    spec.stretchRatio = 1.2;
    const AirDomain d(slope(), spec);
    ASSERT_FALSE(d.layout().uniformZ());
    const std::string path = std::string(GALE_BINARY_DIR) + "/tke_vdb_layers.vdb";
    expectRoundTrip(d, path, TKE_LAYERS_GRID);
    EXPECT_NE(vdbGridStrings(path, TKE_LAYERS_GRID).count("z_levels_m"), 0u);
}

TEST(TkeVdb, AFieldWithoutTurbulenceReadsAsNoneAndAWrongSizeIsRefused) {
    const AirDomain d(slope(), DomainSpec{1.0, 12.0, 2e9});
    const WindField field(d.layout(), d.terrainShared(), d.airFlags());
    const std::string path = std::string(GALE_BINARY_DIR) + "/tke_vdb_none.vdb";
    field.writeVdb(path);
    EXPECT_TRUE(readCellTke(path, field).empty());
    for (const std::string& name : vdbGridNames(path)) EXPECT_NE(name, TKE_GRID);
    EXPECT_THROW(field.writeVdb(path, {}, std::vector<double>(3, 1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace gale::sim

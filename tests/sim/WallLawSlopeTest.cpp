/// \file WallLawSlopeTest.cpp
/// The log-law wall stress on sloping ground (sim/MomentumTurbulence.h): on an inclined plane a
/// uniform flow along the slope loses, in one stress step, the log law's stress over the wetted
/// area along the slope, with its vertical share on the w faces.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/MomentumTurbulence.h"
#include "sim/SurfaceLayer.h"

namespace gale::sim {
namespace {

constexpr double CELL_M = 1.0, Z0_M = 0.03, SPEED_MPS = 4.0;

/// The plane z = slope x (m) over 24 m x 6 m, sampled every half cell, lifted so that its lowest
/// point is 2 m up.
Heightfield inclinedPlane(double slope) {
    Heightfield hf;
    hf.spacing_m = 0.5 * CELL_M;
    hf.nx = 49, hf.ny = 13;
    hf.height_m.resize(size_t(hf.nx) * hf.ny);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            hf.height_m[size_t(j) * hf.nx + i] = float(2.0 + slope * i * hf.spacing_m);
    return hf;
}

/// The faces the solvers update: open ones (AirDomain closes every face touching rock).
std::vector<uint8_t> unknowns(const std::vector<float>& open) {
    std::vector<uint8_t> ok(open.size());
    for (size_t f = 0; f < open.size(); ++f) ok[f] = open[f] > 0.f;
    return ok;
}

class InclinedPlane : public ::testing::TestWithParam<double> {};

TEST_P(InclinedPlane, OneStepRemovesTheLogLawStressOverTheWettedAreaAlongTheSlope) {
    const double s = GetParam();
    const Heightfield terrain = inclinedPlane(s);
    DomainSpec spec;
    spec.voxelSize_m = CELL_M;
    spec.top_m = 2.0 + s * 24.0 + 12.0;
    const AirDomain D(terrain, spec);
    SurfaceLayerSettings layer;
    layer.enabled = true;
    layer.roughness_m = Z0_M;
    TurbulentStress stress(D, layer, /*molecularViscosity_m2ps=*/0.0, unknowns(D.openFractionsX()),
                           unknowns(D.openFractionsY()), unknowns(D.openFractionsZ()));
    // A uniform flow along the slope, |U| = SPEED_MPS: no strain, so no eddy viscosity, and the
    // step's only force is the wall's.
    const double q = std::sqrt(1.0 + s * s);
    const double u0 = SPEED_MPS / q, w0 = s * SPEED_MPS / q;
    const GridLayout& L = D.layout();
    std::vector<double> U(L.count(Placement::FaceX), u0), V(L.count(Placement::FaceY), 0.0),
        W(L.count(Placement::FaceZ), w0);
    const std::vector<double> U0 = U, W0 = W;
    constexpr double DT_S = 1e-5;  // the implicit step's change is the force times dt to O(dt^2)
    (void)stress.apply(DT_S, U, V, W);

    // Oracle: the log law along the normal, tau = (kappa |U| / ln(n_p / z0))^2, n_p = z_p / q
    // the wall sample's distance to the plane (z_p half the face's open height above the
    // ground), acting over the wetted area q h^2 per h^2 of horizontal face, along the flow:
    // x share tau q (u / |U|) = tau, z share tau q (w / |U|) = tau s, each per unit horizontal
    // area, over the face's control-volume height.
    constexpr double FORCE_TOLERANCE = 1e-3;  // relative; dt^2 terms are 1e-5 of it
    const int j = D.ny() / 2;
    int checked = 0;
    for (int i = 4; i <= D.nx() - 4; ++i) {
        int kl = -1;
        for (int k = 0; k < D.nz() && kl < 0; ++k)
            if (D.openFractionX(i, j, k) > 0.f) kl = k;
        ASSERT_GE(kl, 0);
        const double ground =
            terrain.sample(D.wsMin_m()[0] + i * CELL_M, D.wsMin_m()[1] + (j + 0.5) * CELL_M);
        const double open = std::clamp(L.zFace_m(kl + 1) - ground, 0.05 * CELL_M, 1.5 * CELL_M);
        if (open < 0.5 * CELL_M) continue;  // slivers: the clamp, not the law, sets them
        const double np = 0.5 * open / q;
        const double cw = surface::KAPPA / std::log(np / Z0_M);
        const double tau = cw * cw * SPEED_MPS * SPEED_MPS;
        const size_t f = L.faceXIndex(i, j, kl);
        const double forceX = (U0[f] - U[f]) * open / DT_S;
        EXPECT_NEAR(forceX / tau, 1.0, FORCE_TOLERANCE) << "slope " << s << ", x-face " << i;
        ++checked;
    }
    EXPECT_GE(checked, 8);
    // The vertical share, on the lowest open w face of each cell column (the top of its wall
    // cell, control volume the distance between the two centres around it).
    if (s > 0.0) {
        int checkedW = 0;
        for (int i = 4; i < D.nx() - 4; ++i) {
            int kw = -1;
            for (int k = 1; k <= D.nz() && kw < 0; ++k)
                if (D.openFractionZ(i, j, k) > 0.f && D.isAir(i, j, k - 1)) kw = k;
            ASSERT_GE(kw, 1);
            const double ground = terrain.sample(D.wsMin_m()[0] + (i + 0.5) * CELL_M,
                                                 D.wsMin_m()[1] + (j + 0.5) * CELL_M);
            const double open =
                std::clamp(L.zFace_m(kw) - ground, 0.05 * L.dz_m(kw - 1), 1.5 * L.dz_m(kw - 1));
            if (open < 0.5 * L.dz_m(kw - 1)) continue;  // a sliver wall cell: the clamp's
            const double np = 0.5 * open / q;
            const double cw = surface::KAPPA / std::log(np / Z0_M);
            const double tau = cw * cw * SPEED_MPS * SPEED_MPS;
            const size_t f = L.faceZIndex(i, j, kw);
            const double forceZ = (W0[f] - W[f]) * L.centreGap_m(kw) / DT_S;
            EXPECT_NEAR(forceZ / (tau * s), 1.0, FORCE_TOLERANCE) << "slope " << s << ", w " << i;
            ++checkedW;
        }
        EXPECT_GE(checkedW, 3);  // steep slopes make many wall cells slivers
    }
}

// Flat, and the slopes at which the old horizontal law's drag was 1.10, 1.47 and 2.2 times too
// small.
INSTANTIATE_TEST_SUITE_P(WallLaw, InclinedPlane, ::testing::Values(0.0, 0.3, 0.63, 1.0));

}  // namespace
}  // namespace gale::sim

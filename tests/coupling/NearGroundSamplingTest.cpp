// What the grass reads near the ground (coupling/NearGround.h): the mass-consistent field over a
// hemisphere against the exact potential flow, through the sampler the grass uses, and the
// log-law mode against the log profile over flat rough ground. The ground sits between cell
// faces (cut cells) in both.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "coupling/FieldSampling.h"
#include "coupling/NearGround.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"
#include "validation/ExactSolutions.h"

using namespace gale;

namespace {

namespace exact = gale::validation::exact;

// --- the hemisphere: potential flow past a sphere, exact --------------------------------------

// A 16 m knoll: at 2 m cells (gale's usual) that is 8 cells per radius.
constexpr double RADIUS_M = 16.0;
// The ground sits this fraction of a cell above the box's bottom face: cut, between the faces.
constexpr double GROUND_OFFSET_CELLS = 0.3;

// The exact flow (validation/ExactSolutions.h) over ground lifted to zb.
struct Hemisphere {
    exact::HemisphereFlow flow{RADIUS_M, 1.0, 3.0 * RADIUS_M, 3.0 * RADIUS_M};
    double zb = 0.0;  // ground height, metres
    double c() const { return flow.cx_m; }
    glm::dvec3 exact(const glm::dvec3& p) const {
        const auto u = flow.velocity(p.x, p.y, p.z - zb);
        return {u[0], u[1], u[2]};
    }
};

struct SolvedHemisphere {
    Hemisphere geometry;
    sim::Heightfield terrain;
    sim::SteadyWindResult solved;
};

// Box 6R x 6R x 3R with the exact potential carried on its open faces (as the solver's own
// hemisphere benchmark, docs/solver.md), so the box adds no truncation error.
SolvedHemisphere solveHemisphere(int cellsPerRadius) {
    SolvedHemisphere s;
    const double h = RADIUS_M / cellsPerRadius;
    s.geometry.zb = GROUND_OFFSET_CELLS * h;
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Hemisphere;
    ts.sizeX_m = ts.sizeY_m = 2 * s.geometry.c();
    ts.spacing_m = RADIUS_M / 128;
    ts.radius_m = RADIUS_M;
    ts.centerX_m = ts.centerY_m = s.geometry.c();
    s.terrain = sim::makeTerrain(ts);
    for (float& z : s.terrain.height_m) z += float(s.geometry.zb);
    const sim::AirDomain domain(s.terrain, sim::DomainSpec{h, s.geometry.zb + 3.0 * RADIUS_M, 2e9});
    const Hemisphere g = s.geometry;
    auto phi = [g](double x, double y, double z) { return g.flow.phi(x, y, z - g.zb); };
    sim::AmbientWind ambient;
    ambient.profile = sim::WindProfile::Uniform;
    ambient.speed_mps = 1.0;
    sim::SolverSettings settings;
    settings.relativeTolerance = 1e-9;  // the solve's own error well below what is compared
    settings.maxIterations = 200;
    s.solved = sim::solveSteadyWind(domain, ambient, {}, settings, phi);
    EXPECT_TRUE(s.solved.report.converged) << s.solved.report.message;
    return s;
}

// Grass vertices: on the cap up to 40 degrees from the top (slopes up to 0.84, steeper than
// grass-bearing hillsides commonly are) and on the flat ground from 1.3 R out, 16 azimuths each.
// The steeper band, down to the hemisphere's vertical foot, is measured in docs/coupling.md (known
// limits): there u and v are solved only well above the grass and the first-order near-wall law
// carries them down with 1-2 % error.
render::TerrainMesh grassOn(const SolvedHemisphere& s) {
    render::TerrainMesh mesh;
    auto add = [&](double x, double y) {
        mesh.wsPosition_m.push_back(glm::vec3(x, y, s.terrain.sample(x, y)));
        mesh.wsNormal.push_back(glm::vec3(0, 0, 1));  // unused by the sampler
    };
    const double c = s.geometry.c();
    add(c, c);  // the top
    for (int ib = 0; ib < 16; ++ib) {
        const double be = ib * 2 * PI / 16;
        for (int ia = 1; ia <= 4; ++ia) {
            const double al = radiansFromDegrees(ia * 10.0);
            add(c + RADIUS_M * std::sin(al) * std::cos(be),
                c + RADIUS_M * std::sin(al) * std::sin(be));
        }
        for (double rho : {1.3, 1.6, 2.0, 2.5})
            add(c + rho * RADIUS_M * std::cos(be), c + rho * RADIUS_M * std::sin(be));
    }
    mesh.nx = int(mesh.wsPosition_m.size()), mesh.ny = 1;
    return mesh;
}

struct GrassError {
    double relL2 = 0;   // sqrt(sum |u - u_exact|^2 / sum |u_exact|^2)
    double maxRel = 0;  // max |u - u_exact| / U
};

GrassError grassError(const SolvedHemisphere& s, double height_m, coupling::NearGroundModel model) {
    const render::TerrainMesh mesh = grassOn(s);
    coupling::NearGround ng;
    ng.model = model;
    const std::vector<glm::vec3> got = coupling::sampleAtGrass(s.solved.field, mesh, height_m, ng);
    double e2 = 0, n2 = 0;
    GrassError e;
    for (size_t v = 0; v < got.size(); ++v) {
        const glm::vec3& p = mesh.wsPosition_m[v];
        const glm::dvec3 ue = s.geometry.exact(glm::dvec3(p.x, p.y, double(p.z) + height_m));
        const glm::dvec3 d = glm::dvec3(got[v]) - ue;
        const double dd = d.x * d.x + d.y * d.y + d.z * d.z;
        e2 += dd, n2 += ue.x * ue.x + ue.y * ue.y + ue.z * ue.z;
        e.maxRel = std::max(e.maxRel, std::sqrt(dd));
    }
    e.relL2 = std::sqrt(e2 / n2);
    return e;
}

}  // namespace

// The target: over cut ground at 8 cells per radius the grass reads the exact potential
// flow within 1 % at 0.25 m and 0.5 m (mass-consistent field, the sampler's default treatment).
// Also prints the before/after table of docs/coupling.md.
TEST(NearGroundSampling, MassConsistentGrassHeightErrorOverCutGroundIsBelowOnePercent) {
    constexpr double MAX_REL_L2 = 0.01;  // the target
    for (int cells : {4, 8}) {
        const SolvedHemisphere s = solveHemisphere(cells);
        for (double height : {0.25, 0.5, 1.0}) {
            const GrassError before =
                grassError(s, height, coupling::NearGroundModel::Interpolated);
            const GrassError after = grassError(s, height, coupling::NearGroundModel::Tangential);
            std::printf(
                "cells/R %d  height %.2f m  interpolated L2 %.4f max %.4f  tangential L2 %.4f max "
                "%.4f\n",
                cells, height, before.relL2, before.maxRel, after.relL2, after.maxRel);
            if (cells == 8 && height <= 0.5) {
                EXPECT_LE(after.relL2, MAX_REL_L2) << "height " << height;
            }
        }
    }
}

// --- the log law over flat rough ground -----------------------------------------------------

namespace {

constexpr double LOG_H_M = 2.0;  // cell edge
constexpr int LOG_N = 6, LOG_NZ = 8;
constexpr double USTAR_MPS = 0.4, Z0_M = 0.03;

// A field over flat ground at groundOffset_m above the box bottom whose solved faces (centre above
// the ground) hold the log profile u = u*/kappa ln(z/z0) along +x at their heights above the
// ground; the faces the ground closes hold copies of the face above, as the solvers leave them.
sim::WindField logLawField(double groundOffset_m) {
    auto t = std::make_shared<sim::Heightfield>();
    t->nx = t->ny = 2 * LOG_N + 1, t->spacing_m = LOG_H_M / 2;
    t->height_m.assign(size_t(t->nx) * t->ny, float(groundOffset_m));
    std::vector<uint8_t> air(size_t(LOG_N) * LOG_N * LOG_NZ, 1);  // every cell's top face is open
    sim::WindField f(LOG_N, LOG_N, LOG_NZ, LOG_H_M, {0.0, 0.0, 0.0}, t, air);
    for (int k = LOG_NZ - 1; k >= 0; --k)
        for (int j = 0; j < LOG_N; ++j)
            for (int i = 0; i <= LOG_N; ++i) {
                // The first layer with its centre in the air holds its value where the solver's
                // wall function does when it is the layer the ground cuts: at the centroid of its
                // open part, half its open height above the ground (a layer above holds it at its
                // centre).
                const double centre = (k + 0.5) * LOG_H_M - groundOffset_m;
                const bool cut = groundOffset_m > k * LOG_H_M;
                const double z =
                    cut && centre > 0.0 ? 0.5 * ((k + 1) * LOG_H_M - groundOffset_m) : centre;
                const size_t n = i + size_t(LOG_N + 1) * (j + size_t(LOG_N) * k);
                f.u_mps()[n] = z > 0.0 ? sim::surface::logLawSpeed_mps(USTAR_MPS, z, Z0_M)
                                       : f.u_mps()[n + size_t(LOG_N + 1) * LOG_N];
            }
    return f;
}

render::TerrainMesh flatGrass(double groundOffset_m) {
    render::TerrainMesh mesh;
    for (double x : {3.0, 5.5, 6.0, 8.25})
        for (double y : {2.5, 6.0, 9.0}) {
            mesh.wsPosition_m.push_back(glm::vec3(x, y, groundOffset_m));
            mesh.wsNormal.push_back(glm::vec3(0, 0, 1));
        }
    mesh.nx = int(mesh.wsPosition_m.size()), mesh.ny = 1;
    return mesh;
}

}  // namespace

// Log-law mode: below the first cell centre the grass reads the log profile itself, for ground
// at several places between the faces (the first centre 0.9, 0.4 and 0.1 cells above it).
TEST(NearGroundSampling, LogLawModeReproducesTheLogProfileUnderTheFirstCell) {
    // The profile is read at a cell centre (exact there) and carried by the log law's ratio; what
    // is left is float storage of the map and of the velocities.
    constexpr double REL_TOL = 1e-5;
    coupling::NearGround ng;
    ng.model = coupling::NearGroundModel::LogLaw;
    ng.roughness_m = Z0_M;
    for (double offset : {0.1 * LOG_H_M, 0.6 * LOG_H_M, 0.9 * LOG_H_M}) {
        const sim::WindField f = logLawField(offset);
        const render::TerrainMesh mesh = flatGrass(offset);
        for (double height : {0.25, 0.5, 1.0}) {
            const double exact = sim::surface::logLawSpeed_mps(USTAR_MPS, height, Z0_M);
            const std::vector<glm::vec3> got = coupling::sampleAtGrass(f, mesh, height, ng);
            for (const glm::vec3& u : got) {
                EXPECT_NEAR(u.x, exact, REL_TOL * exact)
                    << "ground " << offset << " m, height " << height << " m";
                EXPECT_NEAR(u.y, 0.0, REL_TOL * exact);
                EXPECT_NEAR(u.z, 0.0, REL_TOL * exact);
            }
            // The field as it stands holds the first solved value instead: the error this removes.
            ng.model = coupling::NearGroundModel::Interpolated;
            const std::vector<glm::vec3> before = coupling::sampleAtGrass(f, mesh, height, ng);
            ng.model = coupling::NearGroundModel::LogLaw;
            if (height < 0.5) {
                EXPECT_GT(std::abs(before[0].x - exact), 0.05 * exact) << "offset " << offset;
            }
        }
    }
}

// The wall sample (issue 24, "Why" 3): the solver holds the first open layer's velocity at the
// centroid of its open part (its start field, balance profile and wall function), so a grass
// sampler that read it as sitting at the cell centre, below the centroid on a cut cell, carried
// it down to the grass too fast. Here the field is the solver's own: the mass-consistent start
// over flat ground cut through the first cell at several fractions, whose first guess sets each
// face's log-law speed at its open part's centroid (sim/SteadyWind.cpp) and which the projection
// leaves as it is (the flow is divergence-free already). The grass-height speed must equal the
// log law itself, u*/kappa ln(z/z0) with u* from the ambient wind, for z0 = 0.03, 0.1 and 0.3 m.
TEST(NearGroundSampling, GrassReadsTheFirstCutCellAtTheSolversWallSample) {
    // What is left: the projection's residual (relative tolerance 1e-9) and float storage of the
    // map and the velocities.
    constexpr double REL_TOL = 1e-5;
    // Reading the first cut cell at its centre (the sampler before) is off by at least this at
    // some grass height for each z0: the error the test must see removed (2-34 %).
    constexpr double MIN_CENTRE_READ_ERROR = 0.02;
    constexpr double H_M = 4.0, TOP_M = 40.0;
    for (double z0 : {0.03, 0.1, 0.3}) {
        sim::AmbientWind wind;
        wind.speed_mps = 6.0, wind.referenceHeight_m = 10.0, wind.roughness_m = z0;
        wind.direction_deg = 20.0;
        const double uStar = sim::surface::frictionVelocity_mps(6.0, 10.0, z0);
        double worstBefore = 0.0;
        // Open fractions of the first layer: from the centre 0.45 cells above the ground down to
        // 0.26 (the sampler reads a first centre at least a quarter cell up); 0.6 reads the
        // second layer, whose value sits at its centre.
        for (double open : {0.95, 0.9, 0.8, 0.76, 0.6}) {
            const double ground = (1.0 - open) * H_M;
            sim::Heightfield t;
            t.nx = t.ny = 9, t.spacing_m = H_M;
            t.height_m.assign(size_t(t.nx) * t.ny, float(ground));
            const sim::AirDomain domain(t, sim::DomainSpec{H_M, TOP_M, 2e9});
            sim::SolverSettings settings;
            settings.relativeTolerance = 1e-9;
            const sim::SteadyWindResult r = sim::solveSteadyWind(domain, wind, {}, settings);
            ASSERT_TRUE(r.report.converged) << r.report.message;
            coupling::NearGround ng;
            ng.model = coupling::NearGroundModel::LogLaw;
            ng.roughness_m = z0;
            render::TerrainMesh mesh;
            for (double x : {13.0, 16.0, 19.5})
                for (double y : {14.0, 18.0}) {
                    mesh.wsPosition_m.push_back(glm::vec3(x, y, ground));
                    mesh.wsNormal.push_back(glm::vec3(0, 0, 1));
                }
            mesh.nx = int(mesh.wsPosition_m.size()), mesh.ny = 1;
            for (double height : {0.25, 0.5, 0.75, 1.0}) {
                if (height <= 2.0 * z0) continue;  // the log law's clamp: no profile to compare
                const double exact = sim::surface::logLawSpeed_mps(uStar, height, z0);
                const std::vector<glm::vec3> got =
                    coupling::sampleAtGrass(r.field, mesh, height, ng);
                for (const glm::vec3& u : got)
                    EXPECT_NEAR(std::hypot(u.x, u.y), exact, REL_TOL * exact)
                        << "z0 " << z0 << " m, open " << open << ", height " << height << " m";
                // The centre read: the first layer's value carried down from its centre.
                const double centre = (open - 0.5) * H_M;
                if (centre >= 0.25 * H_M) {
                    const double atCentroid =
                        sim::surface::logLawSpeed_mps(uStar, 0.5 * open * H_M, z0);
                    const double before =
                        sim::surface::logLawRescale_mps(atCentroid, height, centre, z0);
                    worstBefore = std::max(worstBefore, before / exact - 1.0);
                    std::printf("z0 %.2f m  open %.2f  grass %.2f m  centre read %+.1f %%\n", z0,
                                open, height, 100.0 * (before / exact - 1.0));
                }
            }
        }
        EXPECT_GE(worstBefore, MIN_CENTRE_READ_ERROR) << "z0 " << z0;
    }
}

// Extreme roughness: grass below z0 + d reads zero, never NaN or Inf; a very smooth surface stays
// finite; bad parameters are refused with the scene key.
TEST(NearGroundSampling, ExtremeRoughnessGivesFiniteWindAndBadValuesAreRefused) {
    const sim::WindField f = logLawField(0.3 * LOG_H_M);
    const render::TerrainMesh mesh = flatGrass(0.3 * LOG_H_M);
    coupling::NearGround ng;
    ng.model = coupling::NearGroundModel::LogLaw;
    for (double z0 : {1e-9, 0.5, 5.0})
        for (double d : {0.0, 0.4, 3.0}) {
            ng.roughness_m = z0, ng.displacement_m = d;
            for (double height : {0.0, 0.25, 1.0}) {
                for (const glm::vec3& u : coupling::sampleAtGrass(f, mesh, height, ng)) {
                    EXPECT_TRUE(std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z));
                    if (height <= z0 + d) {
                        EXPECT_EQ(u.x, 0.0f) << "z0 " << z0 << " d " << d << " height " << height;
                    }
                }
            }
        }
    for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        ng.roughness_m = bad, ng.displacement_m = 0.0;
        try {
            coupling::GrassSampler sampler(mesh, 0.5, ng);
            FAIL() << "accepted roughness " << bad;
        } catch (const ParameterError& e) {
            EXPECT_EQ(e.key(), "wind.roughness_m");
        }
        ng.roughness_m = 0.03, ng.displacement_m = bad == 0.0 ? -0.5 : bad;
        try {
            coupling::GrassSampler sampler(mesh, 0.5, ng);
            FAIL() << "accepted displacement " << ng.displacement_m;
        } catch (const ParameterError& e) {
            EXPECT_EQ(e.key(), "solver.displacement_height_m");
        }
    }
}

// --- the read plan ------------------------------------------------------------------------------

namespace {

// Equal, or both NaN in the same components (a non-finite point's read keeps its NaN position).
bool sameBits(const glm::vec3& a, const glm::vec3& b) {
    for (int c = 0; c < 3; ++c)
        if (!(a[c] == b[c] || (std::isnan(a[c]) && std::isnan(b[c])))) return false;
    return true;
}

}  // namespace

// The sampler's per-step path (stencils and weights planned once per geometry, then 24 face
// reads) against the direct path (planNearGroundRead, WindField::velocityComponentsAt_mps at its
// points, the map) for every model, over the cut-ground hemisphere, at grass heights and at
// points outside the box; then again for a second field of the same geometry, read through the
// same (kept) plan. The reads planned from kept solved-face flags equal the field's own.
TEST(NearGroundSampling, PlannedSamplerEqualsTheDirectReadOnCutGround) {
    // The planned path repeats the direct path's arithmetic in the same order: the bound.
    constexpr double REL_TOL = 1e-12;
    const SolvedHemisphere s = solveHemisphere(4);
    render::TerrainMesh mesh = grassOn(s);
    const double side = 2 * s.geometry.c();
    for (double x : {-1.0, 0.5 * side, side + 1.0})  // outside the box, and on its side
        mesh.wsPosition_m.push_back(glm::vec3(x, side + 0.5, 0.0f));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    mesh.wsPosition_m.push_back(glm::vec3(nan, 0.5 * side, 0.0f));  // reads zero, never NaN
    mesh.wsNormal.resize(mesh.wsPosition_m.size(), glm::vec3(0, 0, 1));
    mesh.nx = int(mesh.wsPosition_m.size());
    sim::WindField second = s.solved.field;  // same geometry, other velocities
    for (auto* a : {&second.u_mps(), &second.v_mps(), &second.w_mps()})
        for (size_t n = 0; n < a->size(); ++n) (*a)[n] = -2.0 * (*a)[n] + 1e-3 * double(n % 17);
    for (auto model : {coupling::NearGroundModel::Tangential, coupling::NearGroundModel::LogLaw,
                       coupling::NearGroundModel::Interpolated})
        for (double height : {0.25, 0.5, 1.0, 3.0}) {
            coupling::NearGround ng;
            ng.model = model;
            coupling::GrassSampler sampler(mesh, height, ng);
            int nearGroundReads = 0;  // points read off their own stencils, for the coverage
            for (const sim::WindField* field :
                 std::vector<const sim::WindField*>{&s.solved.field, &second}) {
                // The plan from kept solved-face flags (the sampler uses them on large meshes).
                const coupling::SolvedFaces faces(*field);
                const std::vector<glm::vec3> got = sampler.sample(*field);
                ASSERT_EQ(got.size(), mesh.wsPosition_m.size());
                for (size_t v = 0; v < got.size(); ++v) {
                    const glm::vec3& p = mesh.wsPosition_m[v];
                    const coupling::NearGroundRead r = coupling::planNearGroundRead(
                        *field, glm::dvec3(p.x, p.y, double(p.z) + height), ng);
                    const coupling::NearGroundRead kept = coupling::planNearGroundRead(
                        faces, glm::dvec3(p.x, p.y, double(p.z) + height), ng);
                    EXPECT_TRUE(sameBits(kept.wsUV_m, r.wsUV_m) && sameBits(kept.wsW_m, r.wsW_m) &&
                                kept.map == r.map)
                        << "model " << int(model) << " height " << height << " vertex " << v;
                    const auto u = field->velocityComponentsAt_mps(
                        {r.wsUV_m.x, r.wsUV_m.y, r.wsUV_m.z}, {r.wsW_m.x, r.wsW_m.y, r.wsW_m.z});
                    const glm::vec3 want =
                        coupling::applyNearGroundMap(r.map, glm::vec3(u[0], u[1], u[2]));
                    if (r.wsUV_m != glm::vec3(glm::dvec3(p.x, p.y, double(p.z) + height)))
                        ++nearGroundReads;
                    for (int c = 0; c < 3; ++c) {
                        ASSERT_TRUE(std::isfinite(got[v][c]));
                        EXPECT_LE(std::abs(double(got[v][c]) - double(want[c])),
                                  REL_TOL * std::abs(double(want[c])))
                            << "model " << int(model) << " height " << height << " vertex " << v
                            << " component " << c;
                    }
                }
            }
            if (model != coupling::NearGroundModel::Interpolated) {
                EXPECT_GT(nearGroundReads, 0) << "height " << height;
            }
        }
}

/// \file NearBladesTest.cpp
/// The near level's blade geometry (render/NearBlades.h, shaders/shell.vert BLADES): the texture's
/// blade statistics on a hand-drawn texture; placement on the mesh's own triangles, within the
/// radius, at the texture's density, stable when the camera moves, thinned by a density map as the
/// shells are; and, through transform feedback from the drawing shader, every blade keeps its
/// length, stands straight in calm air and bends downwind in a gust; the blades change no pixel
/// whose ray cannot meet one.

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "RenderTestUtil.h"
#include "render/Bend.h"
#include "render/CameraMath.h"
#include "render/DensityMap.h"
#include "render/GlContext.h"
#include "render/NearBlades.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

using detail::BLADE_SEGMENTS;
using detail::BLADE_STRIP_VERTICES;
using detail::BladeGround;
using detail::BladeInstance;
using detail::BladeStatistics;
using detail::BladeView;

void paint(Image& image, int x, int y, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    uint8_t* px = &image.rgba[(static_cast<size_t>(y) * image.width + x) * 4u];
    px[0] = r, px[1] = g, px[2] = b, px[3] = a;
}

TEST(BladeStatistics, CountsFootprintsWidthHeightsAndColoursOfAHandDrawnTexture) {
    Image image = test::makeUniformImage(16, 40, 30, 20, 0);
    // Five blades: a 2 x 2 red one of full height, a green 1 x 3 of half height beside a blue
    // texel of another height (a separate blade), a lone texel, and one across the wrapping edge.
    for (int y = 2; y < 4; ++y)
        for (int x = 2; x < 4; ++x) paint(image, x, y, 255, 0, 0, 255);
    for (int y = 8; y < 11; ++y) paint(image, 8, y, 0, 255, 0, 128);
    paint(image, 9, 8, 0, 0, 255, 100);
    paint(image, 12, 3, 0, 0, 255, 64);
    paint(image, 15, 13, 255, 255, 255, 200);
    paint(image, 0, 13, 255, 255, 255, 200);
    const BladeStatistics s = detail::bladeStatistics(image, 2.0f);
    EXPECT_FLOAT_EQ(s.bladesPerM2, 5.0f / 4.0f);
    // Footprints of 4, 3, 1, 1 and 2 texels: mean 2.2 texels of (2 m / 16)^2.
    EXPECT_NEAR(s.width_m, std::sqrt(11.0f / 5.0f) * 2.0f / 16.0f, 1e-6f);
    // One blade each of heights 64, 100, 128, 200, 255 (/ 255): quantile k / 256 of 5 blades.
    const float heights[5] = {64, 100, 128, 200, 255};
    for (int k = 0; k < 256; ++k) {
        const int blade = std::min(4, static_cast<int>((k + 0.5) / 256.0 * 5.0));
        EXPECT_FLOAT_EQ(s.heightAtQuantile[k], heights[blade] / 255.0f) << "quantile " << k;
    }
    // Colours as the shells show them, filtered over a texel (a 3 x 3 tent of weights 1/4, 1/2,
    // 1/4). The top bin holds the red 2 x 2 blade alone: each of its texels sees red with weight
    // (1/2 + 1/4)^2 = 9/16 and the soil (40, 30, 20) with the rest.
    const float soil = 7.0f / 16.0f;
    const glm::vec3 top = s.colorByHeight[detail::BLADE_COLOR_BINS - 1];
    EXPECT_NEAR(top.r, 9.0f / 16.0f + soil * 40.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(top.g, soil * 30.0f / 255.0f, 1e-6f);
    // Half height (bin 7) holds the green 1 x 3 blade: its texels see green with weights 3/8, 1/2
    // and 3/8, the blue texel beside the first with 1/8 and 1/16, the soil with 1/2, 7/16, 5/8.
    const glm::vec3 half = s.colorByHeight[127 * detail::BLADE_COLOR_BINS / 255];
    EXPECT_NEAR(half.g, (1.25f + (1.5625f) * 30.0f / 255.0f) / 3.0f, 1e-6f);
    EXPECT_NEAR(half.b, (0.1875f + 1.5625f * 20.0f / 255.0f) / 3.0f, 1e-6f);

    const BladeStatistics bare = detail::bladeStatistics(test::makeUniformImage(8, 1, 2, 3, 0), 1);
    EXPECT_EQ(bare.bladesPerM2, 0.0f);
}

/// A terrain grid with its interleaved vertices (position, normal, key light) as BladeGround
/// reads the renderer's buffer.
struct Ground {
    TerrainMesh mesh;
    std::vector<float> vertices;
    BladeGround ground;
    explicit Ground(TerrainMesh m) : mesh(std::move(m)) {
        for (size_t v = 0; v < mesh.wsPosition_m.size(); ++v) {
            const glm::vec3 p = mesh.wsPosition_m[v], n = mesh.wsNormal[v];
            vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z, 1.0f});
        }
        ground.nx = mesh.nx;
        ground.ny = mesh.ny;
        ground.planRegular = detail::planRegular(mesh.nx, mesh.ny, mesh.wsPosition_m,
                                                 ground.origin_m, ground.spacing_m);
        ground.vertices = vertices.data();
        ground.stride = 7;
        ground.keyLightAt = 6;
    }
};

BladeStatistics syntheticStats(float bladesPerM2) {
    BladeStatistics s;
    s.bladesPerM2 = bladesPerM2;
    s.width_m = 0.04f;  // 2 pixels at 6 m for a focal length of 300 px
    s.heightAtQuantile.fill(0.8f);
    s.colorByHeight.fill(glm::vec3(0.2f, 0.5f, 0.1f));
    return s;
}

BladeView viewFrom(glm::vec3 eye, glm::vec3 target, float fov_deg, int budget) {
    Camera camera;
    camera.wsPosition_m = eye;
    camera.wsTarget_m = target;
    camera.fovY_deg = fov_deg;
    camera.near_m = 0.01f;
    BladeView view;
    view.clipFromWorld = clipFromWorld(camera, 1.0f);
    view.wsEye_m = eye;
    view.focal_px = 300.0f;
    view.grassHeight_m = 0.5f;
    view.budget = budget;
    return view;
}

glm::vec3 rootOf(const BladeInstance& b) { return {b.root[0], b.root[1], b.root[2]}; }

/// The height of the mesh at plan point (x, y), from the plane of the triangle holding it: the
/// triangle found by which side of each edge the point is on, the plane by a cross product.
float meshHeight(const TerrainMesh& mesh, float x, float y) {
    const float x0 = mesh.wsPosition_m[0].x, y0 = mesh.wsPosition_m[0].y;
    const float dx = mesh.wsPosition_m[1].x - x0, dy = mesh.wsPosition_m[mesh.nx].y - y0;
    const int i = static_cast<int>(std::floor((x - x0) / dx));
    const int j = static_cast<int>(std::floor((y - y0) / dy));
    const auto p = [&](int a, int b) {
        return mesh.wsPosition_m[static_cast<size_t>(b) * mesh.nx + a];
    };
    const glm::vec3 tris[2][3] = {{p(i, j), p(i + 1, j), p(i + 1, j + 1)},
                                  {p(i, j), p(i + 1, j + 1), p(i, j + 1)}};
    for (const auto& t : tris) {
        bool inside = true;
        for (int e = 0; e < 3; ++e) {
            const glm::vec3 a = t[e], b = t[(e + 1) % 3];
            const float side = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
            inside = inside && side >= -1e-6f;
        }
        if (!inside) continue;
        const glm::vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        return t[0].z - (n.x * (x - t[0].x) + n.y * (y - t[0].y)) / n.z;
    }
    ADD_FAILURE() << "no triangle holds (" << x << ", " << y << ")";
    return 0.0f;
}

TEST(NearBlades, RootsLieOnTheMeshTrianglesWithinTheRadiusAndTheBudget) {
    Ground g(test::makeGridMesh(41, 41, 10.0f, 3.0f, [](float x, float y) {
        return 0.3f * x + 0.4f * std::sin(1.3f * y) + 0.2f * std::cos(0.7f * x * y);
    }));
    ASSERT_TRUE(g.ground.planRegular);
    const BladeView view = viewFrom({0.0f, -8.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 5000);
    const detail::NearBladeSet set =
        detail::placeNearBlades(g.ground, syntheticStats(400.0f), view);
    ASSERT_GT(set.radius_m, 0.0f);
    EXPECT_LE(static_cast<int>(set.blades.size()), view.budget);
    EXPECT_GT(static_cast<int>(set.blades.size()), 500);
    EXPECT_LE(set.radius_m, set.capRadius_m);
    for (const BladeInstance& b : set.blades) {
        const glm::vec3 r = rootOf(b);
        EXPECT_NEAR(r.z, meshHeight(g.mesh, r.x, r.y), 1e-4f) << r.x << ", " << r.y;
        EXPECT_LT(glm::distance(r, view.wsEye_m), set.radius_m);
        EXPECT_NEAR(glm::length(glm::vec3(b.normal[0], b.normal[1], b.normal[2])), 1.0f, 1e-5f);
        // In front of the camera.
        const glm::vec4 clip = view.clipFromWorld * glm::vec4(r, 1.0f);
        EXPECT_GT(clip.w, 0.0f);
    }
}

TEST(NearBlades, InsideTheInnerRadiusTheyHaveTheTexturesBladeDensity) {
    Ground g(test::makeFlatMesh(81, 8.0f, 3.0f));
    // Straight down from 1 m with a 150-degree view: the disc within R is all in the frustum.
    const glm::vec3 eye(0.0f, 0.0f, 1.0f);
    const float rho = 400.0f;
    const BladeView view = viewFrom(eye, {0.0f, 1e-3f, 0.0f}, 150.0f, 4000);
    const detail::NearBladeSet set = detail::placeNearBlades(g.ground, syntheticStats(rho), view);
    ASSERT_GT(set.radius_m, 1.2f);
    // The nearest blade stands right under the eye, 1 m away: R_in = 1 + 0.7 (R - 1).
    const float inner = set.innerRadius_m;  // 3-D distance
    EXPECT_NEAR(inner, 1.0f + 0.7f * (set.radius_m - 1.0f), 0.01f);
    const float planInner = std::sqrt(inner * inner - 1.0f);  // on the ground
    int count = 0;
    for (const BladeInstance& b : set.blades)
        if (glm::distance(rootOf(b), eye) < inner) ++count;
    const double expected = rho * 3.14159265 * planInner * planInner;
    EXPECT_NEAR(count / expected, 1.0, 0.06) << count << " blades, " << expected << " expected";
    // And the fade band thins: fewer per area between R_in and R than inside.
    int band = 0;
    for (const BladeInstance& b : set.blades)
        if (glm::distance(rootOf(b), eye) >= inner) ++band;
    const float planOuter = std::sqrt(set.radius_m * set.radius_m - 1.0f);
    const double bandArea = 3.14159265 * (planOuter * planOuter - planInner * planInner);
    EXPECT_LT(band / bandArea, 0.75 * rho);
    EXPECT_GT(band / bandArea, 0.25 * rho);
}

TEST(NearBlades, TheSameBladesStandThereWhenTheCameraMoves) {
    Ground g(test::makeFlatMesh(41, 10.0f, 3.0f));
    const BladeStatistics stats = syntheticStats(300.0f);
    const glm::vec3 a(0.0f, -3.0f, 1.5f), b(0.25f, -2.9f, 1.5f);
    const auto setA = detail::placeNearBlades(g.ground, stats, viewFrom(a, {0, 3, 0}, 60, 3000));
    const auto setB = detail::placeNearBlades(g.ground, stats, viewFrom(b, {0, 3, 0}, 60, 3000));
    // Inside R_in of both eyes and well inside both views every blade of the lattice stands in
    // both frames.
    const float keep = std::min(setA.innerRadius_m, setB.innerRadius_m);
    const glm::mat4 clipA = viewFrom(a, {0, 3, 0}, 60, 1).clipFromWorld;
    const glm::mat4 clipB = viewFrom(b, {0, 3, 0}, 60, 1).clipFromWorld;
    const auto inBoth = [&](const BladeInstance& blade) {
        const glm::vec3 r = rootOf(blade);
        for (const glm::mat4* m : {&clipA, &clipB}) {
            const glm::vec4 c = *m * glm::vec4(r, 1.0f);
            if (!(c.w > 0.0f && std::abs(c.x) < 0.8f * c.w && std::abs(c.y) < 0.8f * c.w))
                return false;
        }
        return glm::distance(r, a) < keep && glm::distance(r, b) < keep;
    };
    std::map<std::pair<float, float>, float> fromA;
    for (const BladeInstance& blade : setA.blades)
        if (inBoth(blade))
            fromA[{blade.root[0], blade.root[1]}] = blade.blade[0] + 10.0f * blade.blade[2];
    int shared = 0;
    for (const BladeInstance& blade : setB.blades) {
        if (!inBoth(blade)) continue;
        const auto it = fromA.find({blade.root[0], blade.root[1]});
        ASSERT_NE(it, fromA.end())
            << "a blade appeared at " << blade.root[0] << ", " << blade.root[1];
        EXPECT_EQ(it->second, blade.blade[0] + 10.0f * blade.blade[2]);
        ++shared;
    }
    EXPECT_EQ(shared, static_cast<int>(fromA.size()));
    EXPECT_GT(shared, 50);
}

TEST(NearBlades, ADensityMapRemovesTheBladesItRemovesFromTheShells) {
    Ground g(test::makeFlatMesh(41, 10.0f, 3.0f));
    const GrassTexture texture = generateGrassTexture(GrassTextureSpec{});
    const BladeStatistics stats = detail::bladeStatistics(texture.levels[0], 3.0f);
    const std::vector<float> cuts = densityCuts(texture.levels[0]);
    ASSERT_GT(stats.bladesPerM2, 100.0f);
    DensityMap map;  // west half bare, east half full
    map.width = 2;
    map.height = 1;
    map.density = {0.0f, 1.0f};
    map.wsMin_m = glm::vec2(-10.0f);
    map.wsSize_m = glm::vec2(20.0f);
    g.ground.density = &map;
    g.ground.densityCuts = &cuts;
    const BladeView view = viewFrom({0.0f, -4.0f, 1.5f}, {0.0f, 2.0f, 0.0f}, 70.0f, 8000);
    const auto set = detail::placeNearBlades(g.ground, stats, view);
    int east = 0;
    for (const BladeInstance& b : set.blades) {
        EXPECT_GE(b.root[0], 0.0f) << "a blade on the bare half";
        east += b.root[0] >= 0.0f;
    }
    EXPECT_GT(east, 200);

    // Half density: the blades kept are exactly those at or above the shells' cut, about half.
    map.width = 1;
    map.density = {0.5f};
    const auto half = detail::placeNearBlades(g.ground, stats, view);
    g.ground.density = nullptr;
    const auto full = detail::placeNearBlades(g.ground, stats, view);
    const float cut = cuts[static_cast<size_t>(std::lround(0.5f * float(cuts.size() - 1)))];
    int above = 0;
    for (const BladeInstance& b : full.blades) above += b.blade[0] >= cut;
    for (const BladeInstance& b : half.blades) EXPECT_GE(b.blade[0], cut);
    // The budget holds more blades when half are cut, so R grows: compare within the full set's R.
    int halfInside = 0;
    for (const BladeInstance& b : half.blades)
        halfInside += glm::distance(rootOf(b), view.wsEye_m) < full.innerRadius_m;
    int fullInside = 0, aboveInside = 0;
    for (const BladeInstance& b : full.blades) {
        const bool inside = glm::distance(rootOf(b), view.wsEye_m) < full.innerRadius_m;
        fullInside += inside;
        aboveInside += inside && b.blade[0] >= cut;
    }
    EXPECT_EQ(halfInside, aboveInside);
    EXPECT_NEAR(double(aboveInside) / fullInside, 0.5, 0.12);
    EXPECT_GT(above, 0);
}

TEST(NearBlades, NoBudgetNoBladesTextureOrIrregularGridPlacesNone) {
    Ground g(test::makeFlatMesh(21, 5.0f, 3.0f));
    const BladeView view = viewFrom({0.0f, -3.0f, 1.5f}, {0.0f, 2.0f, 0.0f}, 60.0f, 0);
    EXPECT_TRUE(detail::placeNearBlades(g.ground, syntheticStats(300), view).blades.empty());
    BladeView some = view;
    some.budget = 1000;
    EXPECT_TRUE(detail::placeNearBlades(g.ground, syntheticStats(0), some).blades.empty());
    TerrainMesh bent = g.mesh;
    bent.wsPosition_m[5].x += 0.1f;
    glm::vec2 o, h;
    EXPECT_FALSE(detail::planRegular(bent.nx, bent.ny, bent.wsPosition_m, o, h));
    EXPECT_FALSE(detail::placeNearBlades(g.ground, syntheticStats(300), some).blades.empty());
    EXPECT_FLOAT_EQ(detail::nearBladeFade(0.69f, 0.7f, 1.0f), 1.0f);
    EXPECT_NEAR(detail::nearBladeFade(0.85f, 0.7f, 1.0f), 0.5f, 1e-6f);
    EXPECT_FLOAT_EQ(detail::nearBladeFade(1.0f, 0.7f, 1.0f), 0.0f);
    EXPECT_FLOAT_EQ(detail::nearBladeFade(0.1f, 0.0f, 0.0f), 0.0f);
}

/// A flat 10 m meadow with real grass, 0.5 m high, seen from 1.5 m.
struct BladeScene {
    std::unique_ptr<GlContext> context = createOsMesaContext(320, 240);
    ShellRenderer renderer{*context};
    TerrainMesh mesh = test::makeFlatMesh(41, 5.0f, 3.0f);
    Camera camera;
    GrassParams grass;
    explicit BladeScene(int nearBlades) {
        renderer.setTerrain(mesh);
        grass.height_m = 0.5f;
        grass.shells = 16;
        grass.nearBlades = nearBlades;
        renderer.setGrass(grass, generateGrassTexture(GrassTextureSpec{}));
        Lighting lighting;
        lighting.lights.push_back({glm::vec3(30.0f, -20.0f, 40.0f), glm::vec3(1.0f), {1, 0, 0}});
        renderer.setLighting(lighting);
        camera.wsPosition_m = glm::vec3(0.0f, -3.0f, 1.5f);
        camera.wsTarget_m = glm::vec3(0.0f, 2.0f, 0.0f);
    }
};

TEST(NearBladesGl, EachBladeKeepsItsLengthStandsInCalmAirAndBendsDownwind) {
    BladeScene scene(6000);
    // Calm west of x = 0, a strong gust east of it, the wind along +x.
    const GrassWind wind = test::makeUniformWind(scene.mesh, glm::vec3(1, 0, 0), 0.0f, 0.9f);
    const NearBladeCapture capture = scene.renderer.captureNearBlades(scene.camera, wind);
    ASSERT_GT(capture.blades.size(), 500u);
    ASSERT_EQ(capture.vertices.size(), capture.blades.size() * BLADE_STRIP_VERTICES);
    int calm = 0, gust = 0;
    for (size_t k = 0; k < capture.blades.size(); ++k) {
        const BladeInstance& b = capture.blades[k];
        const glm::vec3* v = &capture.vertices[k * BLADE_STRIP_VERTICES];
        const glm::vec3 root = rootOf(b);
        const float length = b.blade[0] * scene.grass.height_m;
        glm::vec3 spine[BLADE_SEGMENTS + 1];
        for (int l = 0; l < BLADE_SEGMENTS; ++l) {
            spine[l] = 0.5f * (v[2 * l] + v[2 * l + 1]);
            // The edges: the blade's width, tapering, across its spine.
            const float width = b.blade[1] * std::sqrt(1.0f - float(l) / BLADE_SEGMENTS);
            EXPECT_NEAR(glm::distance(v[2 * l], v[2 * l + 1]), width, 1e-5f);
        }
        spine[BLADE_SEGMENTS] = v[2 * BLADE_SEGMENTS];
        EXPECT_LT(glm::distance(spine[0], root), 1e-5f);
        float polyline = 0.0f;
        for (int l = 0; l < BLADE_SEGMENTS; ++l) {
            polyline += glm::distance(spine[l], spine[l + 1]);
            EXPECT_GE(spine[l + 1].z, -1e-5f) << "below the ground";
        }
        // The chords of the bent curve: at most its length, short of it by under 1 %.
        EXPECT_LE(polyline, length * 1.0001f);
        EXPECT_GE(polyline, length * 0.99f);
        const glm::vec3 tip = spine[BLADE_SEGMENTS] - root;
        if (root.x < -0.3f) {  // calm: straight up
            EXPECT_LT(glm::length(glm::vec2(tip)), 1e-5f);
            EXPECT_NEAR(tip.z, length, 1e-5f);
            ++calm;
        } else if (root.x > 0.3f) {  // the gust: the full blade's curve, cut at its height
            // The length-preserving bend of render/Bend.h for the group's tilt times the blade's
            // factor, between its shells at the blade's height fraction.
            const int n = scene.grass.shells;
            std::vector<ShellOffset> full(static_cast<size_t>(n) + 1);
            // (The table ends at the saturated tilt, so a softer blade's tilt stops there.)
            const double tilt = std::min(tipTilt_rad(0.9) * b.blade[3], MAX_TIP_TILT_RAD);
            bendBladeByTiltInto(n, scene.grass.height_m, tilt, scene.grass.stiffness, full.data());
            const double at = b.blade[0] * n;
            const int i0 = std::min(static_cast<int>(at), n - 1);
            const double f = at - i0;
            const double up = full[i0].n_m + f * (full[i0 + 1].n_m - full[i0].n_m);
            const double downwind = full[i0].w_m + f * (full[i0 + 1].w_m - full[i0].w_m);
            // Within the table's tilt rows' interpolation (513 rows over +-81 degrees).
            EXPECT_NEAR(tip.z, up, 2e-3) << "blade " << k;
            EXPECT_NEAR(tip.x, downwind, 2e-3) << "blade " << k;
            EXPECT_GT(tip.x, 0.0f);
            EXPECT_LT(std::abs(tip.y), 1e-5f);
            ++gust;
        }
    }
    EXPECT_GT(calm, 100);
    EXPECT_GT(gust, 100);
}

TEST(NearBladesGl, BladesChangeNoPixelWhoseRayCannotMeetOne) {
    const GrassWind wind =
        test::makeUniformWind(BladeScene(0).mesh, glm::vec3(1, 0, 0), 0.3f, 0.3f);
    BladeScene without(0), with(20000);
    without.renderer.draw(without.camera, wind);
    Image a, b;
    without.context->readPixels(a);
    const FrameStats stats = with.renderer.draw(with.camera, wind);
    with.context->readPixels(b);
    ASSERT_GT(stats.blades, 500);
    const float R = stats.bladeRadius_m, h = with.grass.height_m;
    const glm::vec3 eye = with.camera.wsPosition_m;
    int changed = 0, checked = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const WorldRay ray = pixelRay(with.camera, a.width, a.height, x + 0.5, y + 0.5);
            const size_t p = (static_cast<size_t>(y) * a.width + x) * 4u;
            const bool differs = a.rgba[p] != b.rgba[p] || a.rgba[p + 1] != b.rgba[p + 1] ||
                                 a.rgba[p + 2] != b.rgba[p + 2];
            changed += differs;
            // A blade stands within R of the eye and reaches at most h above the ground (z = 0)
            // and h sideways: a ray that stays above h until it is R + h from the eye misses
            // every blade (its pixel would be the shells' alone).
            const float reach = R + h;
            const glm::vec3 far = ray.wsOrigin_m + reach * ray.wsDirection;
            if (far.z > h && glm::distance(ray.wsOrigin_m, eye) < 0.5f) {
                ++checked;
                EXPECT_FALSE(differs) << "pixel " << x << ", " << y;
            }
        }
    EXPECT_GT(changed, a.width * a.height / 50) << "R " << R << " m, " << stats.blades << " blades";
    EXPECT_GT(checked, 0) << "R " << R;
    EXPECT_GT(checked, a.width * a.height / 4);
}

// A frame depends on the scene, the camera and the wind alone: the first frame of a renderer is
// the frame every later draw gives (the first draw once ran with the density cut's unit unbound,
// so the thinning shells of the near band and the far field showed every blade).
TEST(NearBladesGl, TheFirstFrameIsTheFrameEveryLaterDrawGives) {
    BladeScene scene(6000);
    const GrassWind wind = test::makeUniformWind(scene.mesh, glm::vec3(1, 0, 0), 0.3f, 0.3f);
    Image first, second;
    EXPECT_GT(scene.renderer.draw(scene.camera, wind).blades, 500);
    scene.context->readPixels(first);
    scene.renderer.draw(scene.camera, wind);
    scene.context->readPixels(second);
    EXPECT_EQ(test::compareImages(first, second, 0).differingFraction, 0.0);
}

}  // namespace
}  // namespace gale::render

/// \file SceneLook.cpp
/// The sections of the scene format that say how the frames look and where they go: [lighting]
/// (with the default sun), [camera], [output] and [overlay]; the readers SceneParser calls
/// (SceneKeys.h). Split from SceneParser.cpp, which keeps the terrain, grass and solver sections.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "app/scene/SceneKeys.h"
#include "app/scene/SceneParser.h"
#include "app/scene/SceneSection.h"
#include "base/Numbers.h"
#include "render/RenderLimits.h"

namespace gale::app::detail {
namespace {

/// The sun of a scene without lights (SceneParser.h): warm white, not attenuated.
render::PointLight defaultSun() {
    const double az = radiansFromDegrees(DEFAULT_SUN_AZIMUTH_DEG);
    const double el = radiansFromDegrees(DEFAULT_SUN_ELEVATION_DEG);
    render::PointLight sun;
    sun.wsPosition_m = glm::vec3(DEFAULT_SUN_DISTANCE_M * std::cos(el) * std::cos(az),
                                 DEFAULT_SUN_DISTANCE_M * std::cos(el) * std::sin(az),
                                 DEFAULT_SUN_DISTANCE_M * std::sin(el));
    sun.color = glm::vec3(1.0f, 0.95f, 0.85f);
    return sun;
}

}  // namespace

void readLighting(Context& ctx, Section s) {
    render::Lighting& l = ctx.scene->lighting;
    const bool ambientGiven = s.take("ambient") != nullptr;
    l.ambient = toVec3(s.vec<3>("ambient", fromVec3(l.ambient), closed(0.0, 1e3)));
    l.specularPower =
        static_cast<float>(s.number("specular_power", l.specularPower, closed(1.0, 4096.0)));
    l.specularStrength =
        static_cast<float>(s.number("specular_strength", l.specularStrength, closed(0.0, 1e3)));
    l.selfShadowMin =
        static_cast<float>(s.number("self_shadow_min", l.selfShadowMin, closed(0.0, 1.0)));
    l.shadows = s.boolean("shadows", l.shadows);
    std::vector<Section> lights = s.tables("light");
    s.finish();
    if (static_cast<int>(lights.size()) > maxLights())
        s.failKey("light", "at most " + std::to_string(maxLights()) + " lights (got " +
                               std::to_string(lights.size()) + ")");
    for (Section& ls : lights) {
        render::PointLight light;
        if (!ls.take("position_m")) ls.fail(ls.line(), "", "missing key position_m (required)");
        light.wsPosition_m =
            toVec3(ls.vec<3>("position_m", fromVec3(light.wsPosition_m), floatPosition()));
        light.color = toVec3(ls.vec<3>("color", fromVec3(light.color), closed(0.0, 1e6)));
        const auto att = ls.vec<3>("attenuation", fromVec3(light.attenuation), closed(0.0, 1e6));
        if (!(att[0] + att[1] + att[2] > 0.0))
            ls.failKey("attenuation", "k_c, k_l and k_q cannot all be 0 (got [0, 0, 0])");
        light.attenuation = toVec3(att);
        ls.finish();
        l.lights.push_back(light);
    }
    if (lights.empty()) {
        // A scene without lights gets daylight instead of ambient alone (near black): a sun far
        // enough away to be a direction for any terrain, and (unless ambient is given) a sky.
        l.lights.push_back(defaultSun());
        if (!ambientGiven)
            l.ambient = glm::vec3(DEFAULT_SKY_AMBIENT_RGB[0], DEFAULT_SKY_AMBIENT_RGB[1],
                                  DEFAULT_SKY_AMBIENT_RGB[2]);
        ctx.scene->defaultSun = true;
    }
}

void readCamera(Context& ctx, Section s) {
    render::Camera& c = ctx.scene->camera;
    ctx.scene->autoCameraPosition = !s.take("position_m");
    ctx.scene->autoCameraTarget = !s.take("target_m");
    c.wsPosition_m = toVec3(s.vec<3>("position_m", fromVec3(c.wsPosition_m), floatPosition()));
    c.wsTarget_m = toVec3(s.vec<3>("target_m", fromVec3(c.wsTarget_m), floatPosition()));
    c.fovY_deg = static_cast<float>(s.number("fov_deg", c.fovY_deg, closed(1.0, 179.0)));
    c.near_m = static_cast<float>(s.number("near_m", c.near_m, closed(1e-4, 1e6)));
    c.far_m = static_cast<float>(s.number("far_m", c.far_m, above(0.0, 1e9)));
    ctx.scene->autoCameraFar = !s.given("far_m");  // given() holds once the key was read
    s.finish();
    if (!(c.far_m > c.near_m))
        s.failKey("far_m", "must be greater than near_m = " + Limit::num(c.near_m) + " (got " +
                               Limit::num(c.far_m) + ")");
    if (!ctx.scene->autoCameraPosition && !ctx.scene->autoCameraTarget) {
        const glm::vec3 d = c.wsTarget_m - c.wsPosition_m;
        if (!(d.x * d.x + d.y * d.y + d.z * d.z > 1e-12f))
            s.failKey("target_m", "must differ from position_m (the camera needs a direction)");
    }
}

void readOutput(Context& ctx, Section s) {
    OutputSection& o = ctx.scene->output;
    o.width = static_cast<int>(s.integer("width", o.width, 1, MAX_IMAGE_SIDE_PX));
    o.height = static_cast<int>(s.integer("height", o.height, 1, MAX_IMAGE_SIDE_PX));
    o.frames = static_cast<int>(s.integer("frames", o.frames, 1, MAX_FRAMES));
    o.fps = s.number("fps", o.fps, above(0.0, 1000.0));
    o.startTime_s = s.number("start_time_s", o.startTime_s, closed(-1e9, 1e9));
    o.folder = s.string("folder", "out/" + ctx.scene->name);
    o.prefix = s.string("prefix", o.prefix);
    o.contactSheet = s.boolean("contact_sheet", o.contactSheet);
    o.gif = s.boolean("gif", o.gif);
    o.format = s.string("format", o.format);
    s.finish();
    if (o.format != "png" && o.format != "exr")
        s.failKey("format", "must be \"png\" or \"exr\" (got \"" + o.format + "\")");
    if (o.folder.empty()) s.failKey("folder", "must name a folder (got \"\")");
    const bool prefixOk =
        !o.prefix.empty() && o.prefix.size() <= 100 &&
        std::all_of(o.prefix.begin(), o.prefix.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
        });
    if (!prefixOk)
        s.failKey("prefix",
                  "must be 1-100 letters, digits, '_', '-' or '.' (got \"" + o.prefix + "\")");
    if (auto problem = outputBudgetProblem(o)) s.failKey(problem->key, problem->reason);
}

void readOverlay(Context& ctx, Section s) {
    coupling::OverlaySpec& o = ctx.scene->overlay;
    o.arrows = s.boolean("arrows", o.arrows);
    o.arrowSpacing_m = s.optionalNumber("arrow_spacing_m", above(0.0, 1e6));
    o.arrowHeight_m = s.optionalNumber("arrow_height_m", closed(0.0, 1e6));
    o.slice = s.boolean("slice", o.slice);
    o.sliceHeight_m = s.number("slice_height_m", o.sliceHeight_m, above(0.0, 1e6));
    o.streamlines = s.boolean("streamlines", o.streamlines);
    o.streamlineCount = static_cast<int>(s.integer("streamline_count", o.streamlineCount, 1, 1000));
    o.vortexCores = s.boolean("vortex_cores", o.vortexCores);
    o.vortexQ_per_s2 = s.optionalNumber("vortex_q_per_s2", above(0.0, 1e12));
    o.legend = s.boolean("legend", o.legend);
    o.speedMax_mps = s.optionalNumber("speed_max_mps", above(0.0, 1e6));
    s.finish();
}

}  // namespace gale::app::detail

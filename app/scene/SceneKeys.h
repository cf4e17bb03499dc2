#pragma once
/// \file SceneKeys.h
/// Readers of scene keys that live outside SceneParser.cpp: the DEM terrain keys, the
/// meteorological wind direction and the whole [wind] section. Only the parser's files include it.

#include <array>
#include <glm/vec3.hpp>
#include <string>

#include "app/scene/SceneSection.h"

namespace gale::app::detail {

/// |I| up to 4 turns the blade tip through a full circle ((pi/2) * 4 = 2 pi): beyond that the bend
/// means nothing.
inline constexpr double MAX_INTENSITY = 4.0;

/// A scene's [x, y, z] as a render-side vector.
inline glm::vec3 toVec3(const std::array<double, 3>& a) {
    return glm::vec3(static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]));
}
/// A render-side vector as a scene's [x, y, z] (a struct's default handed to Section::vec).
inline std::array<double, 3> fromVec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

/// [terrain] keys of kind = "dem": `dem` (the raster, as written; the parser resolves it) and
/// `crop_m` ([min x, min y, max x, max y] in the DEM's coordinates, metres). Fills t.crop;
/// returns the `dem` string. Throws SceneError for an empty `dem` when `isDem`, or a crop window
/// that is not an increasing rectangle.
std::string readDemKeys(Section& s, TerrainSection& t, bool isDem);

/// [wind] from_deg: the meteorological direction (degrees clockwise from north = +y, where the
/// wind comes FROM). Sets a.direction_deg (towards, counter-clockwise from +x) when given; throws
/// SceneError when both from_deg and direction_deg are given. Call after direction_deg is read.
void readFromDeg(Section& s, sim::AmbientWind& a);

/// The first-hour note: ambient-wind keys (speed_mps, direction_deg, from_deg, profile, ...)
/// given without `kind` drive `gale solve` and `gale probe` but not the frames, whose default
/// point-source wind ignores them; one note says so and how to see them (kind = "solved").
void noteAmbientWithoutKind(Context& ctx, Section& s);

/// The [wind] section (kind, point source, ambient wind, blade response, gusts and whirlwinds), in
/// SceneWind.cpp.
void readWind(Context& ctx, Section s);

/// The [lighting] (a default sun and sky when it names no light), [camera], [output] and
/// [overlay] sections, in SceneLook.cpp.
void readLighting(Context& ctx, Section s);
void readCamera(Context& ctx, Section s);
void readOutput(Context& ctx, Section s);
void readOverlay(Context& ctx, Section s);

}  // namespace gale::app::detail

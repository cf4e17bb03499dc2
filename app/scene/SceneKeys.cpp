/// \file SceneKeys.cpp
/// Scene keys read outside SceneParser.cpp (SceneKeys.h).

#include "app/scene/SceneKeys.h"

namespace gale::app::detail {

std::string readDemKeys(Section& s, TerrainSection& t, bool isDem) {
    const std::string dem = s.string("dem", "");
    if (s.take("crop_m")) {
        const auto c = s.vec<4>("crop_m", {0, 0, 0, 0}, anyFinite());
        if (!(c[2] > c[0]) || !(c[3] > c[1]))
            s.failKey("crop_m",
                      "expected [min x, min y, max x, max y] with max > min, in the "
                      "DEM's coordinates (got [" +
                          Limit::num(c[0]) + ", " + Limit::num(c[1]) + ", " + Limit::num(c[2]) +
                          ", " + Limit::num(c[3]) + "])");
        t.crop = CropWindow{c[0], c[1], c[2], c[3]};
    }
    if (isDem && dem.empty()) {
        if (s.given("dem")) s.failKey("dem", "must name a raster file (got \"\")");
        s.fail(s.line(), "dem", "kind \"dem\" needs a raster file (dem = \"hill.tif\")");
    }
    return dem;
}

void readFromDeg(Section& s, sim::AmbientWind& a) {
    const std::optional<double> from_deg = s.optionalNumber("from_deg", anyFinite());
    if (!from_deg) return;
    if (s.given("direction_deg"))
        s.failKey("from_deg",
                  "give either from_deg (meteorological: where the wind comes from, "
                  "clockwise from north) or direction_deg (where it blows, "
                  "counter-clockwise from +x), not both");
    a.direction_deg = sim::AmbientWind::towardsFromMeteorological_deg(*from_deg);
}

void noteAmbientWithoutKind(Context& ctx, Section& s) {
    if (s.given("kind")) return;
    for (const char* key :
         {"speed_mps", "direction_deg", "from_deg", "profile", "roughness_m", "reference_height_m"})
        if (s.given(key)) {
            ctx.scene->notes.push_back(
                ctx.scene->where(s.full(key)) +
                ": the ambient wind drives gale solve and gale probe, but the frames use the "
                "default kind \"point_source\", which ignores it; set wind.kind = \"solved\" to "
                "see it in the grass");
            return;
        }
}

}  // namespace gale::app::detail

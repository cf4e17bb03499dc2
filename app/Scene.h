#pragma once
/// \file Scene.h
/// A validated scene: everything a run needs, in SI units (metres, seconds, m/s). Parsed from TOML
/// by parseSceneFile (SceneParser.h); the schema, with every key and its unit, is
/// docs/scene-format.md.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "coupling/GustCurve.h"
#include "coupling/PointSourceWind.h"
#include "render/GrassInput.h"
#include "render/GrassTexture.h"
#include "sim/Heightfield.h"

namespace gale::app {

struct TerrainSection {
    sim::TerrainSpec spec;  ///< procedural kinds
    // kind == Heightmap:
    std::string imagePath;        ///< resolved against the scene file's folder
    double metresPerPixel = 1.0;  ///< horizontal spacing of the image's pixels
    double heightScale_m = 10.0;  ///< height of a full-scale pixel (white / 1.0)
    double heightOffset_m = 0.0;  ///< height of a zero pixel
    int meshStride = 1;           ///< render mesh takes every meshStride-th sample
};

struct GrassSection {
    render::GrassParams params;
    std::string texturePath;  ///< empty: generate from `generated`
    render::GrassTextureSpec generated;
};

enum class WindKind { PointSource };

struct WindSection {
    WindKind kind = WindKind::PointSource;
    coupling::PointSourceSpec pointSource;
    std::optional<coupling::GustCurve> curve;  ///< set after parsing
    std::string curveDescription;              ///< how the curve was given, for `gale check`
    bool autoSource = true;  ///< source_m not given: placed from the terrain when it is built
};

struct OutputSection {
    int width = 640;
    int height = 480;
    int frames = 48;
    double fps = 24.0;
    double startTime_s = 0.0;
    std::string folder = "out/scene";  ///< resolved against the current directory
    std::string prefix = "frame";      ///< frame files are <prefix>_0000.png ...
};

struct Scene {
    std::string path;         ///< the file it came from
    std::string name;         ///< the file's stem, for reports
    std::string description;  ///< the optional top-level `description`
    TerrainSection terrain;
    GrassSection grass;
    WindSection wind;
    render::Lighting lighting;
    render::Camera camera;
    OutputSection output;

    bool autoCameraPosition = true;  ///< camera.position_m not given: a 3/4 view of the terrain
    bool autoCameraTarget = true;    ///< camera.target_m not given: the terrain's centre
    /// Line of each key as written ("terrain.image" -> 7), for messages after parsing.
    std::map<std::string, int> keyLines;
    /// Keys given but not used by this scene (e.g. octaves for a gaussian_hill), one line each.
    std::vector<std::string> notes;

    /// "FILE:LINE: key" for messages about `key` (a dotted scene key); "FILE: key" if the key was
    /// not written in the file (its default is in use).
    std::string where(const std::string& key) const {
        auto it = keyLines.find(key);
        if (it == keyLines.end() || it->second <= 0) return path + ": " + key;
        return path + ":" + std::to_string(it->second) + ": " + key;
    }
};

}  // namespace gale::app

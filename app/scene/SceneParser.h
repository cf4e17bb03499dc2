#pragma once
/// \file SceneParser.h
/// Reads a TOML scene into a validated Scene. The schema, with every key, its type, unit, default
/// and range, is docs/scene-format.md. Unknown keys, wrong types and out-of-range values are
/// errors; every error is a SceneError whose message reads
///   FILE:LINE: section.key: reason (got VALUE)
/// or, for TOML syntax errors, FILE:LINE:COL: reason.
///
/// @code
///   gale::app::Scene scene = gale::app::parseSceneFile("examples/knoll.toml");
///   // scene.grass.params.shells, scene.output.folder, ...
/// @endcode

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "app/scene/Scene.h"

namespace gale::app {

/// Scene limits, checked by the parser (and by the CLI for its overrides).
inline constexpr int MAX_SHELLS = 256;           ///< render::MAX_SHELLS
inline constexpr int MAX_IMAGE_SIDE_PX = 16384;  ///< output width and height
inline constexpr int MAX_FRAMES = 100000;

/// The ambient of a scene that gives neither lights nor `lighting.ambient`: a blue-grey sky.
inline constexpr float DEFAULT_SKY_AMBIENT_RGB[3] = {0.30f, 0.34f, 0.40f};
/// Where the default sun stands: from the south-west (azimuth 225 deg counter-clockwise from +x,
/// behind the default camera), 40 deg above the horizon, DEFAULT_SUN_DISTANCE_M away from the
/// origin, so its direction is the same over any terrain gale can hold.
inline constexpr double DEFAULT_SUN_AZIMUTH_DEG = 225.0;
inline constexpr double DEFAULT_SUN_ELEVATION_DEG = 40.0;
inline constexpr double DEFAULT_SUN_DISTANCE_M = 1.0e6;
/// Bounds on an unsteady run's work unless [unsteady] max_files / max_steps raise them.
inline constexpr int64_t DEFAULT_MAX_SEQUENCE_FILES = 10000;
inline constexpr int64_t DEFAULT_MAX_UNSTEADY_STEPS = 1000000;
inline constexpr int MAX_SAMPLES_PER_SIDE = 16384;  ///< heightfield grid (also sim::makeTerrain's)
inline constexpr double MAX_TERRAIN_BYTES = 4.0 * 1024 * 1024 * 1024;  ///< heightfield + mesh
inline constexpr double MAX_FRAME_BYTES = 2.0 * 1024 * 1024 * 1024;    ///< GL buffers of a frame
/// Bytes per pixel held by GL and the frame loop: colour and depth buffers, read-back, encoding.
inline constexpr double FRAME_BYTES_PER_PIXEL = 16.0;
inline constexpr double MAX_OUTPUT_BYTES = 1024.0 * 1024 * 1024 * 1024;  ///< all frames, estimated
inline constexpr uintmax_t MAX_SCENE_FILE_BYTES = 16u * 1024 * 1024;

/// Most point lights a scene may name: render::MAX_LIGHTS (the shell shader's uniform arrays).
int maxLights();

/// Reads and parses the scene file at `path` (relative paths inside it resolve against its
/// folder). Throws SceneError.
Scene parseSceneFile(const std::string& path);

/// Parses scene text; `pathForMessages` names it in error messages and its folder anchors the
/// relative paths inside (image files). Throws SceneError.
Scene parseSceneString(const std::string& text, const std::string& pathForMessages);

/// Every key the parser reads, dotted ("terrain.size_m", "wind.gusts.start_s": entries of arrays of
/// tables without their index), with its default as TOML text ("[40.0, 40.0]") taken from the
/// struct field the value goes to. Optional keys, whose absence has a meaning of its own (`top_m`,
/// `sample_height_m`, ...), map to "" (no default); required keys carry a placeholder; tables
/// appear as keys of their own ("wind.gust"). docs/scene-format.md lists the same defaults; a test
/// holds the two together.
std::map<std::string, std::string> sceneKeyDefaults();

/// Estimated bytes of the heightfield (nx x ny samples) and its render mesh (every stride-th
/// sample): positions, normals, texture coordinates, wind directions and groups, indices, and
/// their GL copies.
double estimateTerrainBytes(int64_t nx, int64_t ny, int stride);

/// Samples along one side of a procedural terrain, as sim::makeTerrain counts them.
int64_t samplesAlong(double size_m, double spacing_m);

/// An output too large to attempt: the key to blame ("width" or "frames") and why.
struct BudgetProblem {
    std::string key;
    std::string reason;
};
/// Refuses frames whose GL buffers would exceed MAX_FRAME_BYTES and runs whose PNGs would exceed
/// MAX_OUTPUT_BYTES (estimated); std::nullopt when the output is reasonable.
std::optional<BudgetProblem> outputBudgetProblem(const OutputSection& output);

/// The .vdb files an unsteady run writes: one at t = 0, one every output_every_s and one at
/// duration_s.
double plannedSequenceFiles(const UnsteadySection& unsteady);

/// Bytes an unsteady run's .vdb sequence takes at most, each file taking fileBytes at most
/// (sim::vdbWindFile_bytes of the box).
double plannedSequenceBytes(const UnsteadySection& unsteady, double fileBytes);

/// Why the sequence is too large for unsteady.max_output_gib (to be blamed on
/// unsteady.output_every_s), or std::nullopt; fileBytes as for plannedSequenceBytes.
std::optional<std::string> sequenceBytesProblem(const UnsteadySection& unsteady, double fileBytes);

/// Time steps an unsteady run takes at least: duration_s / dt_s, or with the adaptive step
/// duration_s / min(max_dt_s, cfl h / ambient speed) (the field's peak is at least the ambient
/// speed, so the real count is higher).
double plannedUnsteadySteps(const Scene& scene);

/// Estimated bytes of all frames as PNG (noisy grass: about 2 bytes per pixel).
double estimatePngBytes(const OutputSection& output);

/// Human-readable byte count in binary units ("3.2 GiB"), the one unit gale prints sizes in.
std::string formatBytes(double bytes);

}  // namespace gale::app

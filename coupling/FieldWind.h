#pragma once
/// \file FieldWind.h
/// Grass wind from a solved field (docs/design.md 5): for each grass vertex, the velocity at grass
/// height projected onto the tangent plane gives the wind direction; a blade response turns the
/// tangent speed into an intensity; vertices are gathered into K animation-step groups so the bend
/// is still evaluated once per group per shell (Bakay et al. 2002, Table 1). docs/coupling.md
/// explains the choices and their costs.
///
/// The field arrives as steps: velocities already sampled at every grass vertex at time t_k
/// (coupling/FieldSampling.h samples a sim field). Frames between steps interpolate in time.
/// Work per field-step interval is linear in the vertex count and multithreaded; work per frame
/// inside an interval is linear in K only.

#include <cstdint>
#include <deque>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "coupling/GroupOscillators.h"
#include "coupling/WindSource.h"
#include "render/GrassInput.h"

namespace gale::coupling {

/// How a blade answers the wind.
enum class BladeResponse {
    /// I = clamp(V_t / bendSpeed, -maxIntensity, maxIntensity): the blade is where the wind puts
    /// it, with V_t the tangent speed along the vertex's wind direction, m/s.
    Static,
    /// A damped oscillator per group, x'' + 2 zeta omega x' + omega^2 x = omega^2 u(t), driven by
    /// the group's static intensity u(t): a gust overshoots and the grass recovers and sways
    /// (after the stiffness and damping of Sousa 2008, GPU Gems 3 ch. 16). Integrated with the
    /// trapezoidal rule, unconditionally stable, in sub-steps of at most 1/(40 f).
    Oscillator,
};

/// How vertices are gathered into groups.
enum class Grouping {
    /// K equal bins of static intensity over the range the vertices span, reassigned at every
    /// field step; a group's intensity is the mean of its members'. Static response only.
    Levels,
    /// K fixed tiles of the terrain's plan (about sqrt(K) x sqrt(K)): neighbours share a wind
    /// history, which is what an oscillator per group needs.
    Tiles,
    /// One group per vertex: the exact per-vertex bend, the reference the others are measured
    /// against (and a mode in its own right when the cost is acceptable).
    PerVertex,
};

struct FieldWindSpec {
    BladeResponse response = BladeResponse::Static;
    Grouping grouping = Grouping::Levels;
    int groups = 64;             ///< K (ignored for PerVertex), 1..4096
    double bendSpeed_mps = 8.0;  ///< tangent speed that drives I = 1 (tip tilted 75.7 deg), > 0
    double maxIntensity = 1.3;   ///< clamp of |I| for the static map, > 0 (over 1 over-bends)
    double frequency_hz = 0.8;   ///< oscillator natural frequency f = omega / (2 pi), > 0
    double dampingRatio = 0.25;  ///< oscillator zeta, > 0
    /// Give every vertex its place between groups (render::VertexWind::groupCoord) so the
    /// renderer blends neighbouring groups and no stripes show where groups change; false: each
    /// vertex shows its group alone (the paper's). Ignored for PerVertex (exact already).
    bool blendGroups = true;
};

/// Validates a spec; throws gale::ParameterError naming the scene key (wind.groups ...).
void validate(const FieldWindSpec& spec);

const char* bladeResponseName(BladeResponse r);
const char* groupingName(Grouping g);
BladeResponse bladeResponseFromName(const std::string& name);
Grouping groupingFromName(const std::string& name);

class FieldWind : public WindSource {
  public:
    /// The mesh gives positions (for tiles) and normals (for the tangent planes); it must outlive
    /// nothing: FieldWind copies what it needs. Throws gale::ParameterError as validate(spec),
    /// std::logic_error for a mesh without vertices or with as many normals as positions.
    FieldWind(const render::TerrainMesh& mesh, const FieldWindSpec& spec);

    /// Adds field step k at time t_s (seconds, strictly after the previous step's): the world
    /// velocity, m/s, at grass height above every mesh vertex. Non-finite velocities count as
    /// zero wind. Throws std::logic_error on a wrong size or a time out of order.
    void addFieldStep(double t_s, std::vector<glm::vec3> wsVelocity_mps);
    /// Replaces the newest field step's velocities (same time, same units as addFieldStep) after
    /// the field it was sampled from changed in place (a source dropped into the running solver,
    /// coupling/LiveWind.h), and rebuilds the current interval's per-vertex data from it, so the
    /// next update() shows the change without a new step; the oscillators keep their state.
    /// Throws std::logic_error on a wrong size or when there is no step yet.
    void replaceLastStep(std::vector<glm::vec3> wsVelocity_mps);
    /// The turbulent flutter amplitude per vertex, radians (coupling/Flutter.h; empty: none),
    /// handed to the renderer with every interval entered from now on (the current one keeps
    /// its amplitudes; render::VertexWind::flutter_rad). Throws std::logic_error on a size other
    /// than 0 or the vertex count.
    void setFlutter(std::vector<float> flutter_rad);
    /// Forgets steps older than t_s except the one bracketing it (streaming runs keep memory flat).
    void dropStepsBefore(double t_s);
    /// The storage of the last step dropped (its contents are stale; empty if none), for the next
    /// step's samples: a run then reuses one buffer instead of asking the system for fresh pages
    /// at every step (12 MB at a million vertices).
    std::vector<glm::vec3> spareStepBuffer() { return std::move(mSpare); }

    int groupCount() const override { return mGroupCount; }
    /// Frames before the first step see the first step; after the last, the last.
    void update(double t_s, render::GrassWind& wind) override;
    std::string describe() const override;
    /// Keeps the solved field the step velocities were sampled from, so views of the field can
    /// show it (currentField()); the source itself never reads it.
    void keepField(std::shared_ptr<const sim::WindField> field) { mField = std::move(field); }
    const sim::WindField* currentField() const override { return mField.get(); }

    size_t vertexCount() const { return mNormal.size(); }
    /// Per-vertex static intensity at time t_s along the direction the renderer gets (the exact
    /// per-vertex value the grouped one approximates, static response). O(vertices).
    std::vector<float> exactStaticIntensity(double t_s);
    /// Per-vertex intensity the renderer shows for `wind` (groupIntensity[group[v]]).
    static std::vector<float> shownIntensity(const render::GrassWind& wind);

  private:
    std::shared_ptr<const sim::WindField> mField;
    struct Step {
        double t_s;
        std::vector<glm::vec3> wsVelocity_mps;
    };
    void enterInterval(
        size_t first);  // O(vertices): directions, drives, groups for steps first, first+1
    double groupDrive(int g, double t_s) const;
    void advanceOscillators(double t_s);

    FieldWindSpec mSpec;
    int mGroupCount;
    std::vector<glm::vec3> mNormal;
    std::vector<uint32_t> mTile;        // fixed groups for Tiles / PerVertex
    std::vector<glm::vec2> mTileCoord;  // Tiles with blending: each vertex's place in the grid
    int mGroupColumns = 0;              // width of the group grid (render::VertexWind)
    std::deque<Step> mSteps;
    std::vector<glm::vec3> mSpare;  // a dropped step's storage
    std::vector<float> mFlutter;    // setFlutter's amplitudes, copied into every interval

    // The interval [mSteps[mInterval], mSteps[mInterval + 1]] the per-vertex data describe.
    bool mHaveInterval = false;
    size_t mIntervalFirst = 0;
    double mIntervalT0_s = 0.0, mIntervalT1_s = 0.0;
    uint64_t mRevision = 0;
    // The interval's directions and groups, handed to every GrassWind by pointer (never copied,
    // never written while anyone else holds them), and the buffers to write the next one into.
    std::shared_ptr<render::VertexWind> mVertex;
    std::vector<std::shared_ptr<render::VertexWind>> mVertexPool;
    static std::shared_ptr<render::VertexWind> newVertexBuffer(size_t count);
    std::shared_ptr<render::VertexWind> freeVertexBuffer();
    std::vector<float> mDrive0, mDrive1;             // per-vertex static intensity at both ends
    std::vector<double> mGroupDrive0, mGroupDrive1;  // per-group mean drive at both ends

    GroupOscillators mOscillators;
};

}  // namespace gale::coupling

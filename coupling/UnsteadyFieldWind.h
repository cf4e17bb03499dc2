#pragma once
/// \file UnsteadyFieldWind.h
/// Grass wind from the unsteady solver (docs/design.md 4.2 -> 5): owns the air domain and the
/// sim::UnsteadyWindSolver, advances it as update(t) asks, samples the field at grass height after
/// every solver step (coupling::sampleAtGrass) and hands the samples to a coupling::FieldWind,
/// which interpolates frames between steps and groups the vertices. Steps older than the frame
/// are dropped, so memory stays flat however long the run.
///
/// Time runs forward only: a frame earlier than the solver's time sees the interpolation of the
/// steps still held (the renderer asks in increasing order). Work per update: the solver steps
/// up to t, one O(vertices) sampling per step, then FieldWind's O(K) per frame.

#include <memory>
#include <string>
#include <vector>

#include "coupling/FieldSampling.h"
#include "coupling/FieldWind.h"
#include "coupling/WindSource.h"
#include "render/GrassInput.h"
#include "sim/AirDomain.h"
#include "sim/UnsteadyWind.h"
#include "sim/WindField.h"

namespace gale::coupling {

/// Totals over the steps done so far, for reports.
struct UnsteadyRunStats {
    int steps = 0;
    double simulated_s = 0;
    double maxCfl = 0;
    double maxDivergenceScaled = 0;
    int maxProjectionIterations = 0;
    /// The largest relative residual a step's projection left (a live step that reaches
    /// unsteady.live_iterations before the tolerance keeps its residual; the next step starts
    /// from it).
    double maxProjectionResidual = 0;
    bool allConverged = true;
    bool allFinite = true;
    double solve_s = 0;     ///< wall time inside the solver's steps
    double sampling_s = 0;  ///< wall time sampling at grass height
};

/// How the grass reads an unsteady field below its solved faces (coupling/NearGround.h): with the
/// surface layer's wall stress (UnsteadySettings::surfaceLayer) the log law with its z0 and d, as
/// for the steady momentum model; without it the free-slip tangential law of the mass-consistent
/// start (no wall stress slows the air there).
NearGround nearGroundOf(const sim::UnsteadySettings& settings);

class UnsteadyFieldWind : public WindSource {
  public:
    /// Takes the domain and the steady field (the initial state and mean flow). sampleHeight_m:
    /// height above the ground where the grass reads the field. Throws gale::ParameterError on
    /// bad settings or a bad response spec (naming the scene key).
    UnsteadyFieldWind(const render::TerrainMesh& mesh, std::unique_ptr<sim::AirDomain> domain,
                      const sim::WindField& steady, const sim::UnsteadySettings& settings,
                      double referenceSpeed_mps, const FieldWindSpec& response,
                      double sampleHeight_m);

    int groupCount() const override { return mWind.groupCount(); }
    void update(double t_s, render::GrassWind& wind) override;
    /// Steps towards t_s, asking `stop` before every solver step; stopped short, the wind shows
    /// the solver's time (the newest field step). Returns that time, seconds.
    double updateUntil(double t_s, render::GrassWind& wind,
                       const std::function<bool()>& stop) override;
    std::string describe() const override;
    /// The solver's current field (views of the field); valid until the next update().
    const sim::WindField* currentField() const override { return &mSolver->field(); }
    /// The last update's solver work: steps, projection iterations, CFL, divergence, wall time.
    std::string stepReport() const override;

    const sim::UnsteadyWindSolver& solver() const { return *mSolver; }
    /// The solver itself, for sources dropped into the running flow (coupling/LiveWind.h); only
    /// from the thread that calls update().
    sim::UnsteadyWindSolver& solver() { return *mSolver; }
    /// Samples the solver's current field again into the newest field step (the solver's own
    /// time), after a source went into the field in place (coupling/LiveWind.h): the next
    /// update() shows it, blended in over the last step interval, without waiting for a solver
    /// step. Only from the thread that calls update().
    void resampleCurrentField();
    /// Moves the run onto another grid of the same scene (gale view's coarser live grid): a
    /// solver on `domain` with `steady` as its mean flow takes up the current one's time,
    /// whirlwinds and flow (sim::UnsteadyWindSolver::continueFrom), the grass samples it at once
    /// (resampleCurrentField) and the old grid is freed. The steps the grass holds stay: they are
    /// samples at the vertices, whatever grid they came from; so does the flutter's mean flow at
    /// grass height, the scene grid's. Returns the take-over's projection.
    /// Only from the thread that calls update().
    sim::SolveReport moveToGrid(std::unique_ptr<sim::AirDomain> domain,
                                const sim::WindField& steady, const sim::UnsteadySettings& settings,
                                double referenceSpeed_mps);
    const UnsteadyRunStats& stats() const { return mStats; }
    /// The sampler the grass reads the field through (its near-ground law: nearGroundOf).
    GrassSampler& sampler() { return mSampler; }

  private:
    void advanceTo(double t_s, const std::function<bool()>& stop);

    std::unique_ptr<sim::AirDomain> mDomain;
    std::unique_ptr<sim::UnsteadyWindSolver> mSolver;
    FieldWind mWind;
    GrassSampler mSampler;
    UnsteadyRunStats mStats;
    UnsteadyRunStats mLastUpdate;  // the same totals over the last update() only
    // The flutter (coupling/Flutter.h): the mean flow at grass height (the initial steady
    // field), its shear k, and the bend speed that turns k into a tilt.
    std::vector<glm::vec3> mMean_mps;
    std::vector<double> mShearTke_m2ps2;
    double mBendSpeed_mps = 1.0;
    void setFlutterFor(const std::vector<glm::vec3>& wsVelocity_mps);
};

}  // namespace gale::coupling

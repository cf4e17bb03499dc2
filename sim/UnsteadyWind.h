#pragma once
/// \file UnsteadyWind.h
/// The unsteady wind (docs/design.md 4.2): incompressible, inviscid or viscous flow on the
/// AirDomain's MAC grid, started from the steady mass-consistent field, which stays the mean flow
/// that enters through the open boundaries. docs/unsteady.md has the method, the choices and the
/// measurements.
///
/// One step of length dt (operator splitting, Stam 1999 "Stable fluids"; Bridson 2015):
///  1. seed whirlwinds whose start time falls in the step (sim/Vortices.h), and carry each
///     whirlwind's axis marker with the flow (midpoint rule);
///  2. advect the velocity through itself (sim/Advection.h: semi-Lagrangian with an RK2 trace,
///     MacCormack or BFECC, both limited). Traces that leave the box through a side or the top
///     read the far field: the steady field (clamped to the box) plus the gusts' added velocity
///     at the end of the step (sim/Gusts.h). That makes every side an inflow where the air comes
///     in and zero-gradient where it goes out;
///  3. forces: region gusts (GustEntry::Region: a moving disc relaxing the flow towards the mean
///     plus the gust), whirlwind forcing during a forced whirlwind's lifetime (relaxes its
///     circulation at 2 r_c back to the seeded one; injects, never removes), vorticity confinement
///     (Fedkiw, Stam, Jensen 2001);
///  4. optional implicit viscosity (sim/Viscosity.h: backward Euler, unconditionally stable), or,
///     with UnsteadySettings::surfaceLayer enabled, the mixing-length eddy viscosity and the
///     log-law wall stress of sim/MomentumTurbulence.h (gusts then slow and lag near rough
///     ground, whirlwinds lose speed at the surface);
///  5. projection: the steady solve's operator with A = I (SteadyWindSolver::makeSystem(domain,
///     1)) on cut cells, fluxes theta_f u_f through open fractions theta_f, Dirichlet (p = 0) on
///     the sides, a free-slip lid on top (UnsteadySettings::openTop), no flux through the terrain;
///     MGPCG warm-started from the previous step's potential. u <- u + grad(psi), closed faces
///     refilled by extrapolation as in the steady solve.
/// The steady field is a fixed point of steps 2-5 up to the advection's truncation error.
///
/// Time step: UnsteadySettings::dt_s if > 0, else adaptive, dt = cfl / cellRate_ps() (the
/// field's and the far field's fastest crossing of a cell: |u| / h horizontally, |w| / dz through
/// the layers, so thin stretched layers bound the step through w), at most maxDt_s. The
/// semi-Lagrangian path is stable at any CFL; each StepReport says what CFL the step reached.
///
/// Stretched layers (GridLayout with level heights, docs/unsteady.md): every step works in world
/// metres. Traces run in world space and sample through the layout's staggered sampler, which
/// knows the level heights; the viscosity is the flux-form Laplacian on the layers
/// (sim/Viscosity.h); the projection is the steady solve's layer-weighted operator with the
/// z-gradient taken over the distance between layer centres; the confinement's vertical
/// derivatives and the kinetic energy use the layer heights, and so do the surface layer's wall
/// stress and eddy viscosity (UnsteadySettings::surfaceLayer; sim/MomentumTurbulence.h).
///
/// @code
///   gale::sim::AirDomain domain(terrain, {/*voxelSize_m=*/2.0});
///   auto steady = gale::sim::solveSteadyWind(domain, ambient, {}, {});
///   gale::sim::UnsteadySettings s;  s.cfl = 2.0;  s.gusts.push_back(gust);
///   gale::sim::UnsteadyWindSolver solver(domain, steady.field, s, ambient.speed_mps);
///   for (const auto& rep : solver.advanceTo(10.0)) if (!rep.finite) break;
///   auto u = solver.field().velocityAt_mps(x, y, z);
/// @endcode

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/Advection.h"
#include "sim/AirDomain.h"
#include "sim/Gusts.h"
#include "sim/MomentumTurbulence.h"
#include "sim/PoissonSolver.h"
#include "sim/Vortices.h"
#include "sim/WindField.h"

namespace gale::sim {

namespace detail {
class FaceExtrapolation;
}

struct UnsteadySettings {
    AdvectionScheme advection = AdvectionScheme::SemiLagrangian;
    /// The advection's arithmetic on cubic cells (sim/Advection.h, AdvectionPrecision): float
    /// SIMD rows by default (docs/unsteady.md "Single precision and rows" has the accuracy
    /// both ways); the steady momentum model keeps double.
    AdvectionPrecision precision = AdvectionPrecision::Single;
    /// The steady momentum model's explicit Eulerian step (sim/MomentumAdvection.h) instead of
    /// `advection`; stable only for dt within EULERIAN_MAX_CFL (the caller's choice of dt).
    bool eulerianAdvection = false;
    /// Incremental pressure correction (Goda 1979), for the steady momentum model: the last
    /// projections' summed gradient is added before the stress step and the projection solves
    /// for the increment, so a fixed point's stress does not act on the pressure gradient.
    bool incrementalPressure = false;
    double dt_s = 0.0;            ///< fixed step, seconds; 0: adaptive from cfl
    double cfl = 2.0;             ///< adaptive: cellRate_ps() dt (max |u| dt / h on cubes), > 0
    double maxDt_s = 1.0;         ///< adaptive: longest step, seconds (used in calm air), > 0
    double viscosity_m2ps = 0.0;  ///< kinematic viscosity nu, m^2/s, >= 0 (0: no diffusion step)
    double vorticityConfinement = 0.0;  ///< epsilon of Fedkiw et al. 2001, >= 0 (0: off)
    /// Projection solve: defaults a little looser than the steady solve (every step is warm).
    SolverSettings projection{/*relativeTolerance=*/1e-5, /*maxIterations=*/60};
    /// Top boundary. false (default): a free-slip lid, w = 0 and no flux, Neumann in the
    /// projection. true: open as in the steady solve, p = 0. Measured (docs/unsteady.md): with
    /// p = 0 on the top a whirlwind's low-pressure core sucks air in through the top, the core
    /// hollows into a ring within 5 s and the kinetic energy grows by 7 % in 10 s without forcing;
    /// under the lid the same vortex stays compact and its energy decays monotonically.
    bool openTop = false;
    /// The lid's normal velocity (m/s, upwards positive) at a world point (x, y) of the top
    /// when the top is closed (openTop false): Neumann data, a prescribed outflow the
    /// projection balances through the sides. Empty (default): 0, a free-slip lid.
    std::function<double(double wsX_m, double wsY_m)> lidVelocity_mps;
    /// Kinematic pressure p / rho (m^2/s^2) on the open boundaries at a world point there (the
    /// x and y sides, and the top when openTop): the projection's Dirichlet data. Its potential
    /// is psi = -dt p / rho (u = u* - dt grad p / rho, Chorin 1968), so a flow whose exact
    /// pressure is known keeps it at the boundary instead of p = 0. Empty (default): p = 0.
    std::function<double(const Vec3d& wsPos_m)> boundaryPressure_m2ps2;
    /// Eddy viscosity and wall stress (off by default); viscosity_m2ps is then added to nu_t.
    SurfaceLayerSettings surfaceLayer;
    std::vector<GustEvent> gusts;
    std::vector<Whirlwind> whirlwinds;

    /// Throws gale::ParameterError with the scene key (unsteady.cfl, wind.gusts[i].duration_s ...).
    void validate() const;
};

/// What one step did. Non-convergence of the projection is reported, never thrown.
struct [[nodiscard]] StepReport {
    double t_s = 0;           ///< time at the end of the step, seconds
    double dt_s = 0;          ///< step length, seconds
    double cfl = 0;           ///< cellRate_ps() dt reached (field before the step and far field)
    double maxSpeed_mps = 0;  ///< max cell-centred speed over air cells after the step
    double kineticEnergy_m5ps2 =
        0;  ///< 1/2 sum_f theta_f u_f^2 V_f after the step (per unit density); V_f the face's
            ///< control volume, h^3 on cubic cells
    double maxDivergenceScaled =
        0;               ///< max over air cells |sum_f theta_f u_f . n| / U after the projection
    bool finite = true;  ///< no NaN/Inf in any velocity after the step
    SolveReport projection;       ///< the elliptic solve of step 5
    int viscosityIterations = 0;  ///< CG iterations of the viscous step (0: none)
    TurbulenceReport turbulence;  ///< the surface-layer stress step (zeros when off)
    /// Kinetic energy the forces of step 3 changed (whirlwind forcing, confinement), m^5/s^2;
    /// 0 when no force runs. Seeding is not forcing: it happens before the step's advection.
    double forcingEnergy_m5ps2 = 0;
    double advection_s = 0, forcing_s = 0, viscosity_s = 0, projection_s = 0,
           total_s = 0;  ///< wall times
};

class UnsteadyWindSolver {
  public:
    /// domain must outlive the solver. meanFlow: the steady field on this domain (its arrays give
    /// the initial state and the far field). referenceSpeed_mps: U of the divergence scaling
    /// (the ambient speed; 0 means 1 m/s). Throws gale::ParameterError on bad settings (and
    /// unsteady.surface_layer when the surface layer is asked for on stretched layers, which it
    /// does not support yet), std::logic_error when the field does not match the domain.
    UnsteadyWindSolver(const AirDomain& domain, const WindField& meanFlow,
                       const UnsteadySettings& settings, double referenceSpeed_mps);

    /// The next step length the settings ask for (fixed, or adaptive from cfl), seconds.
    double nextDt_s() const;
    /// How fast the current field or the far field crosses cells, 1/s: the largest |u| / h,
    /// |v| / h and, on z-faces, |w| / dz with dz the thinner layer beside the face. Times dt it
    /// is the step's CFL number (the thinnest layers bound w's).
    double cellRate_ps() const;
    /// One step of dt_s (> 0) seconds.
    StepReport step(double dt_s);
    /// Steps until time() == t_s (the last step shortened to land on it); none if t_s <= time().
    [[nodiscard]] std::vector<StepReport> advanceTo(double t_s);

    const WindField& field() const { return mField; }
    /// Turbulent kinetic energy (m^2/s^2) on the cells after the last step's surface-layer stress
    /// step (TurbulentStress::turbulentKineticEnergy_m2ps2); empty without the surface layer or
    /// before the first step.
    const std::vector<double>& turbulentKineticEnergy_m2ps2() const;
    /// The field for edits from outside the step (sources the viewer drops in, tests' seeding);
    /// call project() after editing.
    WindField& editField() {
        mFieldRateKnown = false;  // the caller edits: cellRate_ps() measures the field again
        return mField;
    }
    double time_s() const { return mTime_s; }
    const MacGrid& grid() const { return mGrid; }
    const UnsteadySettings& settings() const { return mSettings; }
    /// True when the vortex code path runs (whirlwinds or vorticity confinement).
    bool usesVortexCode() const {
        return !mSettings.whirlwinds.empty() || mSettings.vorticityConfinement > 0.0;
    }
    /// Current axis (x, y) of each whirlwind's marker, carried by the flow, world metres.
    const std::vector<std::array<double, 2>>& whirlwindAxes_m() const { return mAxes; }
    /// Far-field velocity at a world position and time: mean flow (clamped to the box) plus gusts.
    Vec3d farField_mps(const Vec3d& wsPos_m, double t_s) const;
    /// Diagnostics of the current field (the StepReport's, available before any step).
    double kineticEnergy_m5ps2() const;
    double maxSpeed_mps() const;
    double maxDivergenceScaled() const;
    /// The MAC arrays of the field, for sampling helpers.
    MacVelocity velocity() const { return {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()}; }
    /// Replaces the current face velocities (m/s, the domain's WindField layout) with those of
    /// `state`, keeping the mean flow as the far field and time() unchanged: the steady momentum
    /// model starts a fine level from a coarser level's solution this way. Faces outside the air
    /// are refilled by extrapolation as after a projection; the next step projects. Throws
    /// std::logic_error when the arrays do not match the domain.
    void resetState(const WindField& state);
    /// Takes up the run of `other`, a solver of the same scene on another grid (gale view's
    /// coarser live grid): its time, its whirlwinds' seeding and axis markers, and its current
    /// flow sampled trilinearly at this grid's faces (clamped to `other`'s box), refilled under
    /// the terrain and projected. The pressure history starts again. Throws std::logic_error
    /// when the two do not hold the same whirlwinds.
    SolveReport continueFrom(const UnsteadyWindSolver& other);
    /// Projects the current field (after external edits, e.g. seeding in tests).
    SolveReport project();
    /// The same with other criteria (the steady momentum model's final, tighter projection).
    /// Both hold p = 0 on the open boundaries; a step uses
    /// UnsteadySettings::boundaryPressure_m2ps2 there when it is set.
    SolveReport project(const SolverSettings& settings);

  private:
    /// The projection with the boundary potential -dt_s p / rho (dt_s 0: p = 0 data) of a step
    /// of CFL stepCfl (StepReport::cfl; the warm start extrapolates in time only on small ones).
    SolveReport project(const SolverSettings& settings, double dt_s, double stepCfl);
    void seedDue(double t0, double t1);
    void applyForcing(double t0, double dt);
    void extrapolateClosedFaces();
    void closeLid();
    void applyRegionGusts(double t, double dt);
    /// What the step reports of a field, from one pass over its faces and cells
    /// (UnsteadyDiagnostics.cpp): each layer in parallel, the layers reduced in order, so every
    /// number is the serial loop's.
    struct FieldSummary {
        double maxSpeed_mps = 0;         ///< the largest cell-centred speed over air cells
        double kineticEnergy_m5ps2 = 0;  ///< as StepReport::kineticEnergy_m5ps2
        double maxOutflux = 0;   ///< the largest |AirDomain::openOutflux| of an air cell, m/s
        double cellRate_ps = 0;  ///< as cellRate_ps() of these arrays alone (no far field)
        bool finite = true;      ///< no NaN or Inf on any face
    };
    FieldSummary summarise(const std::vector<double>& U, const std::vector<double>& V,
                           const std::vector<double>& W) const;

  public:
    /// Centre of a region gust's forcing disc at time t_s, world metres (GustEntry::Region).
    std::array<double, 2> regionCentre_m(const GustEvent& g, double t_s) const;

  private:
    const AirDomain& mDomain;
    MacGrid mGrid;
    UnsteadySettings mSettings;
    double mRefSpeed_mps;
    double mTime_s = 0.0;
    double mMeanMax_mps = 0.0, mGustMax_mps = 0.0;
    double mFarRate_ps = 0.0;  // cellRate_ps of the mean flow plus the gusts' peaks
    /// cellRate_ps of mField alone, valid while mFieldRateKnown: the step's diagnostics leave it,
    /// every change to the field from outside a step (editField, resetState, project) clears it.
    mutable double mFieldRate_ps = 0.0;
    mutable bool mFieldRateKnown = false;
    WindField mField;
    std::vector<double> mMeanU, mMeanV, mMeanW;
    std::vector<uint8_t> mOkX, mOkY,
        mOkZ;  // faces the projection updates (between air cells or on the box)
    /// The closed faces' refill after each projection, one list per component, worked out once
    /// from the masks (sim/FaceExtrapolation.h).
    std::array<std::shared_ptr<const detail::FaceExtrapolation>, 3> mRefill;
    PoissonSystem mSystem;
    PoissonSolver mPoisson;
    std::vector<double> mPsi;  // projection potential (m^2/s), warm start
    std::vector<double> mRhs;  // the projection's right-hand side (storage kept between steps)
    /// The last two steps' potentials' pressures, for the next step's warm start extrapolated in
    /// time (project(settings, dt)); mPressureSteps counts how many are valid (0-2).
    std::vector<double> mPressureLast, mPressureBefore;
    int mPressureSteps = 0;
    /// The step's velocity before its advection (swapped out of mField, kept for its storage)
    /// and that velocity in float for the row kernels.
    std::vector<double> mBefore[3];
    std::vector<float> mBeforeSingle[3];
    AdvectionScratch mAdvectionScratch;  ///< the advection's working arrays, kept between steps
    std::vector<double> mGradPsi[3];     // incrementalPressure: sum of the projections' corrections
    std::unique_ptr<TurbulentStress> mStress;  // surface-layer stresses, when enabled
    std::vector<std::array<double, 2>> mAxes;
    std::vector<uint8_t> mSeeded;
};

}  // namespace gale::sim

#pragma once
/// \file SteadyWind.h
/// The steady mass-consistent wind (docs/design.md 4.1, after Sherman 1978): the divergence-free
/// field u closest to the first guess u0 (an AmbientWind) in the weighted norm
///   integral of a_h^2 [(u-u0)^2 + (v-v0)^2] + a_v^2 (w-w0)^2,
/// which is u = u0 + A grad(lambda), A = diag(1/(2 a_h^2), 1/(2 a_h^2), 1/(2 a_v^2)), with
///   div(A grad lambda) = -div u0,  lambda = 0 on the open sides and top,  no flux through terrain.
///
/// Discretisation. We solve for psi = lambda / (2 a_h^2) (m^2/s), so u = u0 + (d/dx psi,
/// d/dy psi, r d/dz psi) with r = (a_h / a_v)^2. Cell-centred psi on the AirDomain's cubic cells;
/// MAC velocities on faces; the flux through face f is theta_f * u_f * h^2 with theta_f the open
/// fraction (Batty, Bertails, Bridson 2007; Ng, Min, Gibou 2009): the solid part of a face carries
/// nothing, so the first guess's flux into the terrain is removed and free slip holds. Per cell,
///   sum_f theta_f c_f (psi_c - psi_nb) = h * sum_f theta_f (u0 . n_out)_f   (+ Dirichlet data),
/// c_f = 1 for x/y faces and r for z faces: a PoissonSystem with weights theta_f c_f. Dirichlet
/// values sit on the boundary faces (half a cell from the centre). The result has
/// sum_f theta_f u_f . n_out = residual / h in every air cell, i.e. discretely divergence-free to
/// the solver tolerance.
///
/// Faces closed by the terrain get velocities for interpolation only: if both neighbouring cells
/// are air, u0 + the same potential difference; otherwise the average of the valid face values
/// around them, repeated EXTRAPOLATION_LAYERS times; any face still without a value gets 0
/// (sim/FaceExtrapolation.h). The choice between this model and the momentum model is
/// sim/SteadyModel.h's.
///
/// @code
///   gale::sim::AirDomain domain(terrain, {/*voxelSize_m=*/2.0, /*top_m=*/{},
///   /*memoryLimit_bytes=*/2e9}); gale::sim::SteadyWindSolver solver(domain, {/*alphaH=*/1.0,
///   /*alphaV=*/1.0}); gale::sim::SteadyWindResult res = solver.solve(ambient,
///   gale::sim::SolverSettings{}); if (!res.report.converged) std::cerr << res.report.message <<
///   "\n"; auto u = res.field.velocityAt_mps(x, y, z);
/// @endcode

#include <functional>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyModel.h"  // the dispatcher, for callers that still reach it through this header
#include "sim/WindField.h"

namespace gale::sim {

/// Gauss precision moduli of Sherman 1978 (WindNinja's alpha_h, alpha_v). Only their ratio
/// matters to the field; a_h = a_v gives potential flow.
struct MassConsistentWeights {
    double alphaH = 1.0;  ///< horizontal weight a_h, > 0
    double alphaV = 1.0;  ///< vertical weight a_v, > 0
};

/// Dirichlet data for psi on the open boundary faces: world position (metres) -> psi (m^2/s).
/// Empty: psi = 0, the usual open boundary of mass-consistent models (the correction has no
/// tangential part there). The hemisphere benchmark passes the exact far field through it.
using BoundaryPotential = std::function<double(double wsX_m, double wsY_m, double wsZ_m)>;

struct SteadyWindResult {
    WindField field;
    /// The elliptic solve; maxDivergenceScaled = max over air cells |sum_f theta_f u_f . n| / U
    /// (= |div u| h / U with U = the ambient speed_mps, or 1 m/s when that is 0).
    SolveReport report;
    double assemblySeconds = 0;  ///< first guess, right-hand side, velocity update, extrapolation
};

/// Builds the operator and its multigrid hierarchy once for a domain; solve() may be called many
/// times (other winds, tolerances), each warm-started from the previous potential. Keeps a
/// reference to the domain: the domain must outlive the solver.
class SteadyWindSolver {
  public:
    /// Supported r = (a_h / a_v)^2: outside it the point smoother's V-cycle degrades (the
    /// operator's anisotropy; docs/design.md 7), so we refuse rather than crawl.
    static constexpr double MIN_VERTICAL_RATIO = 0.1;
    static constexpr double MAX_VERTICAL_RATIO = 10.0;
    static constexpr int EXTRAPOLATION_LAYERS = 2;

    /// Throws gale::ParameterError naming solver.alpha_h or solver.alpha_v when a weight is not
    /// > 0 and finite or the ratio is outside [MIN_VERTICAL_RATIO, MAX_VERTICAL_RATIO].
    explicit SteadyWindSolver(const AirDomain& domain, const MassConsistentWeights& weights = {});

    /// Solves for the ambient wind (validated: throws gale::ParameterError naming the scene key,
    /// as AmbientWind::validate and PoissonSolver::solve do).
    /// Non-convergence is in the report, never thrown; the field is then the last iterate.
    [[nodiscard]] SteadyWindResult solve(const AmbientWind& ambient, const SolverSettings& settings,
                                         const BoundaryPotential& boundary = {});

    /// The potential psi (m^2/s) of the last solve, one value per cell (PoissonSystem layout),
    /// 0 outside the air; the next solve starts from it.
    const std::vector<double>& potential_m2ps() const { return mPotential; }
    /// Sets the warm start (cellCount() entries) or clears it (empty); std::logic_error for
    /// another size.
    void setWarmStart(std::vector<double> potential_m2ps);
    const PoissonSystem& system() const { return mSystem; }
    const PoissonSolver& poisson() const { return mPoisson; }
    /// Another solver of system() for solve() to call instead of poisson() (gale_dist's
    /// distributed MGPCG under mpirun): PoissonSolver::solve's contract (right-hand side, warm
    /// start in and solution out, one value per cell, and the report). Empty: poisson().
    using PoissonSolve = std::function<SolveReport(
        const std::vector<double>& rhs, std::vector<double>& solution, const SolverSettings&)>;
    void setPoissonSolve(PoissonSolve solve) { mSolve = std::move(solve); }
    double verticalRatio() const { return mRatio; }

    /// The PoissonSystem of a domain: weights theta_f * c_f, Dirichlet sides and top, Neumann
    /// bottom (under the terrain) and Neumann y sides when the domain has closedSidesY (free-slip
    /// walls of a two-dimensional case). The unsteady projection uses verticalRatio = 1.
    static PoissonSystem makeSystem(const AirDomain& domain, double verticalRatio);

  private:
    const AirDomain& mDomain;
    double mRatio = 1.0;
    PoissonSystem mSystem;
    PoissonSolver mPoisson;
    PoissonSolve mSolve;
    std::vector<double> mPotential;
};

/// One-shot convenience: builds a SteadyWindSolver and solves once from a zero potential.
[[nodiscard]] SteadyWindResult solveSteadyWind(const AirDomain& domain, const AmbientWind& ambient,
                                               const MassConsistentWeights& weights,
                                               const SolverSettings& settings,
                                               const BoundaryPotential& boundary = {});

}  // namespace gale::sim

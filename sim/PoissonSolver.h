#pragma once
/// \file PoissonSolver.h
/// The reusable elliptic solver of gale: multigrid-preconditioned conjugate gradients (MGPCG,
/// McAdams, Sifakis, Teran 2010) for the cell-centred, matrix-free 7-point operator
///
///   (A x)_c = sum over the six faces f of c:  w_f (x_c - x_nb(f)),
///
/// on a box of nx * ny * nz cells with per-face weights w_f >= 0. The weights carry everything the
/// caller's physics needs: open fractions of cut cells (Batty, Bertails, Bridson 2007), the
/// anisotropy of the operator, and zeros around solid cells. A cell whose six weights are all zero
/// is inactive: it is not an unknown and its solution value is 0.
///
/// Boundaries of the box: Dirichlet (value 0 on the boundary face, half a cell from the cell
/// centre, hence the factor 2 the solver applies to boundary-face weights) or Neumann (no flux,
/// boundary weight ignored). Non-zero Dirichlet data is the caller's business: add
/// 2 * w_f * g_f to the right-hand side of the boundary cell (SteadyWind does that).
///
/// Knows nothing about wind or terrain, so the unsteady solver's projection reuses it unchanged:
/// build one PoissonSolver per topology and call solve() every step with the previous solution as
/// the warm start.
///
/// @code
///   gale::sim::PoissonSystem sys = gale::sim::PoissonSystem::uniformBox(64, 64, 32);
///   sys.sides[gale::sim::SIDE_ZMIN] = gale::sim::BoundaryKind::Neumann;   // ground
///   gale::sim::PoissonSolver solver(sys);
///   std::vector<double> rhs(sys.cellCount(), 1.0), x;   // x empty: cold start from 0
///   gale::sim::SolveReport rep = solver.solve(rhs, x, gale::sim::SolverSettings{});
///   if (!rep.converged) { /* the caller decides: report, retry, stop */ }
/// @endcode

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "sim/GridLayout.h"

namespace gale::sim {

enum class BoundaryKind { Dirichlet, Neumann };

/// Index of a side of the box in PoissonSystem::sides.
enum BoxSide : int { SIDE_XMIN = 0, SIDE_XMAX, SIDE_YMIN, SIDE_YMAX, SIDE_ZMIN, SIDE_ZMAX };

/// The operator: box size, boundary kinds and face weights (dimensionless conductances, the
/// open fraction of the face times the operator's coefficient in that direction).
struct PoissonSystem : GridIndex {
    std::array<BoundaryKind, 6> sides{BoundaryKind::Dirichlet, BoundaryKind::Dirichlet,
                                      BoundaryKind::Dirichlet, BoundaryKind::Dirichlet,
                                      BoundaryKind::Dirichlet, BoundaryKind::Dirichlet};
    /// Weights of the x-faces (GridIndex::faceXIndex: face i between cells i-1 and i).
    std::vector<float> weightX;
    /// Weights of the y-faces (GridIndex::faceYIndex).
    std::vector<float> weightY;
    /// Weights of the z-faces (GridIndex::faceZIndex).
    std::vector<float> weightZ;
    /// Smooth with z-line Gauss-Seidel (a tridiagonal solve per column, columns in red-black
    /// order) instead of point Gauss-Seidel: for operators whose z-couplings are much stronger
    /// than the horizontal ones (thin stretched layers), where point smoothing stalls.
    bool zLineSmoothing = false;

    /// All weights 1 (the plain Laplacian scaled by h), all sides Dirichlet.
    static PoissonSystem uniformBox(int nx, int ny, int nz);
};

/// Criteria on input. Defaults suit the steady wind solve.
struct SolverSettings {
    /// Stop when max|r| / max|b| <= relativeTolerance (max norm, as openvdb::math::pcg does, so
    /// the benchmark compares like with like). Must be in (0, 1).
    double relativeTolerance = 1e-6;
    int maxIterations = 100;  ///< PCG iterations (>= 1)
    /// Red-black Gauss-Seidel sweeps before and after the coarse correction: V(n, n).
    int smoothingSweeps = 2;
    /// false: Jacobi (diagonal) preconditioner instead of the V-cycle, for comparisons only.
    bool useMultigrid = true;
};

/// Throws std::logic_error (a broken precondition of the caller) naming the field when a size is
/// < 1, a weight vector has the wrong length, or a weight is negative or not finite: the checks
/// every solver of a PoissonSystem makes (PoissonSolver, gale_dist's distributed one).
void checkSystem(const PoissonSystem& system);

/// Throws gale::ParameterError naming solver.tolerance or solver.max_iterations for a bad
/// setting, std::logic_error for smoothingSweeps outside 1..8.
void checkSettings(const SolverSettings& settings);

/// What a solve reached. Non-convergence is reported here, never thrown.
struct [[nodiscard]] SolveReport {
    bool converged = false;
    int iterations = 0;  ///< PCG iterations done (0: the start already met the criteria)
    double initialRelativeResidual = 0;  ///< max|b - A x0| / max|b|
    double relativeResidual = 0;         ///< max|b - A x| / max|b| on return (recurrence residual)
    double solveSeconds = 0;             ///< wall time of solve()
    double setupSeconds = 0;             ///< wall time of building the hierarchy (constructor)
    int levels = 0;                      ///< multigrid levels (1: no coarsening)
    std::string message;                 ///< why it stopped, in words
    /// Filled by callers that know the physics (SteadyWind): max |div u| * h / U over air cells.
    double maxDivergenceScaled = 0;
};

/// MGPCG on a PoissonSystem. Construction validates the system, copies the weights into a padded
/// layout and builds the multigrid hierarchy (coarse weights: sums of the fine face weights over
/// each coarse face divided by the coarsening factor, i.e. averaged open fractions at twice the
/// spacing, as McAdams et al. 2010 coarsen their cell types). Not copyable; solve() is not
/// re-entrant (it uses the solver's scratch vectors), but every kernel runs on TBB threads.
class PoissonSolver {
  public:
    /// Throws std::logic_error (a broken precondition of the caller) naming the field when a size
    /// is < 1, a weight vector has the wrong length, or a weight is negative or not finite.
    explicit PoissonSolver(const PoissonSystem& system);
    ~PoissonSolver();
    PoissonSolver(PoissonSolver&&) noexcept;
    PoissonSolver& operator=(PoissonSolver&&) noexcept;
    PoissonSolver(const PoissonSolver&) = delete;
    PoissonSolver& operator=(const PoissonSolver&) = delete;

    /// Solves A x = rhs. `solution` on input is the warm start (empty: start from zero; else it
    /// must have cellCount() entries); on output it is the solution, 0 in inactive cells.
    /// Right-hand-side entries of inactive cells are ignored. Throws gale::ParameterError naming
    /// solver.tolerance or solver.max_iterations for a bad setting, std::logic_error for wrong
    /// vector sizes or smoothingSweeps outside 1..8; numerical trouble is in the report.
    SolveReport solve(const std::vector<double>& rhs, std::vector<double>& solution,
                      const SolverSettings& settings);

    /// out = A x (cellCount() entries each), for tests and diagnostics; std::logic_error for
    /// another size.
    void applyOperator(const std::vector<double>& x, std::vector<double>& out) const;

    /// z = M^-1 r: one V(n, n) cycle from zero with n = smoothingSweeps (the preconditioner CG
    /// applies each iteration), cellCount() entries each, 0 in inactive cells; entries of r in
    /// inactive cells are ignored. M^-1 is symmetric positive definite on the active cells, which
    /// is what lets CG keep its guarantees (tested: <a, M^-1 b> = <b, M^-1 a>). Uses the solver's
    /// scratch vectors (not re-entrant). Throws std::logic_error for a wrong size or
    /// smoothingSweeps outside 1..8.
    void applyPreconditioner(const std::vector<double>& r, std::vector<double>& z,
                             int smoothingSweeps = 2);

    int levelCount() const;
    size_t activeCellCount() const;
    /// Bytes held by the hierarchy and the PCG vectors.
    size_t memory_bytes() const;
    /// Bytes this solver will hold for a box of nx * ny * nz cells (the hierarchy it builds, with
    /// each level's ghost layer, the PCG vectors and the coarsest level's dense factor), for
    /// estimates before allocating; doubles so absurd boxes do not overflow.
    static double estimatedBytes(double nx, double ny, double nz);
    /// Bytes moved per cell of the box in one PCG iteration with V(n, n): reads + writes of every
    /// array a kernel streams, counted once per kernel, on the finest level plus 1/7 for the
    /// coarser ones; cells in uniform (full-open) runs skip their weights. For the
    /// memory-bandwidth floor of the benchmark.
    static double bytesPerCellPerIteration(int smoothingSweeps, double uniformFraction);
    /// Fraction of the finest level's cells on the constant-coefficient fast path.
    double uniformCellFraction() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace gale::sim

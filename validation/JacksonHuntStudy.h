#pragma once
/// \file JacksonHuntStudy.h
/// The low ridges of Jackson and Hunt (1975) (docs/validation.md, section 2): cos^2 ridges of
/// L = 200 m (half height at L from the crest) in a two-dimensional box (4 m cells, 3 across,
/// free-slip side walls, top 300 m, 1600 m long, crest at 600 m), log inflow z0 = 0.03 m, 10 m/s
/// at 10 m; the fractional speed-up of |u| at DZ_M above the crest against the same model's
/// wind at x = 100 m (flat, upwind) at the same height above the ground.

#include <cmath>

namespace gale::validation {

namespace jacksonhunt {
constexpr double L_M = 200.0;            ///< horizontal distance from the crest to half height
constexpr double CELL_M = 4.0;           ///< the cell size
constexpr double TOP_M = 300.0;          ///< the box's top
constexpr double LENGTH_M = 1600.0;      ///< the box's length along the wind
constexpr double CREST_X_M = 600.0;      ///< the crest's distance from the inflow face
constexpr double REFERENCE_X_M = 100.0;  ///< the flat upwind column the speed-up is taken against
constexpr double Z0_M = 0.03, SPEED_MPS = 10.0, REFERENCE_HEIGHT_M = 10.0;  ///< the log inflow
/// Heights above the local ground reported (6 m: the lowest the 4 m grid resolves).
constexpr double DZ_M[3] = {6.0, 10.0, 20.0};
/// The ridge heights of the main table (H / L = 0.025, 0.05, 0.1).
constexpr double HEIGHTS_M[3] = {5.0, 10.0, 20.0};
/// The pseudo-time steps per level at most (a crossing of the box is about 320).
constexpr int MAX_ITERATIONS = 1000;
}  // namespace jacksonhunt

/// One ridge: its height, the model, and where it sits against the grid (the whole ground raised
/// by base_m, the crest moved downwind by shift_m; both zero in the main table).
struct JacksonHuntOptions {
    double H_m = 10.0;
    bool momentum = true;  ///< false: the mass-consistent model
    double base_m = 0, shift_m = 0;
};

/// Delta S at jacksonhunt::DZ_M above the crest, and the solve.
struct JacksonHuntStudy {
    double speedup[3] = {NAN, NAN, NAN};
    int iterations = 0;
    bool converged = false;
    double seconds = 0;
    /// Delta S / (H / L) at DZ_M[k].
    double coefficient(int k, double H_m) const { return speedup[k] / (H_m / jacksonhunt::L_M); }
};

/// Solves one ridge. Throws what the solvers throw.
JacksonHuntStudy runJacksonHunt(const JacksonHuntOptions& options);

}  // namespace gale::validation

#pragma once
/// \file CaoTamuraStudy.h
/// The steep ridge of Cao and Tamura (2006) (docs/validation.md, section 3): the measured line
/// (validation/data/cao-tamura-2006-ridge.csv, embedded in the binary) and one solve of either
/// steady model on the ridge of CaoTamuraRidge.h, compared with it. `gale bench models` prints
/// these figures; tests/validation holds them to the page's numbers (AcceptanceLimits.h).
///
/// @code
///   const auto data = validation::caoTamuraMeasurements();
///   validation::CaoTamuraOptions o;  // momentum model, H / h = 5, the published inflow
///   const validation::CaoTamuraStudy s = validation::runCaoTamura(o, data);
///   // s.crestSpeedup: the model's speed-up at the crest, 0.25 H up (measured 1.33)
/// @endcode

#include <cmath>
#include <string>
#include <vector>

#include "sim/MomentumWind.h"
#include "validation/CaoTamuraRidge.h"
#include "validation/StudyLevels.h"

namespace gale::validation {

/// One measured point of the validation line (validation/data/README.md): position in ridge
/// heights from the crest (x / H) and above the local ground (dz / H), the measured u / U_inf and
/// the fractional speed-up against the windward foot (x = -2.5 H) at the same dz.
struct RidgeMeasurement {
    double xOverH = 0, dzOverH = 0, speedup = 0;
    double uOverUinf = 0;  ///< the measurement itself, u / U_inf
};

/// Parses the CSV text of cao-tamura-2006-ridge.csv (header line, then x_over_H, z_over_H,
/// dz_over_H, u_over_Uinf, u_ref_over_Uinf, speedup; rows without a speed-up are skipped).
/// sourceName names the text in errors. Throws std::invalid_argument "<sourceName>:<line>: ..."
/// for a field that is not a number, or when no row has a speed-up.
std::vector<RidgeMeasurement> parseRidgeMeasurements(const std::string& csvText,
                                                     const std::string& sourceName);
/// The embedded campaign (validation/data/cao-tamura-2006-ridge.csv as built into the program).
std::vector<RidgeMeasurement> caoTamuraMeasurements();

/// Measured figures of the data the studies compare with (validation/data/README.md).
constexpr double MEASURED_CREST_SPEEDUP = 1.33;      ///< at dz = 0.25 H
constexpr double MEASURED_LEE_FOOT_SPEEDUP = -0.32;  ///< at x = 2.5 H, dz = 1.0 H
/// Measured u / U_inf nearest dz = 0.25 H: windward foot (dz 0.241 H), crest (0.248 H).
constexpr double MEASURED_FOOT_UINF_025H = 0.377, MEASURED_CREST_UINF_025H = 0.884;
/// The target for the lee deficits: within this of the measured speed-up.
constexpr double LEE_DEFICIT_TOLERANCE = 0.15;

/// One run of the study: which model, grid, inflow and pseudo-time step.
struct CaoTamuraOptions {
    bool momentum = true;      ///< false: the mass-consistent model
    int cellsPerH = 5;         ///< H / h (> 0)
    int maxIterations = 1000;  ///< pseudo-time steps per level at most (momentum)
    double cfl = 2.0;          ///< the semi-Lagrangian step's cfl (momentum)
    ridge::Inflow inflow = ridge::Inflow::Published;
    sim::PseudoTimeAdvection advection = sim::PseudoTimeAdvection::SemiLagrangian;
    sim::TurbulenceClosure turbulence = sim::TurbulenceClosure::MixingLength;  ///< (momentum)
};

/// The figures of one run, as docs/validation.md states them (speed-ups against the model's own
/// windward foot at the same height above the ground; u / U_inf against the inflow's U_inf).
struct CaoTamuraStudy {
    int nx = 0, ny = 0, nz = 0;  ///< the box's cells
    int iterations = 0;          ///< solver iterations (pseudo-time steps over all levels)
    bool converged = false;
    double seconds = 0;  ///< wall time of the solve
    double cfl = NAN;    ///< momentum only: the pseudo-time step's cfl (or the Eulerian one)
    int points = 0;      ///< measured points off the windward foot in the RMS
    double rmsSpeedupError = NAN;  ///< RMS of model minus measured speed-up over those points
    double rmsWindward = NAN, rmsLee = NAN;  ///< the same over x <= 0 and over x > 0
    double crestSpeedup = NAN;  ///< at the crest, the measured point nearest dz = 0.25 H
    double leeSpeedup = NAN;    ///< at the lee foot (2.5 H), the point nearest dz = 1.0 H
    double crestSpeedups[3] = {NAN, NAN, NAN};  ///< at ridge::CREST_DZ_OVER_H
    double crestUinf = NAN, footUinf = NAN;     ///< u / U_inf at dz = 0.25 H
    double rmsUinf = NAN;  ///< RMS of model minus measured u / U_inf, every point
    /// Measured lee deficits (x > 0, speed-up < 0), of them the model's of the same sign, and of
    /// them within LEE_DEFICIT_TOLERANCE of the measurement.
    int leePoints = 0, leeSameSign = 0, leeWithin = 0;
    /// Momentum only, per level (coarsest first): voxel size, steps, final residual, converged.
    using Level = StudyLevel;
    std::vector<Level> levels;
};

/// Solves the ridge with the options and compares the field with data. Throws what the solvers
/// throw; std::invalid_argument if cellsPerH < 1 or data is empty.
CaoTamuraStudy runCaoTamura(const CaoTamuraOptions& options,
                            const std::vector<RidgeMeasurement>& data);

}  // namespace gale::validation

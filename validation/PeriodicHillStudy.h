#pragma once
/// \file PeriodicHillStudy.h
/// The ERCOFTAC periodic hill (UFR 3-30) as a validation study (docs/validation.md, section 4):
/// the reference (validation/data/periodic-hill-xiao-2020-*.csv, the DNS of Xiao, Wu, Laizet and
/// Duan 2020 at Re_h = 5600, embedded in the binary) and one solve of the momentum model on a
/// chain of hills (PeriodicHill.h), compared with it: where the flow separates behind the crest
/// and reattaches on the floor, the mean-velocity profiles at the published stations, the
/// turbulent kinetic energy there, and how far the measured period repeats the one before it.
///
/// Set-up. gale has no periodic boundaries, so the study solves `hills` periods in a row, a
/// two-dimensional box (free-slip side walls, 3 cells across) from the crest of the first hill to
/// the crest after the last, the top at the channel's upper wall (3.036 h above the floor, the
/// steady model's open top with the ambient profile's stress). The inflow at the first crest is
/// the log law over the smooth-wall z0 (PeriodicHill.h) carrying the bulk velocity Ub through the
/// crest gap. Period `measuredHill` (0 = the first) is compared with the reference; the period
/// before it is compared with it to show the flow repeats. The open top lets the flux drift
/// along the chain by a few per cent, so each period's velocities are made dimensionless by the
/// bulk velocity through its own first crest gap, as the DNS's are by its own.
///
/// @code
///   const validation::PeriodicHillData ref = validation::periodicHillReference();
///   validation::PeriodicHillOptions o;  // mixing length, semi-Lagrangian, h / 10 cells
///   const validation::PeriodicHillStudy s = validation::runPeriodicHill(o, ref);
///   // s.reattachment_h against ref.reattachment_h (4.68 h)
/// @endcode

#include <cmath>
#include <string>
#include <vector>

#include "sim/MomentumWind.h"
#include "validation/StudyLevels.h"

namespace gale::validation {

/// One reference point of a profile: station x / h from the crest, height y / h above the flat
/// floor (the hill's foot), mean u / Ub and v / Ub, and k / Ub^2.
struct HillProfilePoint {
    double x_h = 0, y_h = 0, u_Ub = 0, v_Ub = 0, k_Ub2 = 0;
};

/// One sample of the along-wall velocity: x / h from the crest and its signed speed / Ub.
struct WallSample {
    double x_h = 0, u_Ub = 0;
};

/// The reference data of the study.
struct PeriodicHillData {
    std::vector<HillProfilePoint> profiles;           ///< grouped by station, ascending x, then y
    std::vector<WallSample> wall;                     ///< u in the wall-adjacent cells, ascending x
    double separation_h = NAN, reattachment_h = NAN;  ///< from wall, by bubbleOf
    std::vector<double> stations() const;             ///< the profiles' x / h, ascending
};

/// Parses the profiles CSV (header, then x_over_h, y_over_h, u_over_Ub, v_over_Ub, k_over_Ub2)
/// and the wall CSV (header, then x_over_h, y_over_h, u_over_Ub). sourceName names each text in
/// errors. Throws std::invalid_argument "<sourceName>:<line>: ..." for a field that is not a
/// number or a row with too few fields, and when either text has no rows.
PeriodicHillData parsePeriodicHillData(const std::string& profilesCsv,
                                       const std::string& profilesName, const std::string& wallCsv,
                                       const std::string& wallName);
/// The embedded reference (validation/data/periodic-hill-xiao-2020-{profiles,wall}.csv).
/// Throws std::logic_error when they were not embedded at build time.
PeriodicHillData periodicHillReference();

/// The recirculation bubble of a line of along-wall velocities (ascending x): separation is the
/// first zero crossing from + to - at x > searchFrom_h, reattachment the next crossing from - to
/// +, each interpolated linearly between the two samples. NaN when there is none; a bubble still
/// open at the line's end has reattachment NaN. Pure function, no throws.
struct Bubble {
    double separation_h = NAN, reattachment_h = NAN;
    bool exists() const { return std::isfinite(separation_h); }
};
Bubble bubbleOf(const std::vector<WallSample>& line, double searchFrom_h = 0.0);

/// RMS of model minus reference over paired values (equal lengths, at least one). Throws
/// std::invalid_argument otherwise.
double rmsDifference(const std::vector<double>& model, const std::vector<double>& reference);

/// One run of the study.
struct PeriodicHillOptions {
    int cellsPerH = 10;       ///< h / cell edge (> 0)
    int hills = 5;            ///< periods in the box (>= 2)
    int measuredHill = 3;     ///< the period compared (1 <= measuredHill < hills)
    int maxIterations = 500;  ///< pseudo-time steps per level at most
    double cfl = 2.0;         ///< the semi-Lagrangian step's cfl
    sim::PseudoTimeAdvection advection = sim::PseudoTimeAdvection::SemiLagrangian;
    sim::TurbulenceClosure closure = sim::TurbulenceClosure::MixingLength;
    double h_m = 10.0;           ///< the hill height at model scale, metres (> 0)
    double bulkSpeed_mps = 5.0;  ///< Ub through the crest gap, m/s (> 0)
};

/// The figures of one run (lengths in h from the crest of the measured period).
struct PeriodicHillStudy {
    int nx = 0, ny = 0, nz = 0;
    int iterations = 0;
    bool converged = false;
    double seconds = 0;  ///< wall time of the solve (domain, start and momentum)
    double z0_h = NAN;   ///< the smooth-wall roughness used, hill heights
    /// The bubble on the measured period and on the one before it (the repeat check).
    Bubble bubble, previousBubble;
    double reattachmentRelativeError = NAN;  ///< |reattachment / reference - 1|
    struct Station {
        double x_h = 0;
        int points = 0;
        double rmsU = NAN;        ///< RMS of model minus reference u / Ub
        double rmsK = NAN;        ///< RMS of model minus reference k / Ub^2 (NaN without k)
        double repeatRmsU = NAN;  ///< RMS of u / Ub, measured period minus the one before
        /// The model's u / Ub and k / Ub^2 (NaN in a solid cell or without k) at the station's
        /// reference points, in the reference's order.
        std::vector<double> modelU, modelK;
    };
    std::vector<Station> stations;
    double rmsU = NAN, rmsK = NAN, repeatRmsU = NAN;  ///< the same over every station's points
    /// The model's flux through the measured period's first crest gap / (Ub gap), and the same
    /// for the period before. Every u / Ub and k / Ub^2 of a period is over its own bulk.
    double bulkOverUb = NAN, previousBulkOverUb = NAN;
    double minFloorU_Ub = NAN;     ///< the most reversed along-wall velocity on the measured floor
    std::vector<WallSample> wall;  ///< the model's along-wall line on the measured period
    /// Per level (coarsest first): voxel size, steps, final RMS residual, converged.
    using Level = StudyLevel;
    std::vector<Level> levels;
    int cyclePeriod = 0, averagedSteps = 0;  ///< MomentumReport's cycle average, if it ran
};

/// The along-wall sample: WALL_SAMPLE_CELLS cell edges straight above the local floor (the first
/// cell's centre over flat ground), the velocity projected on the floor's tangent.
inline constexpr double WALL_SAMPLE_CELLS = 0.5;
/// The along-wall line's spacing, hill heights.
inline constexpr double WALL_LINE_STEP_H = 0.02;

/// Solves the chain of hills with the options and compares the measured period with the
/// reference. Throws std::invalid_argument for options outside their ranges or empty data, what
/// the solvers throw otherwise (the two-equation closure: std::logic_error until it is built).
PeriodicHillStudy runPeriodicHill(const PeriodicHillOptions& options, const PeriodicHillData& ref);

}  // namespace gale::validation

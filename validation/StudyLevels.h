#pragma once
/// \file StudyLevels.h
/// What a validation study keeps of each level of a momentum solve (its coarse start and the
/// finest level), the same for every study (CaoTamuraStudy.h, PeriodicHillStudy.h).

#include <vector>

#include "sim/MomentumWind.h"

namespace gale::validation {

/// One level: its index (0 the finest), cell edge (m), pseudo-time steps, last RMS residual,
/// converged.
struct StudyLevel {
    int level = 0;
    double voxelSize_m = 0, momentumResidual = 0;
    int iterations = 0;
    bool converged = false;
};

/// The levels of a momentum report, coarsest first.
inline std::vector<StudyLevel> studyLevels(const sim::MomentumReport& report) {
    std::vector<StudyLevel> out;
    for (const sim::MomentumLevel& l : report.levels)
        out.push_back({l.level, l.voxelSize_m, l.momentumResidual, l.iterations, l.converged});
    return out;
}

}  // namespace gale::validation

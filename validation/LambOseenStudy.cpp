/// \file LambOseenStudy.cpp
/// The translating vortex study (LambOseenStudy.h).
#include "validation/LambOseenStudy.h"

#include "validation/TranslatingVortex.h"
#include "validation/UnsteadyStability.h"

namespace gale::validation {

LambOseenStudy runLambOseen(const LambOseenOptions& o) {
    LambOseenStudy s;
    double prev = 0.0;
    for (const auto& [cells, courant] : o.runs) {
        const StabilityRun r = runTranslatingVortex(cells, courant);
        LambOseenStudy::Row row;
        row.cellsPerCore = cells, row.courant = courant, row.steps = r.steps;
        row.error = exact::translatingVortexError(r);
        row.order = prev > 0 ? std::log2(prev / row.error) : NAN;
        row.keStart_m5ps2 = r.keStart_m5ps2, row.keEnd_m5ps2 = r.keEnd_m5ps2, row.wall_s = r.wall_s;
        prev = row.error;
        s.rows.push_back(row);
    }
    return s;
}

}  // namespace gale::validation

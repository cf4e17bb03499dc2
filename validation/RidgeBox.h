#pragma once
/// \file RidgeBox.h
/// The two-dimensional ridge box and log-law inflow the ridge studies of `gale bench models`
/// share (JacksonHuntStudy.cpp, PseudoTimeStudy.cpp).

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"

namespace gale::validation::ridgebox {

/// A box of cubic cells (voxelSize_m, top at top_m, metres) around a ridge whose axis runs along
/// y, with free-slip side walls so the flow stays two-dimensional (DomainSpec::closedSidesY).
inline sim::DomainSpec spec(double voxelSize_m, double top_m, bool momentumModel) {
    sim::DomainSpec s;
    s.voxelSize_m = voxelSize_m;
    s.top_m = top_m;
    s.momentumModel = momentumModel;
    s.closedSidesY = true;
    return s;
}

/// The neutral log law: speed_mps at referenceHeight_m over roughness z0_m (m).
inline sim::AmbientWind logLaw(double speed_mps, double referenceHeight_m, double z0_m) {
    sim::AmbientWind w;
    w.profile = sim::WindProfile::LogLaw;
    w.speed_mps = speed_mps, w.referenceHeight_m = referenceHeight_m;
    w.roughness_m = z0_m;
    return w;
}

}  // namespace gale::validation::ridgebox

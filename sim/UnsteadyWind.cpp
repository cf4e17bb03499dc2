/// \file UnsteadyWind.cpp
/// Operator-split incompressible steps on the MAC grid (Stam 1999; projection as SteadyWind.cpp):
/// set-up, the far field, forcing and the step itself. The projection is in
/// UnsteadyProjection.cpp, the step's field diagnostics in UnsteadyDiagnostics.cpp.
#include "sim/UnsteadyWind.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/AdvectionRows.h"
#include "sim/Format.h"
#include "sim/MomentumAdvection.h"
#include "sim/SteadyWind.h"
#include "sim/UniformLattice.h"
#include "sim/Viscosity.h"

namespace gale::sim {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

using detail::num;

/// Smallest whirlwind forcing time scale, in steps: relaxing faster than one step over-shoots.
constexpr double MIN_FORCING_STEPS = 1.0;
/// Forcing and circulation are measured on a ring of this many core radii (at least 2 cells).
constexpr double FORCING_RING_CORES = 2.0;

/// The steady solve's operator with A = I (on stretched layers weighted by the layer heights);
/// the top closed by a lid unless it is open.
PoissonSystem projectionSystem(const AirDomain& domain, bool openTop) {
    PoissonSystem s = SteadyWindSolver::makeSystem(domain, /*verticalRatio=*/1.0);
    if (!openTop) s.sides[SIDE_ZMAX] = BoundaryKind::Neumann;
    return s;
}

}  // namespace

void UnsteadySettings::validate() const {
    if (!(dt_s >= 0.0) || !std::isfinite(dt_s))
        throw ParameterError("unsteady.dt_s", num(dt_s), "must be >= 0 s and finite");
    if (dt_s == 0.0 && (!(cfl > 0.0) || !std::isfinite(cfl)))
        throw ParameterError("unsteady.cfl", num(cfl), "must be > 0 and finite");
    if (!(maxDt_s > 0.0) || !std::isfinite(maxDt_s))
        throw ParameterError("unsteady.max_dt_s", num(maxDt_s), "must be > 0 s and finite");
    if (!(viscosity_m2ps >= 0.0) || !std::isfinite(viscosity_m2ps))
        throw ParameterError("unsteady.viscosity_m2ps", num(viscosity_m2ps),
                             "must be >= 0 m^2/s and finite");
    if (surfaceLayer.enabled) surfaceLayer.validate();
    if (!(vorticityConfinement >= 0.0) || !std::isfinite(vorticityConfinement))
        throw ParameterError("unsteady.vorticity_confinement", num(vorticityConfinement),
                             "must be >= 0 and finite");
    // Each event names its own key ("wind.gusts.duration_s"); the index makes it the scene's.
    for (size_t i = 0; i < gusts.size(); ++i) try {
            gusts[i].validate();
        } catch (const ParameterError& e) {
            throw e.inElement("wind.gusts", i);
        }
    for (size_t i = 0; i < whirlwinds.size(); ++i) try {
            whirlwinds[i].validate();
        } catch (const ParameterError& e) {
            throw e.inElement("wind.whirlwinds", i);
        }
}

UnsteadyWindSolver::UnsteadyWindSolver(const AirDomain& domain, const WindField& mean,
                                       const UnsteadySettings& settings, double referenceSpeed_mps)
    : mDomain(domain),
      mSettings(settings),
      mRefSpeed_mps(referenceSpeed_mps > 0.0 ? referenceSpeed_mps : 1.0),
      mField(mean),
      mSystem(projectionSystem(domain, settings.openTop)),
      mPoisson(mSystem) {
    mSettings.validate();
    if (mean.nx() != domain.nx() || mean.ny() != domain.ny() || mean.nz() != domain.nz())
        throw std::logic_error("UnsteadyWindSolver: the mean field does not match the domain");
    mGrid = MacGrid(domain.layout(), &domain.terrain());
    mMeanU = mean.u_mps(), mMeanV = mean.v_mps(), mMeanW = mean.w_mps();
    for (const auto* a : {&mMeanU, &mMeanV, &mMeanW})
        for (double x : *a) mMeanMax_mps = std::max(mMeanMax_mps, std::abs(x));
    for (const GustEvent& g : mSettings.gusts) mGustMax_mps += std::abs(g.peak_mps);
    // The far field: the mean flow plus the (horizontal) gusts at their peaks.
    mFarRate_ps = summarise(mMeanU, mMeanV, mMeanW).cellRate_ps + mGustMax_mps / mGrid.voxelSize_m;
    const int nx = mGrid.nx, ny = mGrid.ny, nz = mGrid.nz;
    mOkX.assign(mGrid.count(Placement::FaceX), 0);
    mOkY.assign(mGrid.count(Placement::FaceY), 0);
    mOkZ.assign(mGrid.count(Placement::FaceZ), 0);
    auto air = [&](int i, int j, int k) { return domain.isAir(i, j, k); };
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i <= nx; ++i)
                mOkX[mSystem.faceXIndex(i, j, k)] = (i > 0 && i < nx)
                                                        ? (air(i - 1, j, k) && air(i, j, k))
                                                    : i == 0 ? air(0, j, k)
                                                             : air(nx - 1, j, k);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i < nx; ++i)
                mOkY[mSystem.faceYIndex(i, j, k)] = (j > 0 && j < ny)
                                                        ? (air(i, j - 1, k) && air(i, j, k))
                                                    : domain.closedSidesY() ? 0
                                                    : j == 0                ? air(i, 0, k)
                                                                            : air(i, ny - 1, k);
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                mOkZ[mSystem.faceZIndex(i, j, k)] =
                    (k > 0 && k < nz) ? (air(i, j, k - 1) && air(i, j, k))
                    : k == nz         ? (mSettings.openTop ? air(i, j, nz - 1) : uint8_t(0))
                                      : 0;
    mSeeded.assign(mSettings.whirlwinds.size(), 0);
    if (mSettings.surfaceLayer.enabled)
        mStress = std::make_unique<TurbulentStress>(domain, mSettings.surfaceLayer,
                                                    mSettings.viscosity_m2ps, mOkX, mOkY, mOkZ);
    if (!mSettings.openTop) {
        // The steady field's small flux through the top becomes the lid's first projection.
        closeLid();
        (void)project();
    }
    for (const Whirlwind& w : mSettings.whirlwinds) mAxes.push_back(w.wsPosition_m);
}

Vec3d UnsteadyWindSolver::farField_mps(const Vec3d& ws, double t) const {
    Vec3d m;
    if (UniformLattice::usable(mGrid))  // the traces' cubic sampler: equal to round-off, faster
        UniformLattice(mGrid).sampleFaces(mMeanU.data(), mMeanV.data(), mMeanW.data(), ws.data(),
                                          m.data());
    else
        m = {sampleAt(mGrid, Placement::FaceX, mMeanU, ws),
             sampleAt(mGrid, Placement::FaceY, mMeanV, ws),
             sampleAt(mGrid, Placement::FaceZ, mMeanW, ws)};
    if (mSettings.gusts.empty()) return m;
    // The gust scales with height like the mean flow (capped at 1): calm air near the ground
    // gusts less.
    const double s = std::sqrt(m[0] * m[0] + m[1] * m[1]);
    const double factor =
        mRefSpeed_mps > 0.0 && mMeanMax_mps > 0.0 ? std::min(1.0, s / mRefSpeed_mps) : 1.0;
    for (const GustEvent& g : mSettings.gusts) {
        if (g.entry != GustEntry::Inflow) continue;  // region gusts are forcing, not far field
        const auto a = g.velocityAt_mps(t);
        m[0] += factor * a[0], m[1] += factor * a[1];
    }
    return m;
}

double UnsteadyWindSolver::cellRate_ps() const {
    // A step leaves its field's rate from its diagnostics pass; edits from outside clear it.
    if (!mFieldRateKnown) {
        mFieldRate_ps = summarise(mField.u_mps(), mField.v_mps(), mField.w_mps()).cellRate_ps;
        mFieldRateKnown = true;
    }
    const double own = mFieldRate_ps;
    return std::isfinite(own) ? std::max(own, mFarRate_ps) : own;
}

double UnsteadyWindSolver::nextDt_s() const {
    if (mSettings.dt_s > 0.0) return mSettings.dt_s;
    const double rate = cellRate_ps();
    if (!(rate > 0.0) || !std::isfinite(rate)) return mSettings.maxDt_s;
    return std::min(mSettings.maxDt_s, mSettings.cfl / rate);
}

const std::vector<double>& UnsteadyWindSolver::turbulentKineticEnergy_m2ps2() const {
    static const std::vector<double> none;
    return mStress ? mStress->turbulentKineticEnergy_m2ps2() : none;
}

void UnsteadyWindSolver::resetState(const WindField& state) {
    if (state.u_mps().size() != mField.u_mps().size() ||
        state.v_mps().size() != mField.v_mps().size() ||
        state.w_mps().size() != mField.w_mps().size())
        throw std::logic_error(
            "UnsteadyWindSolver::resetState: the field does not match the "
            "domain");
    mField.u_mps() = state.u_mps(), mField.v_mps() = state.v_mps(), mField.w_mps() = state.w_mps();
    mFieldRateKnown = false;
    extrapolateClosedFaces();
}

SolveReport UnsteadyWindSolver::continueFrom(const UnsteadyWindSolver& other) {
    if (other.mSettings.whirlwinds.size() != mSettings.whirlwinds.size())
        throw std::logic_error("UnsteadyWindSolver::continueFrom: the solvers' whirlwinds differ");
    std::vector<double>* mine[3] = {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()};
    const std::vector<double>* theirs[3] = {&other.mField.u_mps(), &other.mField.v_mps(),
                                            &other.mField.w_mps()};
    for (int c = 0; c < 3; ++c) {
        const Placement p = Placement(c);
        const auto n = mGrid.dims(p);
        tbb::parallel_for(0, n[2], [&](int k) {
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i)
                    (*mine[c])[mGrid.index(p, i, j, k)] =
                        sampleAt(other.mGrid, p, *theirs[c], mGrid.wsPosition(p, i, j, k));
        });
    }
    mTime_s = other.mTime_s;
    mSeeded = other.mSeeded;
    mAxes = other.mAxes;
    mPressureSteps = 0;
    mFieldRateKnown = false;
    extrapolateClosedFaces();
    if (!mSettings.openTop) closeLid();
    return project();
}

std::array<double, 2> UnsteadyWindSolver::regionCentre_m(const GustEvent& g, double t) const {
    const double a = radiansFromDegrees(g.direction_deg), dx = std::cos(a), dy = std::sin(a);
    std::array<double, 2> c = g.regionStart_m;
    if (!g.regionStartGiven) {
        // On the upwind side: from the box centre back along the direction to the box edge.
        const auto o = mGrid.wsMin_m;
        const double hx = 0.5 * mGrid.nx * mGrid.voxelSize_m,
                     hy = 0.5 * mGrid.ny * mGrid.voxelSize_m;
        const double sx = std::abs(dx) > 1e-12 ? hx / std::abs(dx) : 1e300,
                     sy = std::abs(dy) > 1e-12 ? hy / std::abs(dy) : 1e300;
        const double back = std::min(sx, sy);
        c = {o[0] + hx - back * dx, o[1] + hy - back * dy};
    }
    const double speed = g.regionSpeed_mps > 0.0 ? g.regionSpeed_mps : mRefSpeed_mps;
    const double travelled = speed * std::max(0.0, t - g.start_s);
    return {c[0] + travelled * dx, c[1] + travelled * dy};
}

void UnsteadyWindSolver::applyRegionGusts(double t, double dt) {
    const double beta = 1.0 - std::exp(-dt / GustEvent::REGION_RELAXATION_S);
    std::vector<double>* arrays[2] = {&mField.u_mps(), &mField.v_mps()};
    const std::vector<double>* means[2] = {&mMeanU, &mMeanV};
    const std::vector<uint8_t>* masks[2] = {&mOkX, &mOkY};
    for (const GustEvent& g : mSettings.gusts) {
        if (g.entry != GustEntry::Region || t < g.start_s || t > g.start_s + g.duration_s) continue;
        const auto c = regionCentre_m(g, t);
        const auto G = g.velocityAt_mps(t);
        const double R = g.regionRadius_m;
        for (int comp = 0; comp < 2; ++comp) {
            const Placement p = Placement(comp);
            const auto n = mGrid.dims(p);
            std::vector<double>& a = *arrays[comp];
            tbb::parallel_for(0, n[2], [&](int k) {
                for (int j = 0; j < n[1]; ++j)
                    for (int i = 0; i < n[0]; ++i) {
                        const size_t idx = mGrid.index(p, i, j, k);
                        if (!(*masks[comp])[idx]) continue;
                        const Vec3d ws = mGrid.wsPosition(p, i, j, k);
                        const double r = std::hypot(ws[0] - c[0], ws[1] - c[1]);
                        if (r >= R) continue;
                        const double x = std::clamp((r - 0.5 * R) / (0.5 * R), 0.0, 1.0);
                        const double w = 1.0 - x * x * (3.0 - 2.0 * x);
                        // The gust scales with height like the mean flow, as at the inflow.
                        const Vec3d m{sampleAt(mGrid, Placement::FaceX, mMeanU, ws),
                                      sampleAt(mGrid, Placement::FaceY, mMeanV, ws), 0.0};
                        const double f = mMeanMax_mps > 0.0
                                             ? std::min(1.0, std::hypot(m[0], m[1]) / mRefSpeed_mps)
                                             : 1.0;
                        const double target = (*means[comp])[idx] + f * G[comp];
                        a[idx] += beta * w * (target - a[idx]);
                    }
            });
        }
    }
}

void UnsteadyWindSolver::seedDue(double t0, double t1) {
    const Heightfield& T = mDomain.terrain();
    const GroundHeight ground = [&T](double x, double y) { return T.sample(x, y); };
    for (size_t n = 0; n < mSettings.whirlwinds.size(); ++n) {
        const Whirlwind& ww = mSettings.whirlwinds[n];
        if (mSeeded[n] || ww.start_s >= t1) continue;
        (void)t0;
        addWhirlwind(mGrid, ww, mAxes[n], 1.0, ground, mDomain.wsTop_m(), mField.u_mps(),
                     mField.v_mps(), mField.w_mps(), {&mOkX, &mOkY, &mOkZ});
        mSeeded[n] = 1;
    }
}

void UnsteadyWindSolver::applyForcing(double t0, double dt) {
    const Heightfield& T = mDomain.terrain();
    const GroundHeight ground = [&T](double x, double y) { return T.sample(x, y); };
    for (size_t n = 0; n < mSettings.whirlwinds.size(); ++n) {
        const Whirlwind& ww = mSettings.whirlwinds[n];
        if (!ww.forced || !mSeeded[n] || (ww.lifetime_s && t0 > ww.start_s + *ww.lifetime_s))
            continue;
        const double R = std::max(FORCING_RING_CORES * ww.coreRadius_m, 2.0 * mGrid.voxelSize_m);
        const double g0 = ground(mAxes[n][0], mAxes[n][1]);
        const double column = ww.height_m > 0 ? ww.height_m : mDomain.wsTop_m() - g0;
        const double z = g0 + 0.25 * column;
        const double target = ww.circulationWithin_m2ps(R);
        if (target == 0.0) continue;
        const double now = circulationAround(mGrid, velocity(), mAxes[n], R, z);
        const double deficit = std::clamp((target - now) / target, 0.0, 1.0);
        const double vPeak =
            std::abs(ww.circulation()) * peakSpeedFactor(ww.profile) / (2 * PI * ww.coreRadius_m);
        const double tau =
            std::max(ww.coreRadius_m / std::max(vPeak, 1e-9), MIN_FORCING_STEPS * dt);
        const double scale = deficit * (1.0 - std::exp(-dt / tau));
        if (scale > 0.0)
            addWhirlwind(mGrid, ww, mAxes[n], scale, ground, mDomain.wsTop_m(), mField.u_mps(),
                         mField.v_mps(), mField.w_mps(), {&mOkX, &mOkY, &mOkZ});
    }
}

StepReport UnsteadyWindSolver::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::logic_error("UnsteadyWindSolver::step: dt_s must be > 0, got " + num(dt));
    const auto tStart = Clock::now();
    StepReport rep;
    const double t0 = mTime_s, t1 = mTime_s + dt;
    rep.dt_s = dt;
    rep.cfl = cellRate_ps() * dt;

    // 1. whirlwinds: seeding and carrying the axis markers (vortex code only when needed).
    auto t = Clock::now();
    if (!mSettings.whirlwinds.empty()) {
        seedDue(t0, t1);
        const Heightfield& T = mDomain.terrain();
        const FarField far = [&](const Vec3d& p) { return farField_mps(p, t0); };
        for (size_t n = 0; n < mAxes.size(); ++n) {
            if (!mSeeded[n]) continue;
            const Whirlwind& ww = mSettings.whirlwinds[n];
            const double g0 = T.sample(mAxes[n][0], mAxes[n][1]);
            const double column = ww.height_m > 0 ? ww.height_m : mDomain.wsTop_m() - g0;
            const Vec3d x{mAxes[n][0], mAxes[n][1], g0 + 0.25 * column};
            const Vec3d u0 = velocityAt(mGrid, velocity(), far, x);
            const Vec3d mid{x[0] + 0.5 * dt * u0[0], x[1] + 0.5 * dt * u0[1], x[2]};
            const Vec3d u1 = velocityAt(mGrid, velocity(), far, mid);
            mAxes[n] = {x[0] + dt * u1[0], x[1] + dt * u1[1]};
        }
    }
    rep.forcing_s += since(t);

    // 2. advection of each component through the frozen field.
    t = Clock::now();
    {
        // The field before the step moves to mBefore (a swap, not a copy); each component is
        // advected from there back into the field, which the advection writes whole.
        std::vector<double>* now[3] = {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()};
        for (int c = 0; c < 3; ++c) {
            std::swap(mBefore[c], *now[c]);
            now[c]->resize(mBefore[c].size());
        }
        const std::vector<double>&u0 = mBefore[0], &v0 = mBefore[1], &w0 = mBefore[2];
        MacVelocity vel{&u0, &v0, &w0};
        if (mSettings.precision == AdvectionPrecision::Single && !mSettings.eulerianAdvection &&
            UniformLattice::usable(mGrid)) {  // the rows run on cubic cells only
            for (int c = 0; c < 3; ++c)       // rounded once for the three components
                detail::roundToFloat(mBefore[c], mBeforeSingle[c]);
            vel.uSingle = &mBeforeSingle[0], vel.vSingle = &mBeforeSingle[1],
            vel.wSingle = &mBeforeSingle[2];
        }
        const FarField far = [&](const Vec3d& p) { return farField_mps(p, t1); };
        const std::vector<double>* src[3] = {&u0, &v0, &w0};
        std::vector<double>* dst[3] = {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()};
        const std::vector<uint8_t>* masks[3] = {&mOkX, &mOkY, &mOkZ};
        for (int c = 0; c < 3; ++c) {
            const OutsideValue outside = [&, c](const Vec3d& p) { return farField_mps(p, t1)[c]; };
            if (mSettings.eulerianAdvection)
                (void)advectEulerian(mGrid, Placement(c), *src[c], vel, outside, dt, *dst[c],
                                     masks[c]);
            else
                advect(mGrid, Placement(c), *src[c], vel, far, outside, dt, mSettings.advection,
                       *dst[c], masks[c], mSettings.precision, &mAdvectionScratch);
        }
    }
    rep.advection_s = since(t);

    if (!mSettings.openTop) closeLid();
    // 3. forces (the energy they add is measured only when they run).
    t = Clock::now();
    const bool regionGust =
        std::any_of(mSettings.gusts.begin(), mSettings.gusts.end(), [&](const GustEvent& g) {
            return g.entry == GustEntry::Region && t1 >= g.start_s &&
                   t0 <= g.start_s + g.duration_s;
        });
    const bool forcing = std::any_of(mSettings.whirlwinds.begin(), mSettings.whirlwinds.end(),
                                     [](const Whirlwind& w) { return w.forced; }) ||
                         mSettings.vorticityConfinement > 0.0 || regionGust;
    const double keBeforeForces = forcing ? kineticEnergy_m5ps2() : 0.0;
    if (regionGust) applyRegionGusts(t1, dt);
    if (!mSettings.whirlwinds.empty()) applyForcing(t0, dt);
    if (mSettings.vorticityConfinement > 0.0)
        addVorticityConfinement(mGrid, mDomain.airFlags(), mSettings.vorticityConfinement, dt,
                                mField.u_mps(), mField.v_mps(), mField.w_mps());
    if (forcing) rep.forcingEnergy_m5ps2 = kineticEnergy_m5ps2() - keBeforeForces;
    rep.forcing_s += since(t);

    // Incremental pressure (Goda 1979): add the summed projection corrections before the stress
    // step; the projection below then adds only the increment, recorded as after - before.
    std::vector<double>* comps[3] = {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()};
    const std::vector<uint8_t>* okMasks[3] = {&mOkX, &mOkY, &mOkZ};
    auto addGradPsi = [&](double sign) {
        for (int c = 0; c < 3; ++c) {
            if (mGradPsi[c].empty()) mGradPsi[c].assign(comps[c]->size(), 0.0);
            for (size_t f = 0; f < mGradPsi[c].size(); ++f)
                if ((*okMasks[c])[f]) mGradPsi[c][f] += sign * (*comps[c])[f];
        }
    };
    if (mSettings.incrementalPressure && !mGradPsi[0].empty())
        for (int c = 0; c < 3; ++c)
            for (size_t f = 0; f < mGradPsi[c].size(); ++f) (*comps[c])[f] += mGradPsi[c][f];

    // 4. viscosity: the surface layer's stresses, or a constant viscosity.
    if (mStress) {
        t = Clock::now();
        rep.turbulence = mStress->apply(dt, mField.u_mps(), mField.v_mps(), mField.w_mps());
        if (!mSettings.openTop) closeLid();
        rep.viscosity_s = since(t);
    } else if (mSettings.viscosity_m2ps > 0.0) {
        t = Clock::now();
        const ViscosityReport vr =
            diffuseImplicit(mGrid, mSettings.viscosity_m2ps, dt, {&mOkX, &mOkY, &mOkZ},
                            mField.u_mps(), mField.v_mps(), mField.w_mps());
        rep.viscosityIterations = vr.iterations;
        rep.viscosity_s = since(t);
    }

    // 5. projection.
    t = Clock::now();
    if (mSettings.incrementalPressure) addGradPsi(-1.0);
    rep.projection = project(mSettings.projection, dt, rep.cfl);
    if (mSettings.incrementalPressure) addGradPsi(+1.0);
    rep.projection_s = since(t);

    mTime_s = t1;
    rep.t_s = t1;
    // One pass over the new field: the report's diagnostics and the next step's cell rate.
    const FieldSummary sum = summarise(mField.u_mps(), mField.v_mps(), mField.w_mps());
    rep.maxSpeed_mps = sum.maxSpeed_mps;
    rep.kineticEnergy_m5ps2 = sum.kineticEnergy_m5ps2;
    rep.maxDivergenceScaled = sum.maxOutflux / mRefSpeed_mps;
    rep.projection.maxDivergenceScaled = rep.maxDivergenceScaled;
    rep.finite =
        sum.finite && std::isfinite(rep.maxSpeed_mps) && std::isfinite(rep.kineticEnergy_m5ps2);
    mFieldRate_ps = sum.cellRate_ps, mFieldRateKnown = true;
    rep.total_s = since(tStart);
    return rep;
}

std::vector<StepReport> UnsteadyWindSolver::advanceTo(double tEnd) {
    std::vector<StepReport> reps;
    // Steps shorter than this fraction of a regular step are merged into the previous one.
    constexpr double MERGE_FRACTION = 1e-6;
    while (mTime_s < tEnd) {
        double dt = nextDt_s();
        if (mTime_s + dt * (1.0 + MERGE_FRACTION) >= tEnd) dt = tEnd - mTime_s;
        reps.push_back(step(dt));
        if (!reps.back().finite) break;
    }
    return reps;
}

}  // namespace gale::sim

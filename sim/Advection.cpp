/// \file Advection.cpp
/// Semi-Lagrangian (Stam 1999), MacCormack (Selle et al. 2008) and BFECC (Kim et al. 2005)
/// advection on the MAC grid, with substepped traces stopped at the terrain (Advection.h).
#include "sim/Advection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gale::sim {

const char* advectionSchemeName(AdvectionScheme s) {
    switch (s) {
        case AdvectionScheme::SemiLagrangian:
            return "semi_lagrangian";
        case AdvectionScheme::MacCormack:
            return "maccormack";
        case AdvectionScheme::Bfecc:
            return "bfecc";
    }
    return "?";
}

AdvectionScheme advectionSchemeFromName(const std::string& name) {
    if (name == "semi_lagrangian") return AdvectionScheme::SemiLagrangian;
    if (name == "maccormack") return AdvectionScheme::MacCormack;
    if (name == "bfecc") return AdvectionScheme::Bfecc;
    throw std::invalid_argument(
        "advection must be one of semi_lagrangian, maccormack, bfecc (got \"" + name + "\")");
}

namespace {

/// Offset of a placement's samples in index space: faces sit on integer coordinates along their
/// axis and at half cells across it.
constexpr double offset(Placement p, int axis) { return int(p) == axis ? 0.0 : 0.5; }

}  // namespace

double sampleAt(const MacGrid& g, Placement p, const std::vector<double>& q, const Vec3d& ws,
                double* lo, double* hi) {
    return g.sample(p, q.data(), g.isFromWs(ws), lo, hi);
}

Vec3d velocityAt(const MacGrid& g, const MacVelocity& vel, const FarField& far, const Vec3d& ws) {
    if (far && g.outside(ws)) return far(ws);
    return {sampleAt(g, Placement::FaceX, *vel.u, ws), sampleAt(g, Placement::FaceY, *vel.v, ws),
            sampleAt(g, Placement::FaceZ, *vel.w, ws)};
}

namespace {

/// One placement's samples read in index space through the layout's sampler (the hot loop of the
/// advection).
struct IndexSampler {
    const GridLayout& g;
    Placement p;
    const double* a;
    IndexSampler(const MacGrid& grid, Placement placement, const std::vector<double>& q)
        : g(grid), p(placement), a(q.data()) {}
    double operator()(const double* is, double* lo = nullptr, double* hi = nullptr) const {
        return g.sample(p, a, {is[0], is[1], is[2]}, lo, hi);
    }
};

bool outsideIs(const MacGrid& g, const double* is) {
    return !(is[0] >= 0.0 && is[0] <= g.nx && is[1] >= 0.0 && is[1] <= g.ny && is[2] <= g.nz);
}

/// Height of the point above the terrain surface in cells (negative below); +inf without terrain.
double aboveGroundCells(const MacGrid& g, const double* is) {
    if (!g.terrain) return HUGE_VAL;
    const Vec3d ws = g.wsFromIs({is[0], is[1], is[2]});
    return g.cellsFromMetres(ws[2] - g.terrain->sample(ws[0], ws[1]));
}

/// Bisection steps locating where a substep crosses the terrain: the stop lies within
/// 2^-TERRAIN_BISECTIONS of a substep (< 1e-3 cells) above the surface.
constexpr int TERRAIN_BISECTIONS = 12;

/// The substepped midpoint trace of traceBack() in index space (Advection.h, "Traces"):
/// displacements in cells are dt u / h through MacGrid::cellsFromMetres. velocityIs(is, u) gives
/// the velocity (m/s) at an index-space point, the far field outside the box.
/// Index-space z above which no terrain lies (-inf: no terrain): traces above it skip the
/// surface test, which is most of the box.
double terrainTopIs(const MacGrid& g) {
    return g.terrain ? g.isFromWs({0.0, 0.0, g.terrain->maxHeight_m()})[2] : -HUGE_VAL;
}

template <class VelocityIs>
void traceIs(const MacGrid& g, const VelocityIs& velocityIs, const double* x0, double dt,
             double groundTopIs, double* dep) {
    double x[3] = {x0[0], x0[1], x0[2]};
    const double sign = dt < 0.0 ? -1.0 : 1.0;
    double remaining = std::abs(dt);
    // Only a trace that starts above the surface is stopped by it (samples inside cut cells may
    // sit below the bilinear surface; they are traced freely until they emerge).
    bool above = x[2] > groundTopIs || aboveGroundCells(g, x) >= 0.0;
    // A trace that would need more substeps than this is stalled in a near-zero velocity field
    // (each substep covers the whole remaining time once the speed is small): cannot happen,
    // but the cap keeps every trace finite whatever the field holds.
    constexpr int MAX_SUBSTEPS = 4096;
    for (int n = 0; n < MAX_SUBSTEPS && remaining > 0.0; ++n) {
        double u0[3], xm[3], u1[3], xn[3];
        velocityIs(x, u0);
        if (outsideIs(g, x)) {
            // Outside the box: the far field is smooth, finish in one midpoint step.
            for (int a = 0; a < 3; ++a)
                xm[a] = x[a] - sign * g.cellsFromMetres(0.5 * remaining * u0[a]);
            velocityIs(xm, u1);
            for (int a = 0; a < 3; ++a) x[a] -= sign * g.cellsFromMetres(remaining * u1[a]);
            break;
        }
        const double speedCells =
            g.cellsFromMetres(std::max({std::abs(u0[0]), std::abs(u0[1]), std::abs(u0[2])}));
        double s = remaining;
        if (speedCells * s > MAX_TRACE_CELLS_PER_SUBSTEP)
            s = MAX_TRACE_CELLS_PER_SUBSTEP / speedCells;
        if (!(s > 0.0)) break;  // infinite speed: stay put rather than spin
        for (int a = 0; a < 3; ++a) xm[a] = x[a] - sign * g.cellsFromMetres(0.5 * s * u0[a]);
        velocityIs(xm, u1);
        for (int a = 0; a < 3; ++a) xn[a] = x[a] - sign * g.cellsFromMetres(s * u1[a]);
        const double heightNew = xn[2] > groundTopIs ? HUGE_VAL : aboveGroundCells(g, xn);
        if (above && heightNew < 0.0) {
            // Crossed into the rock: bisect for the last point above the surface and stop there.
            double lo = 0.0, hi = 1.0;
            for (int b = 0; b < TERRAIN_BISECTIONS; ++b) {
                const double mid = 0.5 * (lo + hi);
                const double p[3] = {x[0] + mid * (xn[0] - x[0]), x[1] + mid * (xn[1] - x[1]),
                                     x[2] + mid * (xn[2] - x[2])};
                (aboveGroundCells(g, p) >= 0.0 ? lo : hi) = mid;
            }
            for (int a = 0; a < 3; ++a) x[a] += lo * (xn[a] - x[a]);
            break;
        }
        above = above || heightNew >= 0.0;
        for (int a = 0; a < 3; ++a) x[a] = xn[a];
        remaining -= s;
    }
    for (int a = 0; a < 3; ++a) dep[a] = x[a];
}

/// The velocity (m/s, world axes) at an index-space point: interpolated from the staggered faces,
/// or the far field's outside the box when one is given.
struct FaceVelocitySampler {
    FaceVelocitySampler(const MacGrid& grid, const MacVelocity& vel, const FarField& farField)
        : g(grid),
          far(farField),
          Su(grid, Placement::FaceX, *vel.u),
          Sv(grid, Placement::FaceY, *vel.v),
          Sw(grid, Placement::FaceZ, *vel.w) {}
    void operator()(const double* is, double* u) const {
        if (far && outsideIs(g, is)) {
            const Vec3d f = far(g.wsFromIs({is[0], is[1], is[2]}));
            u[0] = f[0], u[1] = f[1], u[2] = f[2];
            return;
        }
        u[0] = Su(is), u[1] = Sv(is), u[2] = Sw(is);
    }
    const MacGrid& g;
    const FarField& far;
    const IndexSampler Su, Sv, Sw;
};

/// One semi-Lagrangian pass; optionally records the min/max of the interpolation neighbours and
/// whether the departure point left the box.
void semiLagrangian(const MacGrid& g, Placement p, const std::vector<double>& q,
                    const MacVelocity& vel, const FarField& far, const OutsideValue& outside,
                    double dt, std::vector<double>& out, const std::vector<uint8_t>* mask,
                    std::vector<double>* lo, std::vector<double>* hi) {
    const auto n = g.dims(p);
    out.resize(q.size());
    if (lo) lo->resize(q.size()), hi->resize(q.size());
    const IndexSampler Q(g, p, q);
    const double groundTop = terrainTopIs(g);
    const FaceVelocitySampler velocityIs(g, vel, far);
    tbb::parallel_for(0, n[2], [&](int k) {
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                const size_t idx = g.index(p, i, j, k);
                if (mask && !(*mask)[idx]) {
                    out[idx] = q[idx];
                    if (lo) (*lo)[idx] = -HUGE_VAL, (*hi)[idx] = HUGE_VAL;
                    continue;
                }
                const double x0[3] = {i + offset(p, 0), j + offset(p, 1), k + offset(p, 2)};
                double dep[3];
                traceIs(g, velocityIs, x0, dt, groundTop, dep);
                if (outside && outsideIs(g, dep)) {
                    out[idx] = outside(g.wsFromIs({dep[0], dep[1], dep[2]}));
                    if (lo) (*lo)[idx] = -HUGE_VAL, (*hi)[idx] = HUGE_VAL;  // no limiter on inflow
                } else if (lo) {
                    out[idx] = Q(dep, &(*lo)[idx], &(*hi)[idx]);
                } else {
                    out[idx] = Q(dep);
                }
            }
    });
}

}  // namespace

Vec3d traceBack(const MacGrid& g, const MacVelocity& vel, const FarField& far, const Vec3d& ws,
                double dt) {
    const FaceVelocitySampler velocityIs(g, vel, far);
    const Vec3d is = g.isFromWs(ws);
    double dep[3];
    traceIs(g, velocityIs, is.data(), dt, terrainTopIs(g), dep);
    return g.wsFromIs({dep[0], dep[1], dep[2]});
}

void advect(const MacGrid& g, Placement p, const std::vector<double>& q, const MacVelocity& vel,
            const FarField& far, const OutsideValue& outside, double dt, AdvectionScheme scheme,
            std::vector<double>& out, const std::vector<uint8_t>* mask) {
    if (q.size() != g.count(p)) throw std::invalid_argument("advect: quantity has the wrong size");
    if (!vel.u || !vel.v || !vel.w || vel.u->size() != g.count(Placement::FaceX) ||
        vel.v->size() != g.count(Placement::FaceY) || vel.w->size() != g.count(Placement::FaceZ))
        throw std::invalid_argument("advect: velocity arrays have the wrong size");
    if (mask && mask->size() != q.size())
        throw std::invalid_argument("advect: mask has the wrong size");
    if (scheme == AdvectionScheme::SemiLagrangian) {
        semiLagrangian(g, p, q, vel, far, outside, dt, out, mask, nullptr, nullptr);
        return;
    }
    std::vector<double> fwd, back, lo, hi;
    semiLagrangian(g, p, q, vel, far, outside, dt, fwd, mask, &lo, &hi);
    semiLagrangian(g, p, fwd, vel, far, outside, -dt, back, mask, nullptr, nullptr);
    out.resize(q.size());
    if (scheme == AdvectionScheme::MacCormack) {
        // Selle et al. 2008: phi^{n+1} = phi_f + (phi^n - phi_b) / 2, limited.
        tbb::parallel_for(size_t(0), q.size(), [&](size_t idx) {
            const double v = fwd[idx] + 0.5 * (q[idx] - back[idx]);
            out[idx] = std::isfinite(v) ? std::clamp(v, lo[idx], hi[idx]) : fwd[idx];
        });
        return;
    }
    // Kim et al. 2005: advect phi + (phi - phi_b) / 2 forward once more, limited by the
    // neighbours of the plain forward pass.
    std::vector<double> corrected(q.size());
    tbb::parallel_for(size_t(0), q.size(),
                      [&](size_t idx) { corrected[idx] = q[idx] + 0.5 * (q[idx] - back[idx]); });
    semiLagrangian(g, p, corrected, vel, far, outside, dt, out, mask, nullptr, nullptr);
    tbb::parallel_for(size_t(0), q.size(), [&](size_t idx) {
        const double v = out[idx];
        out[idx] = std::isfinite(v) ? std::clamp(v, lo[idx], hi[idx]) : fwd[idx];
    });
}

}  // namespace gale::sim

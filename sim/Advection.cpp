/// \file Advection.cpp
/// Semi-Lagrangian (Stam 1999), MacCormack (Selle et al. 2008) and BFECC (Kim et al. 2005)
/// advection on the MAC grid, with substepped traces stopped at the terrain (Advection.h).
#include "sim/Advection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "base/ParameterError.h"
#include "sim/AdvectionRows.h"
#include "sim/UniformLattice.h"

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
    throw ParameterError("unsteady.advection", "\"" + name + "\"",
                         "one of semi_lagrangian, maccormack, bfecc");
}

const char* advectionPrecisionName(AdvectionPrecision p) {
    return p == AdvectionPrecision::Single ? "single" : "double";
}

AdvectionPrecision advectionPrecisionFromName(const std::string& name) {
    if (name == "single") return AdvectionPrecision::Single;
    if (name == "double") return AdvectionPrecision::Double;
    throw ParameterError("unsteady.precision", "\"" + name + "\"", "one of single, double");
}

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

/// Height of a world point above the terrain surface, metres (negative below); +inf without
/// terrain.
double aboveGround_m(const MacGrid& g, const double* x) {
    return g.terrain ? x[2] - g.terrain->sample(x[0], x[1]) : HUGE_VAL;
}

/// The general lattice: world points read through the layout's own sampler at
/// GridLayout::isFromWs (cubic cells and stretched layers alike).
struct LayoutLattice {
    explicit LayoutLattice(const MacGrid& grid) : g(grid) {}
    /// The three MAC components at world point ws (metres) and the thickness (metres) of the
    /// layer it lies in (the end layers' outside the box).
    void sampleFaces(const double* U, const double* V, const double* W, const double* ws, double* u,
                     double* layer_m) const {
        const Vec3d is = g.isFromWs({ws[0], ws[1], ws[2]});
        *layer_m =
            g.uniformZ() ? g.voxelSize_m : g.dz_m(std::clamp(int(std::floor(is[2])), 0, g.nz - 1));
        const Vec3d s = g.sampleFaces(U, V, W, is);
        u[0] = s[0], u[1] = s[1], u[2] = s[2];
    }
    /// sampleFaces at sample (i, j, k) of placement p, whose world position is ws.
    void sampleFacesAt(Placement, int, int, int, const double* U, const double* V, const double* W,
                       const double* ws, double* u, double* layer_m) const {
        sampleFaces(U, V, W, ws, u, layer_m);
    }
    double sample(Placement p, const double* q, const double* ws, double* lo, double* hi) const {
        return g.sample(p, q, g.isFromWs({ws[0], ws[1], ws[2]}), lo, hi);
    }
    const MacGrid& g;
};

/// The fast lattice of cubic cells (UniformLattice.h): same answers to round-off, every layer h
/// thick.
struct CubicLattice {
    explicit CubicLattice(const MacGrid& grid) : lattice(grid), h_m(grid.voxelSize_m) {}
    void sampleFaces(const double* U, const double* V, const double* W, const double* ws, double* u,
                     double* layer_m) const {
        *layer_m = h_m;
        lattice.sampleFaces(U, V, W, ws, u);
    }
    /// At a sample of the lattice the components come from its neighbours directly
    /// (UniformLattice::facesAtSample: 1, 2 or 4 reads each instead of 8 and a stencil).
    void sampleFacesAt(Placement p, int i, int j, int k, const double* U, const double* V,
                       const double* W, const double*, double* u, double* layer_m) const {
        *layer_m = h_m;
        lattice.facesAtSample(p, i, j, k, U, V, W, u);
    }
    double sample(Placement p, const double* q, const double* ws, double* lo, double* hi) const {
        return lattice.sample(p, q, ws, lo, hi);
    }
    UniformLattice lattice;
    double h_m;
};

/// The box's x, y sides and top in world metres, for the test "outside through an x or y side
/// or the top" (MacGrid::outside without the conversion to index space).
struct BoxSides {
    explicit BoxSides(const MacGrid& g)
        : x0(g.wsMin_m[0]),
          x1(g.wsMin_m[0] + g.nx * g.voxelSize_m),
          y0(g.wsMin_m[1]),
          y1(g.wsMin_m[1] + g.ny * g.voxelSize_m),
          top(g.wsTop_m()) {}
    bool outside(const double* x) const {
        return !(x[0] >= x0 && x[0] <= x1 && x[1] >= y0 && x[1] <= y1 && x[2] <= top);
    }
    double x0, x1, y0, y1, top;  ///< metres
};

/// The velocity (m/s, world axes) at a world point: the three MAC components interpolated from
/// their own faces through the lattice (LayoutLattice or CubicLattice), or the far field's
/// outside the box when one is given. Also gives the thickness (metres) of the layer the point
/// lies in (the end layers' outside the box), the spacing a vertical displacement is measured in.
template <class Lattice>
struct FaceVelocitySampler {
    FaceVelocitySampler(const MacGrid& grid, const MacVelocity& vel, const FarField& farField)
        : g(grid),
          lattice(grid),
          box(grid),
          far(farField),
          U(vel.u->data()),
          V(vel.v->data()),
          W(vel.w->data()) {}
    void operator()(const double* ws, double* u, double* layer_m) const {
        if (far && box.outside(ws)) {
            double unused[3];
            lattice.sampleFaces(U, V, W, ws, unused, layer_m);
            const Vec3d f = far({ws[0], ws[1], ws[2]});
            u[0] = f[0], u[1] = f[1], u[2] = f[2];
            return;
        }
        lattice.sampleFaces(U, V, W, ws, u, layer_m);
    }
    /// operator() at sample (i, j, k) of placement p, whose world position is ws (metres).
    void atSample(Placement p, int i, int j, int k, const double* ws, double* u,
                  double* layer_m) const {
        if (far && box.outside(ws)) return (*this)(ws, u, layer_m);
        lattice.sampleFacesAt(p, i, j, k, U, V, W, ws, u, layer_m);
    }
    const MacGrid& g;
    Lattice lattice;
    BoxSides box;
    const FarField& far;
    const double *U, *V, *W;
};

/// Bisection steps locating where a substep crosses the terrain: the stop lies within
/// 2^-TERRAIN_BISECTIONS of a substep (< 1e-3 cells) above the surface.
constexpr int TERRAIN_BISECTIONS = 12;

/// What a trace needs at its start point that does not depend on the direction of the trace:
/// the velocity there (m/s), the thickness of its layer (m) and whether it lies on or above the
/// terrain surface. The forward and backward passes of MacCormack and BFECC start from the same
/// samples, so the forward pass computes it and keeps it for the others.
struct TraceStart {
    double u[3];
    double layer_m;
    bool above;
};

/// The TraceStart at world point x0 (metres); with a sample (p, i, j, k) that lies at x0 the
/// velocity there is read from the sample's neighbours (FaceVelocitySampler::atSample).
template <class Lattice>
TraceStart traceStart(const MacGrid& g, const FaceVelocitySampler<Lattice>& velocityWs,
                      const double* x0, double groundTop_m, const Placement* p = nullptr, int i = 0,
                      int j = 0, int k = 0) {
    TraceStart s{};
    if (p)
        velocityWs.atSample(*p, i, j, k, x0, s.u, &s.layer_m);
    else
        velocityWs(x0, s.u, &s.layer_m);
    // Only a trace that starts above the surface is stopped by it (samples inside cut cells may
    // sit below the bilinear surface; they are traced freely until they emerge).
    s.above = x0[2] > groundTop_m || aboveGround_m(g, x0) >= 0.0;
    return s;
}

/// The substepped midpoint trace of traceBack() in world space (Advection.h, "Traces"): a
/// substep moves by s u metres; its length s holds the travel to at most
/// MAX_TRACE_CELLS_PER_SUBSTEP cells along every axis, horizontal cells of h and vertical ones
/// of the local layer's thickness (so a trace through thin stretched layers takes short
/// substeps). x0 and dep are world metres.
template <class Lattice>
void traceWs(const MacGrid& g, const FaceVelocitySampler<Lattice>& velocityWs, const double* x0,
             const TraceStart& start, double dt, double groundTop_m, double* dep) {
    double x[3] = {x0[0], x0[1], x0[2]};
    const double sign = dt < 0.0 ? -1.0 : 1.0;
    double remaining = std::abs(dt);
    bool above = start.above;
    const double h = g.voxelSize_m;
    // A trace that would need more substeps than this is stalled in a near-zero velocity field
    // (each substep covers the whole remaining time once the speed is small): cannot happen,
    // but the cap keeps every trace finite whatever the field holds.
    constexpr int MAX_SUBSTEPS = 4096;
    for (int n = 0; n < MAX_SUBSTEPS && remaining > 0.0; ++n) {
        double u0[3], xm[3], u1[3], xn[3], layer_m, unused_m;
        if (n == 0) {
            u0[0] = start.u[0], u0[1] = start.u[1], u0[2] = start.u[2], layer_m = start.layer_m;
        } else {
            velocityWs(x, u0, &layer_m);
        }
        if (velocityWs.box.outside(x)) {
            // Outside the box: the far field is smooth, finish in one midpoint step.
            for (int a = 0; a < 3; ++a) xm[a] = x[a] - sign * 0.5 * remaining * u0[a];
            velocityWs(xm, u1, &unused_m);
            for (int a = 0; a < 3; ++a) x[a] -= sign * remaining * u1[a];
            break;
        }
        const double cellsPerSecond =
            std::max({std::abs(u0[0]) / h, std::abs(u0[1]) / h, std::abs(u0[2]) / layer_m});
        double s = remaining;
        if (cellsPerSecond * s > MAX_TRACE_CELLS_PER_SUBSTEP)
            s = MAX_TRACE_CELLS_PER_SUBSTEP / cellsPerSecond;
        if (!(s > 0.0)) break;  // infinite speed: stay put rather than spin
        for (int a = 0; a < 3; ++a) xm[a] = x[a] - sign * 0.5 * s * u0[a];
        velocityWs(xm, u1, &unused_m);
        for (int a = 0; a < 3; ++a) xn[a] = x[a] - sign * s * u1[a];
        const double heightNew = xn[2] > groundTop_m ? HUGE_VAL : aboveGround_m(g, xn);
        if (above && heightNew < 0.0) {
            // Crossed into the rock: bisect for the last point above the surface and stop there.
            double lo = 0.0, hi = 1.0;
            for (int b = 0; b < TERRAIN_BISECTIONS; ++b) {
                const double mid = 0.5 * (lo + hi);
                const double p[3] = {x[0] + mid * (xn[0] - x[0]), x[1] + mid * (xn[1] - x[1]),
                                     x[2] + mid * (xn[2] - x[2])};
                (aboveGround_m(g, p) >= 0.0 ? lo : hi) = mid;
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

/// One semi-Lagrangian pass (`only`: just the samples it flags, the rest left as they are);
/// optionally records the min/max of the interpolation neighbours and
/// whether the departure point left the box. `starts`: the TraceStart of every sample of this
/// placement (index as its array), or null to compute each on the way; `record` (with null
/// starts): where to keep the ones computed, for the scheme's later passes (masked-out samples
/// are not written). groundTop: g.terrainTop_m().
template <class Lattice>
void semiLagrangian(const MacGrid& g, Placement p, const std::vector<double>& q,
                    const MacVelocity& vel, const FarField& far, const OutsideValue& outside,
                    double dt, std::vector<double>& out, const std::vector<uint8_t>* mask,
                    std::vector<double>* lo, std::vector<double>* hi, const TraceStart* starts,
                    TraceStart* record, double groundTop, const uint8_t* only = nullptr) {
    const auto n = g.dims(p);
    out.resize(q.size());
    if (lo) lo->resize(q.size()), hi->resize(q.size());
    const FaceVelocitySampler<Lattice> velocityWs(g, vel, far);
    tbb::parallel_for(0, n[2], [&](int k) {
        for (int j = 0; j < n[1]; ++j) {
            const size_t row = g.index(p, 0, j, k);
            for (int i = 0; i < n[0]; ++i) {
                if (only) {  // the row pass wrote the rest: jump to the next sample it flagged
                    const void* next = std::memchr(only + row + i, 1, size_t(n[0] - i));
                    if (!next) break;
                    i = int(static_cast<const uint8_t*>(next) - (only + row));
                }
                const size_t idx = row + size_t(i);
                if (mask && !(*mask)[idx]) {
                    out[idx] = q[idx];
                    if (lo) (*lo)[idx] = -HUGE_VAL, (*hi)[idx] = HUGE_VAL;
                    continue;
                }
                const Vec3d x0 = g.wsPosition(p, i, j, k);
                double dep[3];
                TraceStart start;
                if (starts)
                    start = starts[idx];
                else
                    start = traceStart(g, velocityWs, x0.data(), groundTop, &p, i, j, k);
                if (record) record[idx] = start;
                traceWs(g, velocityWs, x0.data(), start, dt, groundTop, dep);
                if (outside && velocityWs.box.outside(dep)) {
                    out[idx] = outside({dep[0], dep[1], dep[2]});
                    if (lo) (*lo)[idx] = -HUGE_VAL, (*hi)[idx] = HUGE_VAL;  // no limiter on inflow
                    continue;
                }
                out[idx] =
                    lo ? velocityWs.lattice.sample(p, q.data(), dep, &(*lo)[idx], &(*hi)[idx])
                       : velocityWs.lattice.sample(p, q.data(), dep, nullptr, nullptr);
            }
        }
    });
}

}  // namespace

void detail::roundToFloat(const std::vector<double>& a, std::vector<float>& out) {
    out.resize(a.size());
    constexpr size_t CHUNK = 16384;
    tbb::parallel_for(size_t(0), (a.size() + CHUNK - 1) / CHUNK, [&](size_t c) {
        const size_t end = std::min(a.size(), (c + 1) * CHUNK);
        for (size_t n = c * CHUNK; n < end; ++n) out[n] = float(a[n]);
    });
}

namespace {

/// Which of a scheme's passes a pass is: its only one, the first of several (which may keep
/// its trace starts for the others), or a later one.
enum class PassRole { Only, First, Later };

/// The scheme's combination of semi-Lagrangian passes; `pass(q, dt, out, lo, hi, role)` is one
/// pass (lo/hi: the limiter's bounds, or null).
template <class Pass>
void combinePasses(const std::vector<double>& q, double dt, AdvectionScheme scheme,
                   std::vector<double>& out, AdvectionScratch& scratch, const Pass& pass) {
    if (scheme == AdvectionScheme::SemiLagrangian) {
        pass(q, dt, out, nullptr, nullptr, PassRole::Only);
        return;
    }
    std::vector<double>&fwd = scratch.forward, &back = scratch.backward, &lo = scratch.low,
    &hi = scratch.high, &corrected = scratch.corrected;
    pass(q, dt, fwd, &lo, &hi, PassRole::First);
    pass(fwd, -dt, back, nullptr, nullptr, PassRole::Later);
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
    corrected.resize(q.size());
    tbb::parallel_for(size_t(0), q.size(),
                      [&](size_t idx) { corrected[idx] = q[idx] + 0.5 * (q[idx] - back[idx]); });
    pass(corrected, dt, out, nullptr, nullptr, PassRole::Later);
    tbb::parallel_for(size_t(0), q.size(), [&](size_t idx) {
        const double v = out[idx];
        out[idx] = std::isfinite(v) ? std::clamp(v, lo[idx], hi[idx]) : fwd[idx];
    });
}

/// advect() after its argument checks, through one lattice, in double.
template <class Lattice>
void advectWith(const MacGrid& g, Placement p, const std::vector<double>& q, const MacVelocity& vel,
                const FarField& far, const OutsideValue& outside, double dt, AdvectionScheme scheme,
                std::vector<double>& out, const std::vector<uint8_t>* mask,
                AdvectionScratch& scratch) {
    const double groundTop = g.terrainTop_m();
    // Every pass starts its traces from the same samples through the same frozen velocity: the
    // first pass computes each sample's start and keeps it for the others. Default-initialised
    // (not zeroed): a masked-out sample's entry is never written nor read.
    std::unique_ptr<TraceStart[]> starts;
    if (scheme != AdvectionScheme::SemiLagrangian) starts.reset(new TraceStart[q.size()]);
    combinePasses(q, dt, scheme, out, scratch,
                  [&](const std::vector<double>& a, double t, std::vector<double>& b,
                      std::vector<double>* lo, std::vector<double>* hi, PassRole role) {
                      semiLagrangian<Lattice>(g, p, a, vel, far, outside, t, b, mask, lo, hi,
                                              role == PassRole::Later ? starts.get() : nullptr,
                                              role == PassRole::First ? starts.get() : nullptr,
                                              groundTop);
                  });
}

/// advect() on cubic cells in single precision (AdvectionPrecision::Single): each pass runs the
/// row kernel over every x row, then the general double path over the samples it flagged.
void advectSingle(const MacGrid& g, Placement p, const std::vector<double>& q,
                  const MacVelocity& vel, const FarField& far, const OutsideValue& outside,
                  double dt, AdvectionScheme scheme, std::vector<double>& out,
                  const std::vector<uint8_t>* mask, AdvectionScratch& scratch) {
    const double groundTop = g.terrainTop_m();
    std::vector<float> uf, vf, wf;
    if (!vel.uSingle) {
        detail::roundToFloat(*vel.u, uf);
        detail::roundToFloat(*vel.v, vf);
        detail::roundToFloat(*vel.w, wf);
    }
    std::vector<uint8_t> all;
    if (!mask) all.assign(q.size(), 1);
    const double h = g.voxelSize_m;
    detail::RowPassInput in;
    in.n[0] = g.nx, in.n[1] = g.ny, in.n[2] = g.nz;
    in.placement = int(p);
    in.u = vel.uSingle ? vel.uSingle->data() : uf.data();
    in.v = vel.vSingle ? vel.vSingle->data() : vf.data();
    in.w = vel.wSingle ? vel.wSingle->data() : wf.data();
    in.mask = mask ? mask->data() : all.data();
    if (g.terrain) {
        const Heightfield& T = *g.terrain;
        in.heights = T.height_m.data();
        in.hnx = T.nx, in.hny = T.ny;
        in.hScale = float(h / T.spacing_m);
        in.hOffsetX = float((g.wsMin_m[0] - T.originX_m) / T.spacing_m);
        in.hOffsetY = float((g.wsMin_m[1] - T.originY_m) / T.spacing_m);
        in.zScale = float(1.0 / h);
        in.zOffset = float(-g.wsMin_m[2] / h);
        in.groundTop = float((groundTop - g.wsMin_m[2]) / h);
    }
    const auto d = g.dims(p);
    // The row pass writes every entry of `general` and of `starts` that is read, and each pass
    // rounds its quantity into qf whole.
    std::vector<float>&qf = scratch.quantity, &starts = scratch.starts;
    std::vector<uint8_t>& general = scratch.general;
    general.resize(q.size());
    // The velocity at the samples, kept by the first of several passes for the others.
    if (scheme != AdvectionScheme::SemiLagrangian)
        starts.resize(3 * q.size() + detail::ROW_PASS_PADDING);
    combinePasses(q, dt, scheme, out, scratch,
                  [&](const std::vector<double>& a, double t, std::vector<double>& b,
                      std::vector<double>* lo, std::vector<double>* hi, PassRole role) {
                      b.resize(a.size());
                      if (lo) lo->resize(a.size()), hi->resize(a.size());
                      detail::roundToFloat(a, qf);
                      detail::RowPassInput pass = in;
                      pass.q = qf.data();
                      pass.qExact = a.data();
                      pass.cellsPerMps = float(t / h);
                      pass.count = a.size();
                      if (role == PassRole::First) pass.recordStart = starts.data();
                      if (role == PassRole::Later) pass.start = starts.data();
                      tbb::parallel_for(0, d[2], [&](int k) {
                          for (int j = 0; j < d[1]; ++j)
                              detail::rowPass(pass, j, k, b.data(), lo ? lo->data() : nullptr,
                                              hi ? hi->data() : nullptr, general.data());
                      });
                      semiLagrangian<CubicLattice>(g, p, a, vel, far, outside, t, b, mask, lo, hi,
                                                   nullptr, nullptr, groundTop, general.data());
                  });
}

template <class Lattice>
Vec3d traceBackWith(const MacGrid& g, const MacVelocity& vel, const FarField& far, const Vec3d& ws,
                    double dt) {
    const FaceVelocitySampler<Lattice> velocityWs(g, vel, far);
    Vec3d dep;
    const double groundTop = g.terrainTop_m();
    traceWs(g, velocityWs, ws.data(), traceStart(g, velocityWs, ws.data(), groundTop), dt,
            groundTop, dep.data());
    return dep;
}

}  // namespace

Vec3d traceBack(const MacGrid& g, const MacVelocity& vel, const FarField& far, const Vec3d& ws,
                double dt) {
    return UniformLattice::usable(g) ? traceBackWith<CubicLattice>(g, vel, far, ws, dt)
                                     : traceBackWith<LayoutLattice>(g, vel, far, ws, dt);
}

void advect(const MacGrid& g, Placement p, const std::vector<double>& q, const MacVelocity& vel,
            const FarField& far, const OutsideValue& outside, double dt, AdvectionScheme scheme,
            std::vector<double>& out, const std::vector<uint8_t>* mask,
            AdvectionPrecision precision, AdvectionScratch* scratch) {
    if (q.size() != g.count(p)) throw std::logic_error("advect: quantity has the wrong size");
    if (!vel.u || !vel.v || !vel.w || vel.u->size() != g.count(Placement::FaceX) ||
        vel.v->size() != g.count(Placement::FaceY) || vel.w->size() != g.count(Placement::FaceZ))
        throw std::logic_error("advect: velocity arrays have the wrong size");
    if (mask && mask->size() != q.size()) throw std::logic_error("advect: mask has the wrong size");
    if (vel.uSingle &&
        (!vel.vSingle || !vel.wSingle || vel.uSingle->size() != vel.u->size() ||
         vel.vSingle->size() != vel.v->size() || vel.wSingle->size() != vel.w->size()))
        throw std::logic_error("advect: single-precision velocity arrays have the wrong size");
    // Cubic cells (the live scenes) take the fast lattice, in float if asked; stretched layers
    // the layout's sampler.
    AdvectionScratch own;
    AdvectionScratch& work = scratch ? *scratch : own;
    if (UniformLattice::usable(g) && precision == AdvectionPrecision::Single)
        advectSingle(g, p, q, vel, far, outside, dt, scheme, out, mask, work);
    else if (UniformLattice::usable(g))
        advectWith<CubicLattice>(g, p, q, vel, far, outside, dt, scheme, out, mask, work);
    else
        advectWith<LayoutLattice>(g, p, q, vel, far, outside, dt, scheme, out, mask, work);
}

}  // namespace gale::sim

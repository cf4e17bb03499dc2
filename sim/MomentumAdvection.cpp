/// \file MomentumAdvection.cpp
/// Explicit Eulerian advection of MAC face velocities, upwind with van Leer limited slopes
/// (van Leer 1979; Sweby 1984), for the momentum model's pseudo-time step.
#include "sim/MomentumAdvection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gale::sim {
namespace {

/// van Leer's limited slope from the two one-sided slopes s1, s2 (per metre): their harmonic
/// mean 2 s1 s2 / (s1 + s2) when they have the same sign, else 0 (an extremum: first order).
/// Its magnitude never exceeds twice the smaller slope's.
double vanLeerSlope(double s1, double s2) {
    const double prod = s1 * s2;
    return prod > 0.0 ? 2.0 * prod / (s1 + s2) : 0.0;
}

/// dq/dt at sample 2 of four samples q[0..3] at increasing positions t[0..3] (t grows
/// downstream: sample 1 is upwind, 3 downwind): the difference of the interface values at the
/// midpoints (t1 + t2) / 2 and (t2 + t3) / 2, each reconstructed from its upwind sample with the
/// limited slope, over the interfaces' distance.
double upwindDerivative(const double q[4], const double t[4]) {
    const double sA = (q[1] - q[0]) / (t[1] - t[0]);
    const double sB = (q[2] - q[1]) / (t[2] - t[1]);
    const double sC = (q[3] - q[2]) / (t[3] - t[2]);
    const double fUp = 0.5 * (t[1] + t[2]), fDown = 0.5 * (t[2] + t[3]);
    const double qUp = q[1] + vanLeerSlope(sA, sB) * (fUp - t[1]);
    const double qDown = q[2] + vanLeerSlope(sB, sC) * (fDown - t[2]);
    return (qDown - qUp) / (fDown - fUp);
}

/// Reads a placement's samples and the frozen velocity around them.
struct Stencil {
    const MacGrid& g;
    Placement p;
    std::array<int, 3> n;  // samples of p along each axis
    const MacVelocity& vel;

    /// World height of sample k of p along z (extended linearly beyond the samples with the
    /// end spacing).
    double zPosition(int k) const {
        auto at = [&](int kk) { return p == Placement::FaceZ ? g.zFace_m(kk) : g.zCentre_m(kk); };
        const int last = n[2] - 1;
        if (k >= 0 && k <= last) return at(k);
        const double lo = last > 0 ? at(1) - at(0) : g.dz_m(0);
        const double hi = last > 0 ? at(last) - at(last - 1) : g.dz_m(g.nz - 1);
        return k < 0 ? at(0) + k * lo : at(last) + (k - last) * hi;
    }

    /// The frozen velocity at sample (i, j, k) of p (see the header: own component at the face,
    /// the others averaged from their four nearest faces).
    Vec3d velocityAt(int i, int j, int k) const {
        const std::vector<double>&U = *vel.u, &V = *vel.v, &W = *vel.w;
        const int nx = g.nx, ny = g.ny, nz = g.nz;
        auto cx = [&](int a) { return std::clamp(a, 0, nx - 1); };
        auto cy = [&](int a) { return std::clamp(a, 0, ny - 1); };
        auto cz = [&](int a) { return std::clamp(a, 0, nz - 1); };
        auto u = [&](int a, int b, int c) { return U[g.faceXIndex(a, b, c)]; };
        auto v = [&](int a, int b, int c) { return V[g.faceYIndex(a, b, c)]; };
        auto w = [&](int a, int b, int c) { return W[g.faceZIndex(a, b, c)]; };
        if (p == Placement::FaceX) {
            const int a = cx(i - 1), b = cx(i);
            return {u(i, j, k), 0.25 * (v(a, j, k) + v(b, j, k) + v(a, j + 1, k) + v(b, j + 1, k)),
                    0.25 * (w(a, j, k) + w(b, j, k) + w(a, j, k + 1) + w(b, j, k + 1))};
        }
        if (p == Placement::FaceY) {
            const int a = cy(j - 1), b = cy(j);
            return {0.25 * (u(i, a, k) + u(i + 1, a, k) + u(i, b, k) + u(i + 1, b, k)), v(i, j, k),
                    0.25 * (w(i, a, k) + w(i, b, k) + w(i, a, k + 1) + w(i, b, k + 1))};
        }
        // FaceZ at level k: the layers below and above weighted by the other's thickness
        // (linear interpolation between their centres).
        const int lo = cz(k - 1), hi = cz(k);
        const double dLo = g.dz_m(lo), dHi = g.dz_m(hi);
        const double wLo = lo == hi ? 0.5 : dHi / (dLo + dHi), wHi = 1.0 - wLo;
        return {
            0.5 * (wLo * (u(i, j, lo) + u(i + 1, j, lo)) + wHi * (u(i, j, hi) + u(i + 1, j, hi))),
            0.5 * (wLo * (v(i, j, lo) + v(i, j + 1, lo)) + wHi * (v(i, j, hi) + v(i, j + 1, hi))),
            w(i, j, k)};
    }
};

void checkSizes(const MacGrid& g, const MacVelocity& vel) {
    if (!vel.u || !vel.v || !vel.w || vel.u->size() != g.count(Placement::FaceX) ||
        vel.v->size() != g.count(Placement::FaceY) || vel.w->size() != g.count(Placement::FaceZ))
        throw std::logic_error("Eulerian advection: the velocity arrays do not match the grid");
}

/// Distance between the interfaces around sample m along z (half the span of its neighbours).
double zSpan(const Stencil& s, int k) { return 0.5 * (s.zPosition(k + 1) - s.zPosition(k - 1)); }

}  // namespace

double eulerianRate_ps(const MacGrid& g, const MacVelocity& vel,
                       const std::array<const std::vector<uint8_t>*, 3>& masks) {
    checkSizes(g, vel);
    double rate = 0.0;
    for (int c = 0; c < 3; ++c) {
        const Placement p = Placement(c);
        const Stencil s{g, p, g.dims(p), vel};
        const std::vector<uint8_t>* mask = masks[size_t(c)];
        for (int k = 0; k < s.n[2]; ++k) {
            const double dz = zSpan(s, k);
            for (int j = 0; j < s.n[1]; ++j)
                for (int i = 0; i < s.n[0]; ++i) {
                    if (mask && !(*mask)[g.index(p, i, j, k)]) continue;
                    const Vec3d a = s.velocityAt(i, j, k);
                    const double r =
                        (std::abs(a[0]) + std::abs(a[1])) / g.voxelSize_m + std::abs(a[2]) / dz;
                    if (!(r <= rate)) rate = r;  // NaN sticks
                }
        }
    }
    return rate;
}

double advectEulerian(const MacGrid& g, Placement p, const std::vector<double>& q,
                      const MacVelocity& vel, const OutsideValue& outside, double dt_s,
                      std::vector<double>& out, const std::vector<uint8_t>* mask) {
    checkSizes(g, vel);
    if (p == Placement::Cell || q.size() != g.count(p) || (mask && mask->size() != q.size()))
        throw std::logic_error("advectEulerian: a face placement and arrays of its size");
    out.resize(q.size());
    const Stencil s{g, p, g.dims(p), vel};
    const double h = g.voxelSize_m;
    // Value of sample (i, j, k) + o e_d, with its position along d (metres, relative along x and
    // y). Outside the box through x, y or the top: `outside` at the extended position; below the
    // bottom: the lowest sample.
    auto sample = [&](int i, int j, int k, int d, int o, double& t) {
        int idx[3] = {i, j, k};
        idx[d] += o;
        t = d == 2 ? s.zPosition(idx[2]) : idx[d] * h;
        const bool in = idx[d] >= 0 && idx[d] < s.n[size_t(d)];
        if (in) return q[g.index(p, idx[0], idx[1], idx[2])];
        if (d == 2 && idx[2] < 0) return q[g.index(p, i, j, 0)];
        if (outside) {
            Vec3d ws = g.wsPosition(p, i, j, k);
            ws[size_t(d)] = d == 2 ? t : ws[size_t(d)] + o * h;
            return outside(ws);
        }
        idx[d] = std::clamp(idx[d], 0, s.n[size_t(d)] - 1);
        return q[g.index(p, idx[0], idx[1], idx[2])];
    };
    std::vector<double> kRate(size_t(s.n[2]), 0.0);
    tbb::parallel_for(0, s.n[2], [&](int k) {
        double rate = 0.0;
        const double dz = zSpan(s, k);
        for (int j = 0; j < s.n[1]; ++j)
            for (int i = 0; i < s.n[0]; ++i) {
                const size_t f = g.index(p, i, j, k);
                if (mask && !(*mask)[f]) {
                    out[f] = q[f];
                    continue;
                }
                const Vec3d a = s.velocityAt(i, j, k);
                double conv = 0.0;
                for (int d = 0; d < 3; ++d) {
                    const double ad = a[size_t(d)];
                    if (ad == 0.0) continue;
                    const int up = ad > 0.0 ? 1 : -1;  // t grows downstream: t = up * x
                    double qs[4], ts[4];
                    for (int m = 0; m < 4; ++m) {
                        qs[m] = sample(i, j, k, d, up * (m - 2), ts[m]);
                        ts[m] *= up;
                    }
                    conv += std::abs(ad) * upwindDerivative(qs, ts);
                }
                out[f] = q[f] - dt_s * conv;
                const double r =
                    dt_s * ((std::abs(a[0]) + std::abs(a[1])) / h + std::abs(a[2]) / dz);
                if (!(r <= rate)) rate = r;
            }
        kRate[size_t(k)] = rate;
    });
    double rate = 0.0;
    for (double r : kRate)
        if (!(r <= rate)) rate = r;
    return rate;
}

}  // namespace gale::sim

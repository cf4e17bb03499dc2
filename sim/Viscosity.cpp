/// \file Viscosity.cpp
/// Backward-Euler viscosity by Jacobi-preconditioned CG, per MAC component, in the finite-volume
/// flux form of Patankar 1980 on stretched layers.
#include "sim/Viscosity.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gale::sim {
namespace {

/// Grain of the element-wise loops and reductions: large enough that a task outweighs its
/// scheduling, small enough that a 64 x 64 x 24 component splits over the cores.
constexpr size_t GRAIN = 4096;

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, a.size(), GRAIN), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double s) {
            for (size_t i = r.begin(); i != r.end(); ++i) s += a[i] * b[i];
            return s;
        },
        std::plus<double>());
}

/// Runs body(i) for every i in [0, n) on TBB's threads.
template <class Body>
void forEach(size_t n, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, GRAIN),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
}

/// The backward-Euler operator of one component in flux form, divided by h^3 (Viscosity.h).
/// Level k of the component's samples has control-volume height e_k and lies at distance d_k
/// from level k + 1; mass[k] = e_k / h, horizontal conductance a e_k / h, vertical conductance
/// up[k] = a h / d_k, with a = nu dt / h^2. All 1, a and a on cubic cells.
struct Operator {
    GridIndex grid;
    Placement p;
    std::array<int, 3> n;  // grid.dims(p)
    const std::vector<uint8_t>* mask;
    double a;                        // nu dt / h^2
    std::vector<double> mass, side;  // per level: e_k / h and a e_k / h
    std::vector<double> up;          // per level: a h / d_k towards level k + 1

    Operator(const GridLayout& g, Placement placement, const std::vector<uint8_t>* m,
             double nuDtOverH2)
        : grid(g), p(placement), n(g.dims(placement)), mask(m), a(nuDtOverH2) {
        const double h = g.voxelSize_m;
        const size_t levels = size_t(n[2]);
        mass.resize(levels), side.resize(levels), up.assign(levels, 0.0);
        for (int k = 0; k < n[2]; ++k) {
            // z-faces sit on the level heights, their volumes span centre to centre; every other
            // placement sits at layer centres and spans its layer.
            const bool onFace = p == Placement::FaceZ;
            const double e = onFace ? g.centreGap_m(k) : g.dz_m(k);
            mass[size_t(k)] = e / h, side[size_t(k)] = a * e / h;
            if (k + 1 < n[2]) up[size_t(k)] = a * h / (onFace ? g.dz_m(k) : g.centreGap_m(k + 1));
        }
    }
    size_t idx(int i, int j, int k) const { return grid.index(p, i, j, k); }
    // out = (M + a K) x on masked samples (0 elsewhere); diag receives its diagonal.
    void apply(const std::vector<double>& x, std::vector<double>& out,
               std::vector<double>* diag) const {
        tbb::parallel_for(0, n[2], [&](int k) {
            const double m = mass[size_t(k)], cs = side[size_t(k)];
            const double cDown = k > 0 ? up[size_t(k) - 1] : 0.0, cUp = up[size_t(k)];
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const size_t c = idx(i, j, k);
                    if (!(*mask)[c]) {
                        out[c] = 0.0;
                        if (diag) (*diag)[c] = 1.0;
                        continue;
                    }
                    double s = 0.0, d = m;
                    auto nb = [&](int ii, int jj, int kk, double conductance) {
                        if (ii < 0 || jj < 0 || kk < 0 || ii >= n[0] || jj >= n[1] || kk >= n[2])
                            return;
                        const size_t q = idx(ii, jj, kk);
                        if (!(*mask)[q]) return;
                        s += conductance * (x[c] - x[q]), d += conductance;
                    };
                    nb(i - 1, j, k, cs), nb(i + 1, j, k, cs), nb(i, j - 1, k, cs),
                        nb(i, j + 1, k, cs), nb(i, j, k - 1, cDown), nb(i, j, k + 1, cUp);
                    out[c] = m * x[c] + s;
                    if (diag) (*diag)[c] = d;
                }
        });
    }
};

}  // namespace

ViscosityReport diffuseImplicit(const MacGrid& g, double nu, double dt,
                                const std::array<const std::vector<uint8_t>*, 3>& masks,
                                std::vector<double>& u, std::vector<double>& v,
                                std::vector<double>& w, double tol, int maxIterations) {
    if (!(nu >= 0.0) || !(dt >= 0.0))
        throw std::logic_error("diffuseImplicit: nu and dt must be >= 0, got nu = " +
                               std::to_string(nu) + " m^2/s, dt = " + std::to_string(dt) + " s");
    ViscosityReport rep;
    const double a = nu * dt / (g.voxelSize_m * g.voxelSize_m);
    if (a == 0.0) return rep;
    std::vector<double>* comps[3] = {&u, &v, &w};
    for (int c = 0; c < 3; ++c) {
        const Placement p = Placement(c);
        std::vector<double>& x = *comps[c];
        if (!masks[c] || masks[c]->size() != x.size())
            throw std::logic_error("diffuseImplicit: bad mask");
        const Operator op(g, p, masks[c], a);
        std::vector<double> b(x.size()), r(x.size()), z(x.size()), q(x.size()), Ap(x.size()),
            diag(x.size());
        const std::vector<uint8_t>& mask = *masks[c];
        tbb::parallel_for(0, op.n[2], [&](int k) {
            for (size_t i = op.idx(0, 0, k); i < op.idx(0, 0, k + 1); ++i)
                b[i] = mask[i] ? op.mass[size_t(k)] * x[i] : 0.0;
        });
        op.apply(x, Ap, &diag);
        forEach(x.size(), [&](size_t i) { r[i] = mask[i] ? b[i] - Ap[i] : 0.0; });
        const double bnorm = std::sqrt(dot(b, b));
        if (bnorm == 0.0) continue;
        forEach(x.size(), [&](size_t i) { z[i] = r[i] / diag[i]; });
        q = z;
        double rz = dot(r, z);
        int it = 0;
        double rel = std::sqrt(dot(r, r)) / bnorm;
        while (rel > tol && it < maxIterations) {
            op.apply(q, Ap, nullptr);
            const double qAq = dot(q, Ap);
            if (!(qAq > 0.0)) break;
            const double alpha = rz / qAq;
            forEach(x.size(), [&](size_t i) {
                if (mask[i]) x[i] += alpha * q[i], r[i] -= alpha * Ap[i];
                z[i] = r[i] / diag[i];
            });
            const double rzNew = dot(r, z);
            const double beta = rzNew / rz;
            rz = rzNew;
            forEach(x.size(), [&](size_t i) { q[i] = z[i] + beta * q[i]; });
            rel = std::sqrt(dot(r, r)) / bnorm;
            ++it;
        }
        rep.iterations = std::max(rep.iterations, it);
        rep.relativeResidual = std::max(rep.relativeResidual, rel);
        if (rel > tol) rep.converged = false;
    }
    return rep;
}

}  // namespace gale::sim

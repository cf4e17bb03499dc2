/// \file Viscosity.cpp
/// Backward-Euler viscosity by Jacobi-preconditioned CG, per MAC component.
#include "sim/Viscosity.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gale::sim {
namespace {

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, a.size(), 4096), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double s) {
            for (size_t i = r.begin(); i != r.end(); ++i) s += a[i] * b[i];
            return s;
        },
        std::plus<double>());
}

struct Operator {
    GridIndex grid;
    Placement p;
    std::array<int, 3> n;  // grid.dims(p)
    const std::vector<uint8_t>* mask;
    double a;  // nu dt / h^2
    size_t idx(int i, int j, int k) const { return grid.index(p, i, j, k); }
    // out = (I + a K) x on masked samples (0 elsewhere); diag receives 1 + a * neighbours.
    void apply(const std::vector<double>& x, std::vector<double>& out,
               std::vector<double>* diag) const {
        tbb::parallel_for(0, n[2], [&](int k) {
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const size_t c = idx(i, j, k);
                    if (!(*mask)[c]) {
                        out[c] = 0.0;
                        if (diag) (*diag)[c] = 1.0;
                        continue;
                    }
                    double s = 0.0;
                    int cnt = 0;
                    auto nb = [&](int ii, int jj, int kk) {
                        if (ii < 0 || jj < 0 || kk < 0 || ii >= n[0] || jj >= n[1] || kk >= n[2])
                            return;
                        const size_t q = idx(ii, jj, kk);
                        if (!(*mask)[q]) return;
                        s += x[q], ++cnt;
                    };
                    nb(i - 1, j, k), nb(i + 1, j, k), nb(i, j - 1, k), nb(i, j + 1, k),
                        nb(i, j, k - 1), nb(i, j, k + 1);
                    out[c] = x[c] + a * (cnt * x[c] - s);
                    if (diag) (*diag)[c] = 1.0 + a * cnt;
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
        throw std::invalid_argument("diffuseImplicit: nu and dt must be >= 0");
    ViscosityReport rep;
    const double a = nu * dt / (g.voxelSize_m * g.voxelSize_m);
    if (a == 0.0) return rep;
    std::vector<double>* comps[3] = {&u, &v, &w};
    for (int c = 0; c < 3; ++c) {
        const Placement p = Placement(c);
        std::vector<double>& x = *comps[c];
        if (!masks[c] || masks[c]->size() != x.size())
            throw std::invalid_argument("diffuseImplicit: bad mask");
        const Operator op{g, p, g.dims(p), masks[c], a};
        std::vector<double> b(x.size()), r(x.size()), z(x.size()), q(x.size()), Ap(x.size()),
            diag(x.size());
        for (size_t i = 0; i < x.size(); ++i) b[i] = (*masks[c])[i] ? x[i] : 0.0;
        op.apply(x, Ap, &diag);
        for (size_t i = 0; i < x.size(); ++i) r[i] = (*masks[c])[i] ? b[i] - Ap[i] : 0.0;
        const double bnorm = std::sqrt(dot(b, b));
        if (bnorm == 0.0) continue;
        for (size_t i = 0; i < x.size(); ++i) z[i] = r[i] / diag[i];
        q = z;
        double rz = dot(r, z);
        int it = 0;
        double rel = std::sqrt(dot(r, r)) / bnorm;
        while (rel > tol && it < maxIterations) {
            op.apply(q, Ap, nullptr);
            const double qAq = dot(q, Ap);
            if (!(qAq > 0.0)) break;
            const double alpha = rz / qAq;
            for (size_t i = 0; i < x.size(); ++i)
                if ((*masks[c])[i]) x[i] += alpha * q[i], r[i] -= alpha * Ap[i];
            for (size_t i = 0; i < x.size(); ++i) z[i] = r[i] / diag[i];
            const double rzNew = dot(r, z);
            const double beta = rzNew / rz;
            rz = rzNew;
            for (size_t i = 0; i < x.size(); ++i) q[i] = z[i] + beta * q[i];
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

/// \file SteadyWind.cpp
/// Assembly of Sherman's (1978) mass-consistent problem on cut cells, and the velocity update.
#include "sim/SteadyWind.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "base/ParameterError.h"
#include "sim/FaceExtrapolation.h"
#include "sim/Format.h"

namespace gale::sim {
namespace {

using detail::num;

double checkedRatio(const MassConsistentWeights& w) {
    if (!(w.alphaH > 0.0) || !std::isfinite(w.alphaH))
        throw ParameterError("solver.alpha_h", num(w.alphaH), "must be > 0 and finite");
    if (!(w.alphaV > 0.0) || !std::isfinite(w.alphaV))
        throw ParameterError("solver.alpha_v", num(w.alphaV), "must be > 0 and finite");
    const double r = (w.alphaH / w.alphaV) * (w.alphaH / w.alphaV);
    constexpr double ROUNDING = 1e-9;  // (sqrt(10))^2 must pass as 10
    if (r < SteadyWindSolver::MIN_VERTICAL_RATIO * (1 - ROUNDING) ||
        r > SteadyWindSolver::MAX_VERTICAL_RATIO * (1 + ROUNDING))
        throw ParameterError("solver.alpha_v", num(w.alphaV),
                             "must give (alpha_h / alpha_v)^2 in [" +
                                 num(SteadyWindSolver::MIN_VERTICAL_RATIO) + ", " +
                                 num(SteadyWindSolver::MAX_VERTICAL_RATIO) +
                                 "] (alpha_h = " + num(w.alphaH) + ", ratio " + num(r) + ")");
    return r;
}

}  // namespace

PoissonSystem SteadyWindSolver::makeSystem(const AirDomain& d, double r) {
    PoissonSystem s;
    s.nx = d.nx(), s.ny = d.ny(), s.nz = d.nz();
    s.sides = {BoundaryKind::Dirichlet, BoundaryKind::Dirichlet, BoundaryKind::Dirichlet,
               BoundaryKind::Dirichlet, BoundaryKind::Neumann,   BoundaryKind::Dirichlet};
    if (d.closedSidesY()) s.sides[SIDE_YMIN] = s.sides[SIDE_YMAX] = BoundaryKind::Neumann;
    s.weightX = d.openFractionsX();
    s.weightY = d.openFractionsY();
    s.weightZ = d.openFractionsZ();
    const GridLayout& g = d.layout();
    if (!g.uniformZ()) {
        s.zLineSmoothing = true;  // thin layers: point smoothing stalls (PoissonLineSmoothing.cpp)
        // Finite volumes on stretched layers, divided by h: a side face conducts
        // theta (h dz_k) / h / h = theta dz_k / h, a z-face theta h^2 / d_k / h = theta h / d_k
        // with d_k the distance between the centres it separates (the top face: dz of the last
        // layer, the solver doubles boundary weights for the half distance).
        const double h = g.voxelSize_m;
        for (int k = 0; k < g.nz; ++k) {
            const float side = float(g.dz_m(k) / h);
            for (size_t f = g.faceXIndex(0, 0, k); f < g.faceXIndex(0, 0, k + 1); ++f)
                s.weightX[f] *= side;
            for (size_t f = g.faceYIndex(0, 0, k); f < g.faceYIndex(0, 0, k + 1); ++f)
                s.weightY[f] *= side;
        }
        for (int k = 0; k <= g.nz; ++k) {
            const float up = float(h / g.centreGap_m(k));
            for (size_t f = g.faceZIndex(0, 0, k); f < g.faceZIndex(0, 0, k + 1); ++f)
                s.weightZ[f] *= up;
        }
    }
    if (r != 1.0)
        for (float& w : s.weightZ) w = float(w * r);
    return s;
}

SteadyWindSolver::SteadyWindSolver(const AirDomain& domain, const MassConsistentWeights& weights)
    : mDomain(domain),
      mRatio(checkedRatio(weights)),
      mSystem(makeSystem(domain, mRatio)),
      mPoisson(mSystem) {}

void SteadyWindSolver::setWarmStart(std::vector<double> potential) {
    if (!potential.empty() && potential.size() != mSystem.cellCount())
        throw std::logic_error("SteadyWindSolver::setWarmStart: potential must have " +
                               std::to_string(mSystem.cellCount()) + " entries, got " +
                               std::to_string(potential.size()));
    mPotential = std::move(potential);
}

SteadyWindResult SteadyWindSolver::solve(const AmbientWind& ambient, const SolverSettings& settings,
                                         const BoundaryPotential& boundary) {
    ambient.validate();
    const auto t0 = std::chrono::steady_clock::now();
    const AirDomain& D = mDomain;
    const PoissonSystem& S = mSystem;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const double h = D.voxelSize_m(), r = mRatio;
    const auto o = D.wsMin_m();
    const bool closedY = D.closedSidesY();  // free-slip y sides: no flux, no potential
    const Heightfield& T = D.terrain();

    const GridLayout& G = D.layout();
    SteadyWindResult res;
    res.field = WindField(G, D.terrainShared(), D.airFlags());
    const std::vector<float>&thX = D.openFractionsX(), &thY = D.openFractionsY(),
          &thZ = D.openFractionsZ();
    std::vector<double>& U = res.field.u_mps();
    std::vector<double>& V = res.field.v_mps();
    std::vector<double>& W = res.field.w_mps();

    // --- first guess on faces: the profile at the height above the local ground of the centroid
    //     of the face's open part (vertical faces: the open part spans its top theta*h).
    const bool uniform = ambient.profile == WindProfile::Uniform;
    const auto dir = ambient.velocityAt_mps(ambient.referenceHeight_m);
    const double sref = ambient.speed_mps > 0 ? ambient.speed_mps : 1.0;
    const double ex = dir[0] / sref, ey = dir[1] / sref;  // unit direction (times speed/sref)
    auto speedAt = [&](double x, double y, double zTop, double dz, double theta) {
        if (uniform) return ambient.speed_mps;
        const double zc = zTop - 0.5 * std::max(double(theta), 1e-3) * dz;
        return ambient.speedAt_mps(zc - T.sample(x, y));
    };
    tbb::parallel_for(0, nz, [&](int k) {
        const double dz = G.dz_m(k), zTop = G.zFace_m(k) + dz;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const size_t f = S.faceXIndex(i, j, k);
                U[f] = ex * speedAt(o[0] + i * h, o[1] + (j + 0.5) * h, zTop, dz, thX[f]);
            }
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t f = S.faceYIndex(i, j, k);
                V[f] = closedY && (j == 0 || j == ny)
                           ? 0.0
                           : ey * speedAt(o[0] + (i + 0.5) * h, o[1] + j * h, zTop, dz, thY[f]);
            }
    });
    // W stays 0: the ambient wind is horizontal.

    // --- right-hand side: h * outward open flux of u0, plus Dirichlet data on the open sides.
    // Boundary weights carry the factor 2 of a face half a cell from the centre; on stretched
    // layers side faces conduct dz_k / h and the top dz_top / h times as much as cubic ones.
    auto g = [&](double x, double y, double z) { return boundary ? boundary(x, y, z) : 0.0; };
    std::vector<double> rhs(S.cellCount(), 0.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k)) continue;
                const size_t xm = S.faceXIndex(i, j, k), xp = S.faceXIndex(i + 1, j, k);
                const size_t ym = S.faceYIndex(i, j, k), yp = S.faceYIndex(i, j + 1, k);
                const size_t zp = S.faceZIndex(i, j, k + 1);
                double b = h * D.openOutflux(U, V, W, i, j, k);
                if (boundary) {
                    const double xc = o[0] + (i + 0.5) * h, yc = o[1] + (j + 0.5) * h,
                                 zc = G.zCentre_m(k), side = G.dz_m(k) / h;
                    if (i == 0) b += 2.0 * side * thX[xm] * g(o[0], yc, zc);
                    if (i == nx - 1) b += 2.0 * side * thX[xp] * g(o[0] + nx * h, yc, zc);
                    if (j == 0 && !closedY) b += 2.0 * side * thY[ym] * g(xc, o[1], zc);
                    if (j == ny - 1 && !closedY)
                        b += 2.0 * side * thY[yp] * g(xc, o[1] + ny * h, zc);
                    if (k == nz - 1)
                        b += 2.0 * r * (h / G.dz_m(k)) * thZ[zp] * g(xc, yc, G.wsTop_m());
                }
                rhs[S.cellIndex(i, j, k)] = b;
            }
    });
    const double tAssemble =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // --- solve -----------------------------------------------------------------------------
    res.report =
        mSolve ? mSolve(rhs, mPotential, settings) : mPoisson.solve(rhs, mPotential, settings);
    const auto t1 = std::chrono::steady_clock::now();

    // --- velocity update: u = u0 + (d/dx psi, d/dy psi, r d/dz psi) on every face whose
    //     neighbouring cells are air (open or not); boundary faces use the Dirichlet data.
    const std::vector<double>& psi = mPotential;
    std::vector<uint8_t> okX(U.size(), 0), okY(V.size(), 0), okZ(W.size(), 0);
    auto P = [&](int i, int j, int k) { return psi[S.cellIndex(i, j, k)]; };
    auto air = [&](int i, int j, int k) { return D.isAir(i, j, k); };
    tbb::parallel_for(0, nz, [&](int k) {
        const double zc = G.zCentre_m(k);
        for (int j = 0; j < ny; ++j) {
            const double yc = o[1] + (j + 0.5) * h;
            for (int i = 0; i <= nx; ++i) {
                const size_t f = S.faceXIndex(i, j, k);
                if (i > 0 && i < nx && air(i - 1, j, k) && air(i, j, k)) {
                    U[f] += (P(i, j, k) - P(i - 1, j, k)) / h, okX[f] = 1;
                } else if (i == 0 && air(0, j, k)) {
                    U[f] += 2.0 * (P(0, j, k) - g(o[0], yc, zc)) / h, okX[f] = 1;
                } else if (i == nx && air(nx - 1, j, k)) {
                    U[f] += 2.0 * (g(o[0] + nx * h, yc, zc) - P(nx - 1, j, k)) / h, okX[f] = 1;
                }
            }
        }
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const double xc = o[0] + (i + 0.5) * h;
                const size_t f = S.faceYIndex(i, j, k);
                if (j > 0 && j < ny && air(i, j - 1, k) && air(i, j, k)) {
                    V[f] += (P(i, j, k) - P(i, j - 1, k)) / h, okY[f] = 1;
                } else if (j == 0 && air(i, 0, k) && !closedY) {
                    V[f] += 2.0 * (P(i, 0, k) - g(xc, o[1], zc)) / h, okY[f] = 1;
                } else if (j == ny && air(i, ny - 1, k) && !closedY) {
                    V[f] += 2.0 * (g(xc, o[1] + ny * h, zc) - P(i, ny - 1, k)) / h, okY[f] = 1;
                }
            }
    });
    tbb::parallel_for(0, nz + 1, [&](int k) {
        const double gap = G.centreGap_m(k);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t f = S.faceZIndex(i, j, k);
                if (k > 0 && k < nz && air(i, j, k - 1) && air(i, j, k)) {
                    W[f] += r * (P(i, j, k) - P(i, j, k - 1)) / gap, okZ[f] = 1;
                } else if (k == nz && air(i, j, nz - 1)) {
                    const double xc = o[0] + (i + 0.5) * h, yc = o[1] + (j + 0.5) * h;
                    W[f] += 2.0 * r * (g(xc, yc, G.wsTop_m()) - P(i, j, nz - 1)) / gap, okZ[f] = 1;
                }
            }
    });
    detail::extrapolateFaces(U, okX, G, Placement::FaceX, EXTRAPOLATION_LAYERS);
    detail::extrapolateFaces(V, okY, G, Placement::FaceY, EXTRAPOLATION_LAYERS);
    detail::extrapolateFaces(W, okZ, G, Placement::FaceZ, EXTRAPOLATION_LAYERS);

    // --- divergence of the open fluxes, per air cell, scaled by h / U ----------------------
    const double Uref = ambient.speed_mps > 0.0 ? ambient.speed_mps : 1.0;
    double maxDiv = 0.0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!air(i, j, k)) continue;
                maxDiv = std::max(maxDiv, std::abs(D.openOutflux(U, V, W, i, j, k)));
            }
    res.report.maxDivergenceScaled = maxDiv / Uref;
    res.assemblySeconds =
        tAssemble + std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    return res;
}

SteadyWindResult solveSteadyWind(const AirDomain& domain, const AmbientWind& ambient,
                                 const MassConsistentWeights& weights,
                                 const SolverSettings& settings,
                                 const BoundaryPotential& boundary) {
    SteadyWindSolver solver(domain, weights);
    return solver.solve(ambient, settings, boundary);
}

}  // namespace gale::sim

/// \file UnsteadyProjection.cpp
/// The unsteady solver's projection (UnsteadyWind.h, step 5): the right-hand side from the open
/// fluxes and the boundary pressure, the MGPCG solve warm-started from the pressure of the last
/// two steps, the gradient update, the closed faces refilled and the lid closed again.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "sim/FaceExtrapolation.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {

namespace {
/// Layers of closed faces refilled from their neighbours after each projection (as SteadyWind).
constexpr int EXTRAPOLATION_LAYERS = SteadyWindSolver::EXTRAPOLATION_LAYERS;
/// The largest step CFL at which the warm start extrapolates the pressure in time (twice the
/// live wind's CFL of 2); above it the last potential is the start.
constexpr double PRESSURE_EXTRAPOLATION_MAX_CFL = 4.0;
}  // namespace

void UnsteadyWindSolver::extrapolateClosedFaces() {
    if (!mRefill[0]) {  // the masks are set once, in the constructor: so are the refills
        const std::vector<uint8_t>* masks[3] = {&mOkX, &mOkY, &mOkZ};
        for (int c = 0; c < 3; ++c)
            mRefill[size_t(c)] = std::make_shared<const detail::FaceExtrapolation>(
                *masks[c], mGrid, Placement(c), EXTRAPOLATION_LAYERS);
    }
    mRefill[0]->apply(mField.u_mps());
    mRefill[1]->apply(mField.v_mps());
    if (mDomain.closedSidesY())  // free-slip walls: nothing flows through them
        for (int k = 0; k < mGrid.nz; ++k)
            for (int i = 0; i < mGrid.nx; ++i)
                mField.v_mps()[mGrid.faceYIndex(i, 0, k)] =
                    mField.v_mps()[mGrid.faceYIndex(i, mGrid.ny, k)] = 0.0;
    mRefill[2]->apply(mField.w_mps());
}

SolveReport UnsteadyWindSolver::project() { return project(mSettings.projection); }

SolveReport UnsteadyWindSolver::project(const SolverSettings& settings) {
    return project(settings, 0.0, 0.0);
}

SolveReport UnsteadyWindSolver::project(const SolverSettings& settings, double dt, double stepCfl) {
    mFieldRateKnown = false;  // the projection changes the field (a step measures it after)
    const int nx = mGrid.nx, ny = mGrid.ny, nz = mGrid.nz;
    const double h = mGrid.voxelSize_m;
    const auto o = mGrid.wsMin_m;
    const PoissonSystem& S = mSystem;
    std::vector<double>&U = mField.u_mps(), &V = mField.v_mps(), &W = mField.w_mps();
    auto air = [&](int i, int j, int k) { return mDomain.isAir(i, j, k); };
    // The potential on the open boundaries: -dt p / rho of the given pressure, else 0.
    const auto& pressure = mSettings.boundaryPressure_m2ps2;
    const bool data = pressure && dt > 0.0;
    auto g = [&](double x, double y, double z) { return data ? -dt * pressure({x, y, z}) : 0.0; };
    const std::vector<float>&thX = mDomain.openFractionsX(), &thY = mDomain.openFractionsY(),
          &thZ = mDomain.openFractionsZ();
    // Right-hand side: h times the outward open flux plus the boundary data, with the factor 2 of
    // a boundary value half a cell from the centre, as SteadyWind.cpp assembles it.
    std::vector<double>& rhs = mRhs;  // kept between steps: every entry is written below
    rhs.resize(S.cellCount());
    const uint8_t* airFlags = mDomain.airFlags().data();
    tbb::parallel_for(0, nz, [&](int k) {
        const double zc = mGrid.zCentre_m(k), side = mGrid.dz_m(k) / h;
        for (int j = 0; j < ny; ++j) {
            const size_t c0 = S.cellIndex(0, j, k);
            double* b = rhs.data() + c0;
            mDomain.openOutfluxRow(U, V, W, j, k, b);
            for (int i = 0; i < nx; ++i) b[i] = airFlags[c0 + size_t(i)] ? h * b[i] : 0.0;
            if (!data) continue;
            for (int i = 0; i < nx; ++i) {
                if (!air(i, j, k) || (i > 0 && i < nx - 1 && j > 0 && j < ny - 1 &&
                                      !(k == nz - 1 && mSettings.openTop)))
                    continue;
                const double xc = o[0] + (i + 0.5) * h, yc = o[1] + (j + 0.5) * h;
                if (i == 0) b[i] += 2.0 * side * thX[S.faceXIndex(0, j, k)] * g(o[0], yc, zc);
                if (i == nx - 1)
                    b[i] += 2.0 * side * thX[S.faceXIndex(nx, j, k)] * g(o[0] + nx * h, yc, zc);
                if (j == 0) b[i] += 2.0 * side * thY[S.faceYIndex(i, 0, k)] * g(xc, o[1], zc);
                if (j == ny - 1)
                    b[i] += 2.0 * side * thY[S.faceYIndex(i, ny, k)] * g(xc, o[1] + ny * h, zc);
                if (k == nz - 1 && mSettings.openTop)
                    b[i] += 2.0 * (h / mGrid.dz_m(k)) * thZ[S.faceZIndex(i, j, nz)] *
                            g(xc, yc, mGrid.wsTop_m());
            }
        }
    });
    // Warm start. A step's potential is psi = -dt p / rho (Chorin 1968), and p moves smoothly
    // with the flow, so the guess is -dt times p extrapolated linearly from the last two
    // steps' (what the last step left, after two steps). Projections outside a step (a source
    // dropped in, a reset) are no pressure: they start the history again. Only where a step
    // moves the flow a few cells: a step of CFL 57 (the stability suite's MacCormack ridge)
    // carries the pressure tens of cells, the line through the last two says nothing more than
    // the last one, and the different start moved that case's drift from 0.099 to 0.103.
    const bool history = dt > 0.0 && !mSettings.incrementalPressure;
    if (history && mPressureSteps == 2 && stepCfl <= PRESSURE_EXTRAPOLATION_MAX_CFL) {
        tbb::parallel_for(size_t(0), mPsi.size(), [&](size_t c) {
            mPsi[c] = -dt * (2.0 * mPressureLast[c] - mPressureBefore[c]);
        });
    }
    SolveReport rep = mPoisson.solve(rhs, mPsi, settings);
    if (history) {
        std::swap(mPressureBefore, mPressureLast);
        mPressureLast.resize(mPsi.size());
        tbb::parallel_for(size_t(0), mPsi.size(),
                          [&](size_t c) { mPressureLast[c] = -mPsi[c] / dt; });
        mPressureSteps = std::min(mPressureSteps + 1, 2);
    } else {
        mPressureSteps = 0;
    }
    const std::vector<double>& psi = mPsi;
    auto P = [&](int i, int j, int k) { return psi[S.cellIndex(i, j, k)]; };
    // u += grad psi on the faces the projection updates: the interior faces row by row (a blend
    // where a face is closed, which the compiler vectorises), the box's faces with their data.
    auto interior = [](double* u, const uint8_t* ok, const double* hi, const double* lo, int n,
                       double gap) {
        for (int i = 0; i < n; ++i) u[i] = ok[i] ? u[i] + (hi[i] - lo[i]) / gap : u[i];
    };
    tbb::parallel_for(0, nz, [&](int k) {
        const double zc = mGrid.zCentre_m(k);
        for (int j = 0; j < ny; ++j) {
            const double yc = o[1] + (j + 0.5) * h;
            const size_t f0 = S.faceXIndex(0, j, k);
            const double* row = psi.data() + S.cellIndex(0, j, k);
            interior(U.data() + f0 + 1, mOkX.data() + f0 + 1, row + 1, row, nx - 1, h);
            if (mOkX[f0]) U[f0] += 2.0 * (P(0, j, k) - g(o[0], yc, zc)) / h;
            if (mOkX[f0 + size_t(nx)])
                U[f0 + size_t(nx)] += 2.0 * (g(o[0] + nx * h, yc, zc) - P(nx - 1, j, k)) / h;
        }
        for (int j = 1; j < ny; ++j) {
            const size_t f0 = S.faceYIndex(0, j, k);
            interior(V.data() + f0, mOkY.data() + f0, psi.data() + S.cellIndex(0, j, k),
                     psi.data() + S.cellIndex(0, j - 1, k), nx, h);
        }
        for (int i = 0; i < nx; ++i) {
            const double xc = o[0] + (i + 0.5) * h;
            const size_t f = S.faceYIndex(i, 0, k), l = S.faceYIndex(i, ny, k);
            if (mOkY[f]) V[f] += 2.0 * (P(i, 0, k) - g(xc, o[1], zc)) / h;
            if (mOkY[l]) V[l] += 2.0 * (g(xc, o[1] + ny * h, zc) - P(i, ny - 1, k)) / h;
        }
    });
    // z-faces: level 0 is the ground (never updated), level nz the top.
    tbb::parallel_for(1, nz + 1, [&](int k) {
        const double gap = mGrid.centreGap_m(k);  // h on cubic cells
        for (int j = 0; j < ny; ++j) {
            const size_t f0 = S.faceZIndex(0, j, k);
            if (k < nz) {
                interior(W.data() + f0, mOkZ.data() + f0, psi.data() + S.cellIndex(0, j, k),
                         psi.data() + S.cellIndex(0, j, k - 1), nx, gap);
                continue;
            }
            for (int i = 0; i < nx; ++i) {
                if (!mOkZ[f0 + size_t(i)]) continue;
                const double top = g(o[0] + (i + 0.5) * h, o[1] + (j + 0.5) * h, mGrid.wsTop_m());
                W[f0 + size_t(i)] += 2.0 * (top - P(i, j, nz - 1)) / gap;
            }
        }
    });
    extrapolateClosedFaces();
    if (!mSettings.openTop) closeLid();  // extrapolation must not reopen it
    return rep;
}

void UnsteadyWindSolver::closeLid() {
    std::vector<double>& W = mField.w_mps();
    const auto& lid = mSettings.lidVelocity_mps;
    const double h = mGrid.voxelSize_m;
    for (int j = 0; j < mGrid.ny; ++j)
        for (int i = 0; i < mGrid.nx; ++i)
            W[mSystem.faceZIndex(i, j, mGrid.nz)] =
                lid ? lid(mGrid.wsMin_m[0] + (i + 0.5) * h, mGrid.wsMin_m[1] + (j + 0.5) * h) : 0.0;
}

}  // namespace gale::sim

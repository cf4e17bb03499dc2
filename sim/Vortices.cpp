/// \file Vortices.cpp
/// Rankine, Lamb-Oseen and Burgers whirlwinds; vorticity confinement (Fedkiw, Stam, Jensen 2001).
#include "sim/Vortices.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"

namespace gale::sim {
namespace {
using gale::PI;
/// max over x of (1 - exp(-x^2)) / x, at x = 1.12091: the Lamb-Oseen peak in units of Gamma/(2 pi
/// r_c).
constexpr double LAMB_OSEEN_PEAK = 0.638161;
/// Smoothstep window from full to zero between the seeded radius and this multiple of it.
constexpr double WINDOW_END_FACTOR = 1.5;
/// Below this radius the axis itself: v = 0 (the profile's limit for every core).
constexpr double AXIS_EPS_M = 1e-12;

using detail::num;
using detail::smoothstep;
}  // namespace

const char* vortexProfileName(VortexProfile p) {
    switch (p) {
        case VortexProfile::Rankine:
            return "rankine";
        case VortexProfile::LambOseen:
            return "lamb_oseen";
        case VortexProfile::Burgers:
            return "burgers";
    }
    return "?";
}

VortexProfile vortexProfileFromName(const std::string& n) {
    if (n == "rankine") return VortexProfile::Rankine;
    if (n == "lamb_oseen") return VortexProfile::LambOseen;
    if (n == "burgers") return VortexProfile::Burgers;
    throw ParameterError("wind.whirlwinds.profile", "\"" + n + "\"",
                         "expected one of: rankine, lamb_oseen, burgers");
}

double peakSpeedFactor(VortexProfile p) {
    return p == VortexProfile::Rankine ? 1.0 : LAMB_OSEEN_PEAK;
}

void Whirlwind::validate() const {
    if (!std::isfinite(wsPosition_m[0]) || !std::isfinite(wsPosition_m[1]))
        throw ParameterError("wind.whirlwinds.position_m",
                             "[" + num(wsPosition_m[0]) + ", " + num(wsPosition_m[1]) + "]",
                             "must be finite");
    if (!(coreRadius_m > 0.0) || !std::isfinite(coreRadius_m))
        throw ParameterError("wind.whirlwinds.core_radius_m", num(coreRadius_m),
                             "must be > 0 and finite");
    if (!std::isfinite(peakSpeed_mps) || std::abs(peakSpeed_mps) > 1000.0)
        throw ParameterError("wind.whirlwinds.peak_speed_mps", num(peakSpeed_mps),
                             "must be in [-1000, 1000]");
    if (!std::isfinite(circulation_m2ps))
        throw ParameterError("wind.whirlwinds.circulation_m2ps", num(circulation_m2ps),
                             "must be finite");
    if (!(updraft_mps >= 0.0) || updraft_mps > 1000.0)
        throw ParameterError("wind.whirlwinds.updraft_mps", num(updraft_mps),
                             "must be in [0, 1000]");
    if (lifetime_s && !(*lifetime_s > 0.0))
        throw ParameterError("wind.whirlwinds.lifetime_s", num(*lifetime_s), "must be > 0");
    if (!std::isfinite(start_s))
        throw ParameterError("wind.whirlwinds.start_s", num(start_s), "must be finite");
    if (!(height_m >= 0.0) || !std::isfinite(height_m))
        throw ParameterError("wind.whirlwinds.height_m", num(height_m), "must be >= 0 and finite");
    // Not a scene key: the callers (the scene builder, live wind) keep the default.
    if (!(outerRadiusFactor >= 1.0) || !std::isfinite(outerRadiusFactor))
        throw std::logic_error("Whirlwind.outerRadiusFactor must be >= 1, got " +
                               num(outerRadiusFactor));
}

double Whirlwind::circulation() const {
    if (peakSpeed_mps != 0.0)
        return peakSpeed_mps * 2.0 * PI * coreRadius_m / peakSpeedFactor(profile);
    return circulation_m2ps;
}

double Whirlwind::tangentialSpeed_mps(double r) const {
    const double G = circulation(), rc = coreRadius_m;
    if (r < AXIS_EPS_M) return 0.0;
    if (profile == VortexProfile::Rankine)
        return r <= rc ? G * r / (2 * PI * rc * rc) : G / (2 * PI * r);
    return G / (2 * PI * r) * -std::expm1(-r * r / (rc * rc));
}

double Whirlwind::circulationWithin_m2ps(double r) const {
    return 2 * PI * r * tangentialSpeed_mps(r);
}

Whirlwind withMinimumCore(const Whirlwind& given, double voxelSize_m) {
    const double minCore_m = MIN_SMOOTHED_CORE_CELLS * voxelSize_m;
    if (!(given.coreRadius_m < minCore_m)) return given;
    Whirlwind smoothed = given;
    smoothed.circulation_m2ps = given.circulation();  // the same circulation, spread wider
    smoothed.peakSpeed_mps = 0.0;
    smoothed.coreRadius_m = minCore_m;
    return smoothed;
}

void addWhirlwind(const MacGrid& g, const Whirlwind& given, std::array<double, 2> c, double scale,
                  const GroundHeight& ground, double zTop, std::vector<double>& u,
                  std::vector<double>& v, std::vector<double>& w,
                  const std::array<const std::vector<uint8_t>*, 3>& masks) {
    const Whirlwind ww = withMinimumCore(given, g.voxelSize_m);
    const double rc = ww.coreRadius_m, rSeed = ww.outerRadiusFactor * rc,
                 rEnd = WINDOW_END_FACTOR * rSeed;
    double updraft = ww.updraft_mps;
    const double groundC = ground ? ground(c[0], c[1]) : g.wsMin_m[2];
    const double column = ww.height_m > 0.0 ? ww.height_m : std::max(zTop - groundC, g.voxelSize_m);
    if (ww.profile == VortexProfile::Burgers && updraft == 0.0) {
        // Burgers' strain a with r_c^2 = 4 nu / a; without a viscosity here we take the strain
        // that turns the core over once per column: a = v_peak / r_c, updraft a * column / 2.
        updraft =
            std::abs(ww.tangentialSpeed_mps(1.1209 * rc)) / rc * 0.5 * std::min(column, 4.0 * rc);
    }
    // The height window, of the height above the ground.
    auto vertical = [&](double above) {
        if (ww.height_m <= 0.0) return 1.0;
        return 1.0 - smoothstep((above - ww.height_m) / (0.5 * ww.height_m));
    };
    auto radial = [&](double r) { return 1.0 - smoothstep((r - rSeed) / (rEnd - rSeed)); };
    const double h = g.voxelSize_m;
    const Vec3d isC = g.isFromWs({c[0], c[1], 0.0});
    const int iLo = std::max(0, int(std::floor(isC[0] - rEnd / h)) - 1),
              iHi = std::min(g.nx, int(std::ceil(isC[0] + rEnd / h)) + 1);
    const int jLo = std::max(0, int(std::floor(isC[1] - rEnd / h)) - 1),
              jHi = std::min(g.ny, int(std::ceil(isC[1] + rEnd / h)) + 1);
    std::vector<double>* arrays[3] = {&u, &v, &w};
    /// What a column of faces shares whatever its height: the radial window and the profile's
    /// velocity along the component (or the updraft), and the ground under it.
    struct Column {
        bool skip = true;
        double radialWeight = 0, speed = 0, direction = 0, ground = 0;
    };
    for (int comp = 0; comp < 3; ++comp) {
        const Placement p = Placement(comp);
        const auto n = g.dims(p);
        std::vector<double>& a = *arrays[comp];
        const std::vector<uint8_t>* mask = masks[comp];
        const int i1 = std::min(iHi, n[0] - 1), j1 = std::min(jHi, n[1] - 1);
        if (i1 < iLo || j1 < jLo) continue;
        const int width = i1 - iLo + 1;
        std::vector<Column> columns(size_t(width) * size_t(j1 - jLo + 1));
        tbb::parallel_for(jLo, j1 + 1, [&](int j) {
            for (int i = iLo; i <= i1; ++i) {
                Column& col = columns[size_t(j - jLo) * size_t(width) + size_t(i - iLo)];
                const Vec3d ws = g.wsPosition(p, i, j, 0);
                const double dx = ws[0] - c[0], dy = ws[1] - c[1], r = std::sqrt(dx * dx + dy * dy);
                if (r >= rEnd) continue;
                if (comp == 2 && updraft == 0.0) continue;
                if (comp != 2 && r < AXIS_EPS_M) continue;
                col.skip = false;
                col.radialWeight = radial(r);
                col.ground = ground ? ground(ws[0], ws[1]) : g.wsMin_m[2];
                if (comp == 2) {
                    col.speed = updraft, col.direction = std::exp(-r * r / (rc * rc));
                } else {
                    // e_theta = (-dy, dx) / r
                    col.speed = ww.tangentialSpeed_mps(r),
                    col.direction = comp == 0 ? -dy / r : dx / r;
                }
            }
        });
        tbb::parallel_for(0, n[2], [&](int k) {
            const double z = g.wsPosition(p, 0, 0, k)[2];
            for (int j = jLo; j <= j1; ++j)
                for (int i = iLo; i <= i1; ++i) {
                    const Column& col = columns[size_t(j - jLo) * size_t(width) + size_t(i - iLo)];
                    if (col.skip) continue;
                    const size_t idx = g.index(p, i, j, k);
                    if (mask && !(*mask)[idx]) continue;
                    const double wgt = scale * col.radialWeight * vertical(z - col.ground);
                    if (wgt == 0.0) continue;
                    a[idx] += wgt * col.speed * col.direction;
                }
        });
    }
}

double circulationAround(const MacGrid& g, const MacVelocity& vel, std::array<double, 2> c,
                         double r, double z) {
    constexpr int POINTS = 64;  // a 64-gon: the trapezoidal rule is spectrally accurate on a circle
    double sum = 0.0;
    for (int n = 0; n < POINTS; ++n) {
        const double a = 2 * PI * n / POINTS;
        const Vec3d ws{c[0] + r * std::cos(a), c[1] + r * std::sin(a), z};
        const Vec3d uv = velocityAt(g, vel, {}, ws);
        sum += -uv[0] * std::sin(a) + uv[1] * std::cos(a);
    }
    return sum / POINTS * 2 * PI * r;
}

double verticalVorticity(const MacGrid& g, const MacVelocity& vel, int i, int j, int k) {
    // Cell-centred v and u of the neighbours, central differences (one-sided at the box sides).
    auto uc = [&](int ii, int jj) {
        ii = std::clamp(ii, 0, g.nx - 1), jj = std::clamp(jj, 0, g.ny - 1);
        const size_t a = g.faceXIndex(ii, jj, k);
        return 0.5 * ((*vel.u)[a] + (*vel.u)[g.faceXIndex(ii + 1, jj, k)]);
    };
    auto vc = [&](int ii, int jj) {
        ii = std::clamp(ii, 0, g.nx - 1), jj = std::clamp(jj, 0, g.ny - 1);
        const size_t a = g.faceYIndex(ii, jj, k);
        return 0.5 * ((*vel.v)[a] + (*vel.v)[g.faceYIndex(ii, jj + 1, k)]);
    };
    const int ip = std::min(i + 1, g.nx - 1), im = std::max(i - 1, 0),
              jp = std::min(j + 1, g.ny - 1), jm = std::max(j - 1, 0);
    const double h = g.voxelSize_m;
    const double dvdx = (vc(ip, j) - vc(im, j)) / (std::max(ip - im, 1) * h);
    const double dudy = (uc(i, jp) - uc(i, jm)) / (std::max(jp - jm, 1) * h);
    return dvdx - dudy;
}

void addVorticityConfinement(const MacGrid& g, const std::vector<uint8_t>& air, double eps,
                             double dt, std::vector<double>& u, std::vector<double>& v,
                             std::vector<double>& w) {
    if (!(eps > 0.0)) return;
    const int nx = g.nx, ny = g.ny, nz = g.nz;
    const double h = g.voxelSize_m;
    const size_t N = g.cellCount();
    auto cell = [&](int i, int j, int k) { return g.cellIndex(i, j, k); };
    // Cell-centred velocity, then vorticity by central differences over air neighbours.
    std::vector<Vec3d> uc(N);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t fx = g.faceXIndex(i, j, k), fy = g.faceYIndex(i, j, k);
                const size_t fz = g.faceZIndex(i, j, k);
                uc[cell(i, j, k)] = {0.5 * (u[fx] + u[fx + 1]), 0.5 * (v[fy] + v[fy + nx]),
                                     0.5 * (w[fz] + w[g.faceZIndex(i, j, k + 1)])};
            }
    });
    auto d = [&](int i, int j, int k, int axis, int comp) {
        int lo[3] = {i, j, k}, hi[3] = {i, j, k};
        const int n[3] = {nx, ny, nz};
        lo[axis] = std::max(lo[axis] - 1, 0), hi[axis] = std::min(hi[axis] + 1, n[axis] - 1);
        size_t a = cell(lo[0], lo[1], lo[2]), b = cell(hi[0], hi[1], hi[2]);
        if (!air[a]) a = cell(i, j, k), lo[axis] = (axis == 0 ? i : axis == 1 ? j : k);
        if (!air[b]) b = cell(i, j, k), hi[axis] = (axis == 0 ? i : axis == 1 ? j : k);
        const int span = hi[axis] - lo[axis];
        // Distance between the two centres: span h, through the layer heights along z.
        const double dist =
            axis < 2 || g.uniformZ() ? span * h : g.zCentre_m(hi[2]) - g.zCentre_m(lo[2]);
        return span > 0 ? (uc[b][comp] - uc[a][comp]) / dist : 0.0;
    };
    std::vector<Vec3d> om(N, Vec3d{0, 0, 0});
    std::vector<double> mag(N, 0.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t c = cell(i, j, k);
                if (!air[c]) continue;
                om[c] = {d(i, j, k, 1, 2) - d(i, j, k, 2, 1), d(i, j, k, 2, 0) - d(i, j, k, 0, 2),
                         d(i, j, k, 0, 1) - d(i, j, k, 1, 0)};
                mag[c] = std::sqrt(om[c][0] * om[c][0] + om[c][1] * om[c][1] + om[c][2] * om[c][2]);
            }
    });
    std::vector<Vec3d> f(N, Vec3d{0, 0, 0});
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t c = cell(i, j, k);
                if (!air[c]) continue;
                auto m = [&](int ii, int jj, int kk) {
                    ii = std::clamp(ii, 0, nx - 1), jj = std::clamp(jj, 0, ny - 1),
                    kk = std::clamp(kk, 0, nz - 1);
                    const size_t q = cell(ii, jj, kk);
                    return air[q] ? mag[q] : mag[c];
                };
                // Vertically over the two centre gaps around the cell (2 h on cubic cells).
                const double spanZ = g.centreGap_m(k) + g.centreGap_m(k + 1);
                Vec3d eta{(m(i + 1, j, k) - m(i - 1, j, k)) / (2 * h),
                          (m(i, j + 1, k) - m(i, j - 1, k)) / (2 * h),
                          (m(i, j, k + 1) - m(i, j, k - 1)) / spanZ};
                const double len = std::sqrt(eta[0] * eta[0] + eta[1] * eta[1] + eta[2] * eta[2]);
                if (!(len > 1e-12)) continue;
                const Vec3d Nv{eta[0] / len, eta[1] / len, eta[2] / len};
                const Vec3d& o = om[c];
                f[c] = {eps * h * (Nv[1] * o[2] - Nv[2] * o[1]),
                        eps * h * (Nv[2] * o[0] - Nv[0] * o[2]),
                        eps * h * (Nv[0] * o[1] - Nv[1] * o[0])};
            }
    });
    // Average to interior faces between two air cells.
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t c = cell(i, j, k);
                if (!air[c]) continue;
                if (i > 0 && air[cell(i - 1, j, k)])
                    u[g.faceXIndex(i, j, k)] += dt * 0.5 * (f[c][0] + f[cell(i - 1, j, k)][0]);
                if (j > 0 && air[cell(i, j - 1, k)])
                    v[g.faceYIndex(i, j, k)] += dt * 0.5 * (f[c][1] + f[cell(i, j - 1, k)][1]);
                if (k > 0 && air[cell(i, j, k - 1)])
                    w[g.faceZIndex(i, j, k)] += dt * 0.5 * (f[c][2] + f[cell(i, j, k - 1)][2]);
            }
    });
}

}  // namespace gale::sim

/// \file LiveWind.cpp
/// Sources dropped into the running unsteady flow (see LiveWind.h).

#include "coupling/LiveWind.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <vector>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"
#include "sim/Interpolation.h"
#include "sim/Vortices.h"

namespace gale::coupling {
namespace {

/// 0 below edge0, 1 above edge1, sim's Hermite smoothstep between.
double smoothstep(double edge0, double edge1, double x) {
    return sim::detail::smoothstep((x - edge0) / (edge1 - edge0));
}

/// Full below full_m above the ground, zero above full_m + taper_m, smooth between; zero under
/// the ground (closed faces are the solver's to refill).
double heightWindow(double aboveGround_m, double full_m, double taper_m) {
    if (aboveGround_m < 0.0) return 0.0;
    return 1.0 - smoothstep(full_m, full_m + taper_m, aboveGround_m);
}

/// Added velocity (m/s, world axes) at a world point aboveGround_m over the terrain.
using AddedVelocity = std::function<sim::Vec3d(const sim::Vec3d& wsPos_m, double aboveGround_m)>;

/// Adds the velocity's component along each face's axis to that face (MAC layout, i fastest).
void addToFaces(sim::UnsteadyWindSolver& solver, const AddedVelocity& added) {
    const sim::MacGrid& g = solver.grid();
    sim::WindField& field = solver.editField();
    std::vector<double>* arrays[3] = {&field.u_mps(), &field.v_mps(), &field.w_mps()};
    const sim::Placement placements[3] = {sim::Placement::FaceX, sim::Placement::FaceY,
                                          sim::Placement::FaceZ};
    for (int axis = 0; axis < 3; ++axis) {
        const auto d = g.dims(placements[axis]);
        std::vector<double>& a = *arrays[axis];
        for (int k = 0; k < d[2]; ++k)
            for (int j = 0; j < d[1]; ++j)
                for (int i = 0; i < d[0]; ++i) {
                    const sim::Vec3d ws = g.wsPosition(placements[axis], i, j, k);
                    const double ground_m =
                        g.terrain ? g.terrain->sample(ws[0], ws[1]) : g.wsMin_m[2];
                    const sim::Vec3d u = added(ws, ws[2] - ground_m);
                    a[g.index(placements[axis], i, j, k)] += u[axis];
                }
    }
}

}  // namespace

const char* liveSourceName(LiveSourceKind kind) {
    switch (kind) {
        case LiveSourceKind::Whirlwind:
            return "whirlwind";
        case LiveSourceKind::GustFront:
            return "gust front";
        case LiveSourceKind::Blast:
            return "blast";
        case LiveSourceKind::Downwash:
            return "downwash";
    }
    return "?";
}

void LiveSource::validate() const {
    if (!(std::isfinite(speed_mps) && speed_mps > 0.0))
        throw ParameterError("live.speed_mps", formatG(speed_mps), "must be finite and > 0");
    if (!(std::isfinite(radius_m) && radius_m > 0.0))
        throw ParameterError("live.radius_m", formatG(radius_m), "must be finite and > 0");
    for (double c : {wsAt_m[0], wsAt_m[1], wsTo_m[0], wsTo_m[1]})
        if (!std::isfinite(c))
            throw ParameterError("live.position_m", formatG(c), "must be finite");
}

sim::SolveReport addLiveSource(sim::UnsteadyWindSolver& solver, const LiveSource& s) {
    s.validate();
    const sim::MacGrid& g = solver.grid();
    const double R = s.radius_m;
    const double x0 = s.wsAt_m[0], y0 = s.wsAt_m[1];
    switch (s.kind) {
        case LiveSourceKind::Whirlwind: {
            sim::Whirlwind ww;
            ww.wsPosition_m = s.wsAt_m;
            ww.coreRadius_m = R;
            ww.peakSpeed_mps = s.speed_mps;
            ww.profile = sim::VortexProfile::LambOseen;
            const sim::Heightfield* T = g.terrain;
            const double floor_m = g.wsMin_m[2];
            const sim::GroundHeight ground = [T, floor_m](double x, double y) {
                return T ? T->sample(x, y) : floor_m;
            };
            sim::WindField& field = solver.editField();
            sim::addWhirlwind(g, ww, s.wsAt_m, 1.0, ground, g.wsMin_m[2] + g.nz * g.voxelSize_m,
                              field.u_mps(), field.v_mps(), field.w_mps());
            break;
        }
        case LiveSourceKind::GustFront: {
            double dx = s.wsTo_m[0] - x0, dy = s.wsTo_m[1] - y0;
            const double length = std::hypot(dx, dy);
            if (length > 0.0) {
                dx /= length, dy /= length;
            } else {
                dx = 1.0, dy = 0.0;  // a click without a drag: along +x
            }
            const double halfLength = 0.5 * std::max(length, 2.0 * R);
            const double cx = x0 + 0.5 * length * dx, cy = y0 + 0.5 * length * dy;
            addToFaces(solver, [&](const sim::Vec3d& ws, double above_m) -> sim::Vec3d {
                const double along = (ws[0] - cx) * dx + (ws[1] - cy) * dy;
                const double across = -(ws[0] - cx) * dy + (ws[1] - cy) * dx;
                const double f = (1.0 - smoothstep(halfLength, halfLength + R, std::abs(along))) *
                                 (1.0 - smoothstep(R, 2.0 * R, std::abs(across))) *
                                 heightWindow(above_m, 2.0 * R, R);
                return {s.speed_mps * f * dx, s.speed_mps * f * dy, 0.0};
            });
            break;
        }
        case LiveSourceKind::Blast:
            addToFaces(solver, [&](const sim::Vec3d& ws, double above_m) -> sim::Vec3d {
                const double rx = ws[0] - x0, ry = ws[1] - y0;
                const double r2 = (rx * rx + ry * ry) / (R * R);
                // (r / R) exp((1 - r^2/R^2) / 2) times the unit radial vector (rx, ry) / r.
                const double f = s.speed_mps / R * std::exp(0.5 * (1.0 - r2)) *
                                 heightWindow(above_m, R, 0.5 * R);
                return {f * rx, f * ry, 0.0};
            });
            break;
        case LiveSourceKind::Downwash:
            addToFaces(solver, [&](const sim::Vec3d& ws, double above_m) -> sim::Vec3d {
                const double rx = ws[0] - x0, ry = ws[1] - y0;
                const double lift = smoothstep(0.25 * R, 0.5 * R, above_m);  // not at the ground
                return {0.0, 0.0, -s.speed_mps * std::exp(-(rx * rx + ry * ry) / (R * R)) * lift};
            });
            break;
    }
    return solver.project();
}

std::optional<glm::vec3> pickTerrain(const render::TerrainMesh& mesh, const glm::vec3& wsOrigin_m,
                                     const glm::vec3& wsDirection) {
    if (mesh.nx < 2 || mesh.ny < 2 || mesh.wsPosition_m.size() != size_t(mesh.nx) * size_t(mesh.ny))
        return std::nullopt;
    const glm::vec3 lo = mesh.wsPosition_m.front(), hi = mesh.wsPosition_m.back();
    std::vector<float> xs(mesh.nx), ys(mesh.ny);
    float zMax = -INFINITY;
    for (int i = 0; i < mesh.nx; ++i) xs[i] = mesh.wsPosition_m[i].x;
    for (int j = 0; j < mesh.ny; ++j) ys[j] = mesh.wsPosition_m[size_t(j) * mesh.nx].y;
    for (const glm::vec3& p : mesh.wsPosition_m) zMax = std::max(zMax, p.z);
    // Height of the mesh under (x, y), bilinear in the quad; nothing outside the plan.
    auto heightAt = [&](float x, float y) -> std::optional<float> {
        if (!(x >= lo.x && x <= hi.x && y >= lo.y && y <= hi.y)) return std::nullopt;
        const int i = int(std::clamp<std::ptrdiff_t>(
            std::upper_bound(xs.begin(), xs.end(), x) - xs.begin() - 1, 0, mesh.nx - 2));
        const int j = int(std::clamp<std::ptrdiff_t>(
            std::upper_bound(ys.begin(), ys.end(), y) - ys.begin() - 1, 0, mesh.ny - 2));
        const float tx = (x - xs[i]) / (xs[i + 1] - xs[i]), ty = (y - ys[j]) / (ys[j + 1] - ys[j]);
        auto z = [&](int a, int b) { return mesh.wsPosition_m[size_t(b) * mesh.nx + a].z; };
        return sim::bilinearWeighted(z(i, j), z(i + 1, j), z(i, j + 1), z(i + 1, j + 1), tx, ty);
    };
    // March in steps of half the finest mesh spacing, then bisect the step that went under.
    const float step_m = 0.5f * std::min(xs[1] - xs[0], ys[1] - ys[0]);
    const float reach_m = glm::length(hi - lo) + std::abs(wsOrigin_m.z - zMax) +
                          glm::length(glm::vec2(wsOrigin_m) - glm::vec2(0.5f * (lo + hi)));
    if (!(step_m > 0.0f) || !std::isfinite(reach_m)) return std::nullopt;
    auto below = [&](float s) {
        const glm::vec3 p = wsOrigin_m + s * wsDirection;
        const std::optional<float> z = heightAt(p.x, p.y);
        return z && p.z <= *z;
    };
    float previous = 0.0f;
    for (float s = 0.0f; s <= reach_m; s += step_m) {
        if (below(s)) {
            float a = previous, b = s;
            for (int n = 0; n < 30; ++n) {
                const float m = 0.5f * (a + b);
                (below(m) ? b : a) = m;
            }
            glm::vec3 hit = wsOrigin_m + b * wsDirection;
            hit.z = heightAt(hit.x, hit.y).value_or(hit.z);
            return hit;
        }
        previous = s;
    }
    return std::nullopt;
}

}  // namespace gale::coupling

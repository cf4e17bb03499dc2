#include "coupling/FieldOverlayBuilder.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Interpolation.h"

namespace gale::coupling {
namespace {

/// Default arrow height, in grass heights: just above the tips, so the grass does not hide them.
constexpr double ARROW_ABOVE_GRASS = 1.25;
/// Arrows reach this fraction of their grid spacing at the top of the colour map.
constexpr double ARROW_LENGTH_OF_SPACING = 0.85;
/// Arrow grids default to this many arrows along the terrain's larger side.
constexpr double DEFAULT_ARROWS_ALONG = 16.0;
/// Slice grid: 4 quads per arrow spacing, at most this many points a side.
constexpr int MAX_SLICE_SIDE = 128;
/// At most this many vortex-core markers, the strongest.
constexpr size_t MAX_VORTEX_MARKERS = 24;
/// Vortex-core maxima closer than this many cells (in every axis) to a stronger one are the same
/// core.
constexpr int MARKER_SEPARATION = 4;
/// Streamline step, in voxels.
constexpr double STREAMLINE_STEP_VOXELS = 0.5;

glm::dvec3 toD(const std::array<double, 3>& a) { return glm::dvec3(a[0], a[1], a[2]); }

double defaultSpacing(const MeshHeight& h, const OverlaySpec& spec) {
    if (spec.arrowSpacing_m) return *spec.arrowSpacing_m;
    return std::max(h.maxX() - h.minX(), h.maxY() - h.minY()) / DEFAULT_ARROWS_ALONG;
}

/// Grid coordinates inset half a spacing from both ends of [lo, hi].
std::vector<double> insetGrid(double lo, double hi, double spacing) {
    const int n = std::max(1, int(std::floor((hi - lo) / spacing + 1e-9)));
    const double first = lo + 0.5 * ((hi - lo) - (n - 1) * spacing);
    std::vector<double> out;
    for (int k = 0; k < n; ++k) out.push_back(first + k * spacing);
    return out;
}

render::OverlaySlice buildSlice(const MeshHeight& ground, double spacing, double height_m,
                                const VelocityFn& velocity) {
    render::OverlaySlice s;
    const double sx = ground.maxX() - ground.minX(), sy = ground.maxY() - ground.minY();
    const double cell = spacing / 4.0;
    s.nx = std::clamp(int(std::ceil(sx / cell)) + 1, 2, MAX_SLICE_SIDE);
    s.ny = std::clamp(int(std::ceil(sy / cell)) + 1, 2, MAX_SLICE_SIDE);
    for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i) {
            const double x = ground.minX() + sx * i / (s.nx - 1);
            const double y = ground.minY() + sy * j / (s.ny - 1);
            const glm::dvec3 p(x, y, ground.at(x, y) + height_m);
            s.wsPosition_m.emplace_back(p);
            s.speed.push_back(float(glm::length(velocity(p))));
        }
    return s;
}

}  // namespace

void validate(const OverlaySpec& spec) {
    auto bad = [](const std::string& key, const std::string& what, double got) {
        throw ParameterError("overlay." + key, formatG(got), what);
    };
    // An unset optional means "automatic"; a set one must be a usable number.
    auto badOptional = [&](const std::optional<double>& v, const std::string& key, double lo,
                           bool loOpen) {
        if (v && (!std::isfinite(*v) || (loOpen ? !(*v > lo) : !(*v >= lo))))
            bad(key, std::string(loOpen ? "must be > " : "must be >= ") + formatG(lo), *v);
    };
    badOptional(spec.arrowSpacing_m, "arrow_spacing_m", 0.0, /*loOpen=*/true);
    badOptional(spec.arrowHeight_m, "arrow_height_m", 0.0, /*loOpen=*/false);
    if (!(spec.sliceHeight_m > 0.0) || !std::isfinite(spec.sliceHeight_m))
        bad("slice_height_m", "must be > 0", spec.sliceHeight_m);
    if (spec.streamlineCount < 1 || spec.streamlineCount > 1000)
        bad("streamline_count", "must be in 1..1000", spec.streamlineCount);
    badOptional(spec.vortexQ_per_s2, "vortex_q_per_s2", 0.0, /*loOpen=*/true);
    badOptional(spec.speedMax_mps, "speed_max_mps", 0.0, /*loOpen=*/true);
}

MeshHeight::MeshHeight(const render::TerrainMesh& mesh) : mMesh(mesh) {
    if (mesh.nx < 2 || mesh.ny < 2 || mesh.wsPosition_m.size() != size_t(mesh.nx) * size_t(mesh.ny))
        throw std::logic_error("MeshHeight: the mesh must be a grid of nx, ny >= 2");
    mX0 = mesh.wsPosition_m.front().x;
    mY0 = mesh.wsPosition_m.front().y;
    mX1 = mesh.wsPosition_m.back().x;
    mY1 = mesh.wsPosition_m.back().y;
}

double MeshHeight::at(double x, double y) const {
    const double fx = std::clamp((x - mX0) / (mX1 - mX0), 0.0, 1.0) * (mMesh.nx - 1);
    const double fy = std::clamp((y - mY0) / (mY1 - mY0), 0.0, 1.0) * (mMesh.ny - 1);
    const int i = std::min(int(fx), mMesh.nx - 2), j = std::min(int(fy), mMesh.ny - 2);
    const double tx = fx - i, ty = fy - j;
    auto z = [&](int a, int b) { return double(mMesh.wsPosition_m[size_t(b) * mMesh.nx + a].z); };
    return sim::bilinearWeighted(z(i, j), z(i + 1, j), z(i, j + 1), z(i + 1, j + 1), tx, ty);
}

glm::dvec3 rk2Step(const VelocityFn& velocity, const glm::dvec3& x, double dt_s) {
    const glm::dvec3 mid = x + 0.5 * dt_s * velocity(x);
    return x + dt_s * velocity(mid);
}

std::vector<glm::dvec3> traceStreamline(const VelocityFn& velocity, const glm::dvec3& seed,
                                        double step_m, int maxPoints, double minSpeed_mps) {
    std::vector<glm::dvec3> points{seed};
    glm::dvec3 x = seed;
    while (int(points.size()) < maxPoints) {
        const double speed = glm::length(velocity(x));
        if (!(speed >= minSpeed_mps)) break;
        const glm::dvec3 next = rk2Step(velocity, x, step_m / speed);
        if (!(glm::length(velocity(next)) >= minSpeed_mps)) break;  // left the field
        points.push_back(next);
        x = next;
    }
    return points;
}

double qCriterion(const std::array<std::array<double, 3>, 3>& g) {
    double omega2 = 0.0, strain2 = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double s = 0.5 * (g[i][j] + g[j][i]);
            const double w = 0.5 * (g[i][j] - g[j][i]);
            strain2 += s * s;
            omega2 += w * w;
        }
    return 0.5 * (omega2 - strain2);
}

float niceSpeedMax(float maxSpeed) {
    if (!(maxSpeed > 0.0f) || !std::isfinite(maxSpeed)) return 1.0f;
    const std::vector<float> ticks = render::FieldOverlay::legendTicks(maxSpeed);
    const float step = ticks.size() > 1 ? ticks[1] : maxSpeed;
    return step * std::ceil(maxSpeed / step - 1e-6f);
}

namespace {

/// The legend's "where" line: the heights above the ground of what is coloured, metres.
std::string legendHeights(const OverlaySpec& spec, double arrowHeight_m) {
    const std::string slice = formatG(spec.sliceHeight_m, 3) + " m";
    const std::string arrows = formatG(arrowHeight_m, 3) + " m";
    const bool sheet = spec.slice || spec.streamlines;
    if (spec.arrows && sheet && slice != arrows)
        return "slice " + slice + ", arrows " + arrows + " above ground";
    if (spec.arrows) return arrows + " above ground";
    if (sheet) return slice + " above ground";
    return "";
}

}  // namespace

render::FieldOverlayData buildFieldOverlay(const sim::WindField& field,
                                           const render::TerrainMesh& mesh, const OverlaySpec& spec,
                                           double grassHeight_m) {
    validate(spec);
    const MeshHeight ground(mesh);
    const VelocityFn velocity = [&field](const glm::dvec3& p) {
        return toD(field.velocityAt_mps(p.x, p.y, p.z));
    };
    const double spacing = defaultSpacing(ground, spec);
    const double arrowHeight = spec.arrowHeight_m.value_or(ARROW_ABOVE_GRASS * grassHeight_m);
    render::FieldOverlayData data;
    data.legend = spec.legend;
    data.quantity = "wind speed";
    data.where = legendHeights(spec, arrowHeight);
    float maxSpeed = 0.0f;

    std::vector<glm::dvec3> arrowVelocity;
    if (spec.arrows)
        for (double y : insetGrid(ground.minY(), ground.maxY(), spacing))
            for (double x : insetGrid(ground.minX(), ground.maxX(), spacing)) {
                const glm::dvec3 base(x, y, ground.at(x, y) + arrowHeight);
                const glm::dvec3 u = velocity(base);
                render::OverlayArrow a;
                a.wsBase_m = glm::vec3(base);
                a.speed = float(glm::length(u));
                data.arrows.push_back(a);
                arrowVelocity.push_back(u);
                maxSpeed = std::max(maxSpeed, a.speed);
            }
    if (spec.slice || spec.streamlines) {
        render::OverlaySlice slice = buildSlice(ground, spacing, spec.sliceHeight_m, velocity);
        glm::dvec3 mean(0.0);
        for (size_t v = 0; v < slice.speed.size(); ++v) {
            mean += velocity(glm::dvec3(slice.wsPosition_m[v]));
            if (spec.slice) maxSpeed = std::max(maxSpeed, slice.speed[v]);
        }
        if (spec.slice) data.slice = std::move(slice);
        if (spec.streamlines && glm::length(glm::dvec2(mean)) > 0.0) {
            // Seeds along the edge the mean wind comes from, a quarter voxel inside the terrain.
            const bool alongX = std::fabs(mean.x) >= std::fabs(mean.y);
            const double inset = 0.25 * field.voxelSize_m();
            const double step = STREAMLINE_STEP_VOXELS * field.voxelSize_m();
            const double extent = (ground.maxX() - ground.minX()) + (ground.maxY() - ground.minY());
            const int maxPoints = int(std::min(100000.0, 4.0 * extent / step));
            for (int k = 0; k < spec.streamlineCount; ++k) {
                const double f = (k + 0.5) / spec.streamlineCount;
                double x, y;
                if (alongX) {
                    x = mean.x > 0 ? ground.minX() + inset : ground.maxX() - inset;
                    y = ground.minY() + f * (ground.maxY() - ground.minY());
                } else {
                    y = mean.y > 0 ? ground.minY() + inset : ground.maxY() - inset;
                    x = ground.minX() + f * (ground.maxX() - ground.minX());
                }
                const glm::dvec3 seed(x, y, ground.at(x, y) + spec.sliceHeight_m);
                render::OverlayPolyline line;
                for (const glm::dvec3& p : traceStreamline(velocity, seed, step, maxPoints)) {
                    line.wsPoint_m.emplace_back(p);
                    line.speed.push_back(float(glm::length(velocity(p))));
                    maxSpeed = std::max(maxSpeed, line.speed.back());
                }
                if (line.wsPoint_m.size() >= 2) data.streamlines.push_back(std::move(line));
            }
        }
    }
    if (spec.vortexCores) {
        const int nx = field.nx(), ny = field.ny(), nz = field.nz();
        const double h = field.voxelSize_m();
        const auto idx = [&](int i, int j, int k) { return field.layout().cellIndex(i, j, k); };
        std::vector<double> q(field.layout().cellCount(), -1e300);
        double qMax = 0.0, uMax = 0.0;
        for (int k = 1; k + 1 < nz; ++k)
            for (int j = 1; j + 1 < ny; ++j)
                for (int i = 1; i + 1 < nx; ++i) {
                    if (!field.isAir(i, j, k)) continue;
                    const auto c = field.cellVelocity_mps(i, j, k);
                    uMax = std::max(uMax, glm::length(toD(c)));
                    // Cells within two of the terrain or the box sides read extrapolated faces:
                    // their differences are boundary artefacts, not vortices.
                    if (i < 2 || j < 2 || k < 2 || i + 2 >= nx || j + 2 >= ny || k + 2 >= nz)
                        continue;
                    bool nearSolid = false;
                    for (int dk = -2; dk <= 2 && !nearSolid; ++dk)
                        for (int dj = -2; dj <= 2 && !nearSolid; ++dj)
                            for (int di = -2; di <= 2 && !nearSolid; ++di)
                                nearSolid = !field.isAir(i + di, j + dj, k + dk);
                    if (nearSolid) continue;
                    const int n[3][3] = {{i - 1, j, k}, {i, j - 1, k}, {i, j, k - 1}};
                    const int p[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
                    bool ok = true;
                    std::array<std::array<double, 3>, 3> g{};
                    for (int d = 0; d < 3 && ok; ++d) {
                        ok = field.isAir(n[d][0], n[d][1], n[d][2]) &&
                             field.isAir(p[d][0], p[d][1], p[d][2]);
                        if (!ok) break;
                        const auto up = field.cellVelocity_mps(p[d][0], p[d][1], p[d][2]);
                        const auto dn = field.cellVelocity_mps(n[d][0], n[d][1], n[d][2]);
                        for (int comp = 0; comp < 3; ++comp)
                            g[comp][d] = (up[comp] - dn[comp]) / (2.0 * h);
                    }
                    if (!ok) continue;
                    q[idx(i, j, k)] = qCriterion(g);
                    qMax = std::max(qMax, q[idx(i, j, k)]);
                }
        const double threshold = spec.vortexQ_per_s2.value_or(
            std::max(0.25 * qMax, (0.1 * uMax / h) * (0.1 * uMax / h)));
        std::vector<std::pair<double, glm::ivec3>> cores;
        for (int k = 1; k + 1 < nz; ++k)
            for (int j = 1; j + 1 < ny; ++j)
                for (int i = 1; i + 1 < nx; ++i) {
                    const double qc = q[idx(i, j, k)];
                    if (!(qc > threshold)) continue;
                    bool peak = true;
                    for (int dk = -1; dk <= 1 && peak; ++dk)
                        for (int dj = -1; dj <= 1 && peak; ++dj)
                            for (int di = -1; di <= 1 && peak; ++di)
                                if ((di || dj || dk) && q[idx(i + di, j + dj, k + dk)] > qc)
                                    peak = false;
                    if (peak) cores.emplace_back(qc, glm::ivec3(i, j, k));
                }
        std::sort(cores.begin(), cores.end(), [](auto& a, auto& b) { return a.first > b.first; });
        const auto origin = field.wsMin_m();
        std::vector<glm::ivec3> kept;
        for (const auto& [qc, cell] : cores) {
            if (kept.size() >= MAX_VORTEX_MARKERS) break;
            const int i = cell.x, j = cell.y, k = cell.z;
            // One marker per core: skip maxima within MARKER_SEPARATION cells of a stronger one.
            bool near = false;
            for (const glm::ivec3& o : kept)
                near = near || (std::abs(o.x - i) <= MARKER_SEPARATION &&
                                std::abs(o.y - j) <= MARKER_SEPARATION &&
                                std::abs(o.z - k) <= MARKER_SEPARATION);
            if (near) continue;
            kept.emplace_back(i, j, k);
            render::OverlayMarker m;
            // Where the core touches the ground: the ring sits on the grass tops under the
            // core's cell, so it marks the grass the core stirs instead of floating above it.
            const double x = origin[0] + (i + 0.5) * h, y = origin[1] + (j + 0.5) * h;
            m.wsPosition_m = glm::vec3(x, y, ground.at(x, y) + grassHeight_m);
            m.size_m = float(1.5 * h);
            data.vortexCores.push_back(m);
        }
    }
    data.speedMax = spec.speedMax_mps
                        ? float(*spec.speedMax_mps)
                        : std::max(float(spec.speedMaxFloor_mps), niceSpeedMax(maxSpeed));
    const double arrowScale = ARROW_LENGTH_OF_SPACING * spacing / data.speedMax;
    for (size_t a = 0; a < data.arrows.size(); ++a)
        data.arrows[a].wsVector_m = glm::vec3(arrowVelocity[a] * arrowScale);
    return data;
}

render::FieldOverlayData buildGrassWindOverlay(const render::GrassWind& wind,
                                               const render::TerrainMesh& mesh,
                                               const OverlaySpec& spec, double grassHeight_m) {
    validate(spec);
    const MeshHeight ground(mesh);
    render::FieldOverlayData data;
    data.legend = spec.legend;
    data.unit = "intensity";
    data.quantity = "grass bend intensity";
    data.where = "per blade group";
    data.speedMax = float(spec.speedMax_mps.value_or(1.0));
    const std::vector<glm::vec3>& direction = wind.wsDirection();
    const std::vector<uint32_t>& group = wind.group();
    if (!spec.arrows || direction.size() != mesh.wsPosition_m.size() ||
        group.size() != mesh.wsPosition_m.size())
        return data;
    const double spacing = defaultSpacing(ground, spec);
    const double arrowHeight = spec.arrowHeight_m.value_or(ARROW_ABOVE_GRASS * grassHeight_m);
    const double arrowScale = ARROW_LENGTH_OF_SPACING * spacing / data.speedMax;
    for (double y : insetGrid(ground.minY(), ground.maxY(), spacing))
        for (double x : insetGrid(ground.minX(), ground.maxX(), spacing)) {
            const int i = int(
                std::lround((x - ground.minX()) / (ground.maxX() - ground.minX()) * (mesh.nx - 1)));
            const int j = int(
                std::lround((y - ground.minY()) / (ground.maxY() - ground.minY()) * (mesh.ny - 1)));
            const size_t v = size_t(j) * mesh.nx + size_t(i);
            const uint32_t g = group[v];
            const float intensity = g < wind.groupIntensity.size() ? wind.groupIntensity[g] : 0.0f;
            render::OverlayArrow a;
            a.wsBase_m = glm::vec3(x, y, ground.at(x, y) + arrowHeight);
            a.wsVector_m = direction[v] * float(intensity * arrowScale);
            a.speed = std::fabs(intensity);
            data.arrows.push_back(a);
        }
    return data;
}

render::FieldOverlayData buildOverlay(const WindSource& source, const render::GrassWind& wind,
                                      const render::TerrainMesh& mesh, const OverlaySpec& spec,
                                      double grassHeight_m) {
    if (!spec.any()) {
        render::FieldOverlayData none;
        none.legend = false;
        return none;
    }
    if (const sim::WindField* field = source.currentField())
        return buildFieldOverlay(*field, mesh, spec, grassHeight_m);
    return buildGrassWindOverlay(wind, mesh, spec, grassHeight_m);
}

}  // namespace gale::coupling

#include "render/NearBlades.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>
#include <queue>
#include <stdexcept>
#include <utility>

#include "render/TerrainChunks.h"

namespace gale::render::detail {

namespace {

/// A 32-bit hash of a lattice cell and a stream number (the finaliser of MurmurHash3 over a
/// mix of the three): each stream gives an independent uniform value per cell.
uint32_t cellHash(int32_t ci, int32_t cj, uint32_t stream) {
    uint32_t h = static_cast<uint32_t>(ci) * 0x8da6b343u ^ static_cast<uint32_t>(cj) * 0xd8163841u ^
                 (stream + 1u) * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

/// Uniform in [0, 1).
float cellUniform(int32_t ci, int32_t cj, uint32_t stream) {
    return static_cast<float>(cellHash(ci, cj, stream) >> 8) * (1.0f / 16777216.0f);
}

enum Stream : uint32_t { JITTER_X, JITTER_Y, HEIGHT, WIDTH, FACING, STIFFNESS, TINT, FADE_KEY };

/// A blade's ribbon faces any way about the normal: facing in [-pi, pi), radians.
constexpr float MAX_FACING_RAD = 3.14159265f;

/// The six planes of a clip-from-world matrix (Gribb and Hartmann 2001), normalised so that a
/// plane's value at a point is its distance, positive inside.
class Frustum {
  public:
    explicit Frustum(const glm::mat4& m) {
        for (int k = 0; k < 3; ++k)
            for (const float sign : {1.0f, -1.0f}) {
                glm::vec4 p;
                for (int c = 0; c < 4; ++c) p[c] = m[c][3] + sign * m[c][k];
                const float len = glm::length(glm::vec3(p));
                mPlanes[mCount++] = len > 0.0f ? p / len : p;
            }
    }
    /// False only when the sphere lies wholly outside a plane.
    bool mayHoldSphere(const glm::vec3& centre, float radius) const {
        for (int k = 0; k < mCount; ++k)
            if (glm::dot(glm::vec3(mPlanes[k]), centre) + mPlanes[k].w < -radius) return false;
        return true;
    }

  private:
    glm::vec4 mPlanes[6];
    int mCount = 0;
};

}  // namespace

float nearBladeFade(float d_m, float innerRadius_m, float radius_m) {
    if (!(radius_m > 0.0f)) return 0.0f;
    const float lo = std::min(innerRadius_m, radius_m);
    if (d_m <= lo) return 1.0f;
    if (d_m >= radius_m) return 0.0f;
    const float t = (d_m - lo) / (radius_m - lo);
    return 1.0f - t * t * (3.0f - 2.0f * t);
}

BladeStatistics bladeStatistics(const Image& level0, float tile_m) {
    if (!(tile_m > 0.0f)) throw std::logic_error("bladeStatistics: tile_m must be > 0");
    const int n = level0.width;
    if (n <= 0 || level0.height != n ||
        level0.rgba.size() != static_cast<size_t>(n) * static_cast<size_t>(n) * 4u)
        throw std::logic_error("bladeStatistics: level 0 must be square with width^2 RGBA texels");
    const auto alphaAt = [&](int x, int y) {
        return level0.rgba[(static_cast<size_t>(y) * n + static_cast<size_t>(x)) * 4u + 3u];
    };
    // Footprints: 4-connected regions of one alpha (one blade's height), wrapping as the texture
    // tiles. Overlapping blades of equal height count as one, which errs towards fewer blades.
    std::vector<uint8_t> seen(static_cast<size_t>(n) * static_cast<size_t>(n), 0);
    std::vector<std::pair<int, int>> stack;
    std::array<double, 256> bladesOfAlpha{};
    double blades = 0.0, area = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const uint8_t a = alphaAt(x, y);
            const size_t at = static_cast<size_t>(y) * n + static_cast<size_t>(x);
            if (a == 0 || seen[at]) continue;
            seen[at] = 1;
            stack.assign(1, {x, y});
            while (!stack.empty()) {
                const auto [px, py] = stack.back();
                stack.pop_back();
                area += 1.0;
                const int next[4][2] = {{(px + 1) % n, py},
                                        {(px + n - 1) % n, py},
                                        {px, (py + 1) % n},
                                        {px, (py + n - 1) % n}};
                for (const auto& q : next) {
                    const size_t k = static_cast<size_t>(q[1]) * n + static_cast<size_t>(q[0]);
                    if (seen[k] || alphaAt(q[0], q[1]) != a) continue;
                    seen[k] = 1;
                    stack.push_back({q[0], q[1]});
                }
            }
            blades += 1.0;
            bladesOfAlpha[a] += 1.0;
        }
    BladeStatistics s;
    if (blades == 0.0) return s;
    s.bladesPerM2 = static_cast<float>(blades / (double(tile_m) * double(tile_m)));
    s.width_m = static_cast<float>(std::sqrt(area / blades) * double(tile_m) / double(n));
    // Heights: the inverse of the blades' height distribution at the quantiles' midpoints.
    double cumulative = 0.0;
    int alpha = 1;
    for (int k = 0; k < 256; ++k) {
        const double q = (double(k) + 0.5) / 256.0 * blades;
        while (alpha < 255 && cumulative + bladesOfAlpha[alpha] < q)
            cumulative += bladesOfAlpha[alpha++];
        s.heightAtQuantile[k] = static_cast<float>(alpha) / 255.0f;
    }
    // Colour by height over the blade texels.
    std::array<glm::dvec3, BLADE_COLOR_BINS> sum{};
    std::array<double, BLADE_COLOR_BINS> count{};
    // A shell fragment shows the texture filtered over about a texel (bilinear between texel
    // centres): a blade texel's colour mixed with its neighbours', soil included. The blades take
    // that colour, so they match the shells they replace: the mean over blade texels of the
    // 3 x 3 tent filter (weights 1/4, 1/2, 1/4 each way, the mean of bilinear lookups spread
    // uniformly over the texel).
    const auto rgbAt = [&](int x, int y) {
        const size_t p =
            (static_cast<size_t>((y + n) % n) * n + static_cast<size_t>((x + n) % n)) * 4u;
        return glm::dvec3(level0.rgba[p], level0.rgba[p + 1], level0.rgba[p + 2]) / 255.0;
    };
    const double tent[3] = {0.25, 0.5, 0.25};
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const int a = alphaAt(x, y);
            if (a == 0) continue;
            glm::dvec3 filtered(0.0);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    filtered += tent[dx + 1] * tent[dy + 1] * rgbAt(x + dx, y + dy);
            const int bin = std::min(BLADE_COLOR_BINS - 1, (a - 1) * BLADE_COLOR_BINS / 255);
            sum[bin] += filtered;
            count[bin] += 1.0;
        }
    for (int b = 0; b < BLADE_COLOR_BINS; ++b) {
        int from = -1;
        for (int d = 0; d < BLADE_COLOR_BINS && from < 0; ++d) {
            if (b - d >= 0 && count[b - d] > 0.0)
                from = b - d;
            else if (b + d < BLADE_COLOR_BINS && count[b + d] > 0.0)
                from = b + d;
        }
        s.colorByHeight[b] = glm::vec3(sum[from] / count[from]);
    }
    return s;
}

bool planRegular(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m, glm::vec2& origin_m,
                 glm::vec2& spacing_m) {
    if (nx < 2 || ny < 2 || wsPosition_m.size() != static_cast<size_t>(nx) * ny) return false;
    const glm::vec3 o = wsPosition_m[0];
    const float dx = (wsPosition_m[static_cast<size_t>(nx) - 1].x - o.x) / float(nx - 1);
    const float dy = (wsPosition_m[static_cast<size_t>(ny - 1) * static_cast<size_t>(nx)].y - o.y) /
                     float(ny - 1);
    if (!(dx > 0.0f) || !(dy > 0.0f)) return false;
    const float tolerance = 1e-4f * std::min(dx, dy);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const glm::vec3& p = wsPosition_m[static_cast<size_t>(j) * nx + i];
            if (std::abs(p.x - (o.x + float(i) * dx)) > tolerance ||
                std::abs(p.y - (o.y + float(j) * dy)) > tolerance)
                return false;
        }
    origin_m = glm::vec2(o.x, o.y);
    spacing_m = glm::vec2(dx, dy);
    return true;
}

NearBladeSet placeNearBlades(const BladeGround& ground, const BladeStatistics& stats,
                             const BladeView& view) {
    NearBladeSet set;
    if (view.budget <= 0 || !(stats.bladesPerM2 > 0.0f) || !ground.planRegular ||
        ground.vertices == nullptr || ground.nx < 2 || ground.ny < 2)
        return set;
    const int nx = ground.nx, ny = ground.ny;
    const size_t vertexCount = static_cast<size_t>(nx) * static_cast<size_t>(ny);
    const auto pos = [&ground](size_t v) {
        const float* p = ground.vertices + v * ground.stride + ground.positionAt;
        return glm::vec3(p[0], p[1], p[2]);
    };
    const auto nor = [&ground](size_t v) {
        const float* p = ground.vertices + v * ground.stride + ground.normalAt;
        return glm::vec3(p[0], p[1], p[2]);
    };
    const auto keyLight = [&ground](size_t v) {
        return ground.keyLightAt < 0 ? 1.0f
                                     : ground.vertices[v * ground.stride + ground.keyLightAt];
    };
    const glm::vec2 o = ground.origin_m, h = ground.spacing_m;
    set.capRadius_m = stats.width_m * view.focal_px / MIN_BLADE_PX;
    const float cap = set.capRadius_m;

    // Quads in the frustum whose nearest point is within the cap, nearest first.
    struct Quad {
        float near_m;
        int i, j;
    };
    std::vector<Quad> quads;
    const glm::vec3 eye = view.wsEye_m;
    const int i0 = std::max(0, static_cast<int>(std::floor((eye.x - cap - o.x) / h.x)));
    const int i1 = std::min(nx - 2, static_cast<int>(std::floor((eye.x + cap - o.x) / h.x)));
    const int j0 = std::max(0, static_cast<int>(std::floor((eye.y - cap - o.y) / h.y)));
    const int j1 = std::min(ny - 2, static_cast<int>(std::floor((eye.y + cap - o.y) / h.y)));
    const auto at = [nx](int i, int j) { return static_cast<size_t>(j) * nx + i; };
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            glm::vec3 lo = pos(at(i, j)), hi = lo;
            for (const size_t v : {at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)}) {
                lo = glm::min(lo, pos(v));
                hi = glm::max(hi, pos(v));
            }
            const float near = distanceToBox(eye, lo, hi);
            if (near > cap) continue;
            // A bent blade reaches its height from its root in any direction.
            const glm::vec3 reach(view.grassHeight_m);
            if (!boxMayBeVisible(view.clipFromWorld, lo - reach, hi + reach)) continue;
            quads.push_back({near, i, j});
        }
    if (quads.empty()) return set;
    std::sort(quads.begin(), quads.end(), [](const Quad& a, const Quad& b) {
        return a.near_m != b.near_m ? a.near_m < b.near_m : (a.j != b.j ? a.j < b.j : a.i < b.i);
    });
    // Pass 1, candidates: the visible lattice blades, quads nearest first, until no quad left
    // can hold a blade nearer than the budget's farthest so far.
    struct Candidate {
        int32_t ci, cj;
        std::array<std::pair<size_t, float>, 3> weights;  // the root's triangle, barycentric
        glm::vec3 root;
        float d_m;
    };
    std::vector<Candidate> candidates;
    const float a = 1.0f / std::sqrt(stats.bladesPerM2);  // lattice spacing, metres
    const Frustum frustum(view.clipFromWorld);
    const float bladeRadius = 0.5f * view.grassHeight_m;
    // The budget's nearest distances so far (a max-heap): once it is full, its top is the
    // distance no later quad can beat once the quads' nearest points pass it.
    std::priority_queue<float> nearestD;
    const auto budget = static_cast<size_t>(view.budget);
    for (const Quad& q : quads) {
        if (nearestD.size() == budget && q.near_m >= nearestD.top()) break;
        const float qx0 = o.x + float(q.i) * h.x, qy0 = o.y + float(q.j) * h.y;
        const float qx1 = qx0 + h.x, qy1 = qy0 + h.y;
        const size_t v00 = at(q.i, q.j), v10 = at(q.i + 1, q.j), v01 = at(q.i, q.j + 1),
                     v11 = at(q.i + 1, q.j + 1);
        const auto c0 = static_cast<int32_t>(std::floor(qx0 / a)),
                   c1 = static_cast<int32_t>(std::floor(qx1 / a));
        const auto r0 = static_cast<int32_t>(std::floor(qy0 / a)),
                   r1 = static_cast<int32_t>(std::floor(qy1 / a));
        for (int32_t cj = r0; cj <= r1; ++cj)
            for (int32_t ci = c0; ci <= c1; ++ci) {
                const float px = (float(ci) + cellUniform(ci, cj, JITTER_X)) * a;
                const float py = (float(cj) + cellUniform(ci, cj, JITTER_Y)) * a;
                if (px < qx0 || px >= qx1 || py < qy0 || py >= qy1) continue;
                // The mesh's triangles (render/TerrainGrid.h): (v00, v10, v11) and
                // (v00, v11, v01), split along the v00-v11 diagonal.
                const float fx = (px - qx0) / h.x, fy = (py - qy0) / h.y;
                Candidate c{ci, cj,
                            fx >= fy ? std::array<std::pair<size_t, float>, 3>{{{v00, 1.0f - fx},
                                                                                {v10, fx - fy},
                                                                                {v11, fy}}}
                                     : std::array<std::pair<size_t, float>, 3>{{{v00, 1.0f - fy},
                                                                                {v11, fx},
                                                                                {v01, fy - fx}}},
                            glm::vec3(0.0f), 0.0f};
                for (const auto& [v, wt] : c.weights) c.root += wt * pos(v);
                c.root.x = px;
                c.root.y = py;
                c.d_m = glm::distance(c.root, eye);
                if (c.d_m > cap) continue;
                // The sphere around the standing blade holds it bent in any direction.
                const glm::vec3 centre = c.root + glm::vec3(0.0f, 0.0f, bladeRadius);
                if (!frustum.mayHoldSphere(centre, 2.0f * bladeRadius)) continue;
                if (nearestD.size() == budget) {
                    if (c.d_m >= nearestD.top()) continue;
                    nearestD.pop();
                }
                nearestD.push(c.d_m);
                candidates.push_back(c);
            }
    }
    if (candidates.empty()) return set;
    // R: the distance of the budget's farthest candidate (the cap when fewer are in view).
    float radius = cap;
    if (candidates.size() >= budget) {
        const auto last = candidates.begin() + static_cast<std::ptrdiff_t>(budget - 1);
        std::nth_element(candidates.begin(), last, candidates.end(),
                         [](const Candidate& x, const Candidate& y) { return x.d_m < y.d_m; });
        radius = std::max(last->d_m, 1e-3f);
    }
    set.radius_m = radius;
    float nearest = radius;
    for (const Candidate& c : candidates) nearest = std::min(nearest, c.d_m);
    const float inner = nearest + 0.7f * (radius - nearest);
    set.innerRadius_m = inner;
    // Nearest first: the early depth test then discards more of the blades behind.
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& x, const Candidate& y) { return x.d_m < y.d_m; });

    // Pass 2: thin towards R, apply the density map, describe each blade.
    const bool densityOn = ground.density != nullptr && ground.density->width > 0 &&
                           ground.densityCuts != nullptr && !ground.densityCuts->empty();
    const VertexWind* wind = ground.wind;
    const bool hasWind = wind != nullptr && wind->wsDirection.size() == vertexCount;
    const bool hasGroup = hasWind && wind->group.size() == vertexCount;
    const bool hasCoord = hasWind && wind->groupCoord.size() == vertexCount;
    const bool hasFlutter = hasWind && wind->flutter_rad.size() == vertexCount;
    for (const Candidate& c : candidates) {
        if (c.d_m > radius) break;
        const int32_t ci = c.ci, cj = c.cj;
        if (cellUniform(ci, cj, FADE_KEY) >= nearBladeFade(c.d_m, inner, radius)) continue;
        const float heightFrac = stats.heightAtQuantile[cellHash(ci, cj, HEIGHT) >> 24];
        if (densityOn) {
            // The shells' rule (shell.frag): a blade stays while its height is at or above the
            // cut of the map's density at its root.
            const DensityMap& m = *ground.density;
            const float u = (c.root.x - m.wsMin_m.x) / m.wsSize_m.x;
            const float vv = 1.0f - (c.root.y - m.wsMin_m.y) / m.wsSize_m.y;
            const int tx = std::clamp(static_cast<int>(u * float(m.width)), 0, m.width - 1);
            const int ty = std::clamp(static_cast<int>(vv * float(m.height)), 0, m.height - 1);
            const float dens = std::clamp(
                m.density[static_cast<size_t>(ty) * m.width + static_cast<size_t>(tx)], 0.0f, 1.0f);
            const std::vector<float>& cuts = *ground.densityCuts;
            const size_t k = std::min(
                cuts.size() - 1, static_cast<size_t>(std::lround(dens * float(cuts.size() - 1))));
            if (heightFrac < cuts[k]) continue;
        }
        BladeInstance b{};
        glm::vec3 n(0.0f), dir(0.0f);
        glm::vec2 coord(0.0f);
        float flutter = 0.0f, key = 0.0f;
        size_t closest = c.weights[0].first;  // the vertex of the largest weight
        float closestW = -1.0f;
        for (const auto& [v, wt] : c.weights) {
            n += wt * nor(v);
            if (hasWind) dir += wt * wind->wsDirection[v];
            if (hasCoord) coord += wt * wind->groupCoord[v];
            if (hasFlutter) flutter += wt * wind->flutter_rad[v];
            key += wt * keyLight(v);
            if (wt > closestW) {
                closestW = wt;
                closest = v;
            }
        }
        n = glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
        // The bend moves a blade along its tangent-plane wind: keep the direction's tangent
        // part, unit, so the blade keeps its length (render/Bend.h).
        dir -= glm::dot(dir, n) * n;
        dir = glm::length(dir) > 1e-4f ? glm::normalize(dir) : glm::vec3(0.0f);
        const float tint = 1.0f + BLADE_TINT_SPREAD * (2.0f * cellUniform(ci, cj, TINT) - 1.0f);
        const int bin = std::min(BLADE_COLOR_BINS - 1,
                                 std::max(0, static_cast<int>(std::ceil(heightFrac * 255.0f)) - 1) *
                                     BLADE_COLOR_BINS / 255);
        const glm::vec3 color = glm::min(stats.colorByHeight[bin] * tint, glm::vec3(1.0f));
        b.root[0] = c.root.x, b.root[1] = c.root.y, b.root[2] = c.root.z;
        b.normal[0] = n.x, b.normal[1] = n.y, b.normal[2] = n.z;
        b.blade[0] = heightFrac;
        b.blade[1] = stats.width_m * (0.75f + 0.5f * cellUniform(ci, cj, WIDTH));
        b.blade[2] = MAX_FACING_RAD * (2.0f * cellUniform(ci, cj, FACING) - 1.0f);
        b.blade[3] = 1.0f + BLADE_STIFFNESS_SPREAD * (2.0f * cellUniform(ci, cj, STIFFNESS) - 1.0f);
        b.windDir[0] = dir.x, b.windDir[1] = dir.y, b.windDir[2] = dir.z;
        b.group = hasGroup ? wind->group[closest] : 0u;
        b.groupCoord[0] = coord.x, b.groupCoord[1] = coord.y;
        b.flutter_rad = flutter;
        b.color[0] = color.x, b.color[1] = color.y, b.color[2] = color.z;
        b.color[3] = key;
        set.blades.push_back(b);
    }
    return set;
}

}  // namespace gale::render::detail

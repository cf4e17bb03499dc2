/// \file NearGround.cpp
/// The near-ground read plans (see NearGround.h).

#include "coupling/NearGround.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Interpolation.h"
#include "sim/SurfaceLayer.h"

namespace gale::coupling {
namespace {

// |(n - n_Q) S| (Frobenius) is capped here: the first-order law is meant for a gentle change
// between the wall and Q; at the foot of a cliff or on a needle the wind at Q is carried with at
// most a 50 % correction rather than an unbounded one.
constexpr double MAX_CURVATURE_CORRECTION = 0.5;
// Log law: the first cell centre used must stand at least this many cells above the ground; a
// centre closer to it sits in a sliver cut cell, the value the solver resolves worst.
constexpr double MIN_LOG_CENTRE_CELLS = 0.25;
// The ground's normal and curvature are differenced this many cells apart: wide enough to see the
// terrain the solver resolves, narrow enough that a vertex beside a cliff does not see the cliff.
constexpr double FRAME_DIFFERENCE_CELLS = 0.5;
// Fixed-point steps towards the foot of the normal through the grass point: each shrinks the
// offset by the factor n_P / (radius of curvature), so three leave it far below a millimetre.
constexpr int FOOT_STEPS = 3;
// The readings must fix the model's unknowns: |det| of the reading matrix at least this fraction
// of its flat-ground value n_w (over a slope it is about n_w N_z^2; 0.1 admits slopes up to ~72
// degrees).
constexpr double MIN_READING_DETERMINANT = 0.1;
// A map entry larger than this amplifies reading errors more than any well-posed read would.
constexpr double MAX_MAP_ENTRY = 4.0;

constexpr unsigned UV = sim::WindField::COMPONENT_U | sim::WindField::COMPONENT_V;
constexpr unsigned W = sim::WindField::COMPONENT_W;

// The unit normal from the four heights h(x +- delta, y) and h(x, y +- delta).
glm::dvec3 normalFrom(double hE, double hW, double hN, double hS, double delta_m) {
    const double hx = (hE - hW) / (2.0 * delta_m);
    const double hy = (hN - hS) / (2.0 * delta_m);
    return glm::normalize(glm::dvec3(-hx, -hy, 1.0));
}

// Heightfield::sample split by axis: a coordinate's lattice cell and fraction, found once per
// distinct x or y and shared by every height on that line (the final frame's 17 heights need 14
// conversions instead of 34, each foot step's 5 heights 6 instead of 10). The arithmetic is
// Heightfield::sample's, step for step, so each height is bit for bit the one it returns.
struct LatticeCoord {
    int i;
    double t;
};

LatticeCoord latticeX(const sim::Heightfield& h, double wsX_m) {
    const double f = std::clamp((wsX_m - h.originX_m) / h.spacing_m, 0.0, double(h.nx - 1));
    const int i = std::min(static_cast<int>(f), h.nx - 2);
    return {i, f - i};
}

LatticeCoord latticeY(const sim::Heightfield& h, double wsY_m) {
    const double f = std::clamp((wsY_m - h.originY_m) / h.spacing_m, 0.0, double(h.ny - 1));
    const int j = std::min(static_cast<int>(f), h.ny - 2);
    return {j, f - j};
}

double heightAt(const sim::Heightfield& h, const LatticeCoord& x, const LatticeCoord& y) {
    return sim::bilinearWeighted<double>(h.at(x.i, y.i), h.at(x.i + 1, y.i), h.at(x.i, y.i + 1),
                                         h.at(x.i + 1, y.i + 1), x.t, y.t);
}

// The ground at (x, y): its height and its unit normal from the heights `delta_m` away along x
// and y, with the lattice coordinates of x, y and x, y +- delta_m kept for the shape operator.
struct GroundPoint {
    double x, y, z;
    glm::dvec3 n;
    LatticeCoord cx, cy, east, west, north, south;
};

GroundPoint groundAt(const sim::Heightfield& t, double x, double y, double delta_m) {
    GroundPoint g{x,
                  y,
                  0.0,
                  {},
                  latticeX(t, x),
                  latticeY(t, y),
                  latticeX(t, x + delta_m),
                  latticeX(t, x - delta_m),
                  latticeY(t, y + delta_m),
                  latticeY(t, y - delta_m)};
    g.z = heightAt(t, g.cx, g.cy);
    g.n = normalFrom(heightAt(t, g.east, g.cy), heightAt(t, g.west, g.cy),
                     heightAt(t, g.cx, g.north), heightAt(t, g.cx, g.south), delta_m);
    return g;
}

// The shape operator S of the ground at g: dN along the surface, as a symmetric 3 x 3 acting on
// tangent vectors and taking N to 0, by central differences `delta_m` apart (g made with the same
// delta_m).
glm::dmat3 shapeOperator(const sim::Heightfield& t, const GroundPoint& g, double delta_m) {
    // The normals at (x +- delta, y) and (x, y +- delta), each from its four neighbours; the
    // four diagonal heights are shared by two normals each.
    const double x = g.x, y = g.y, xE = x + delta_m, xW = x - delta_m, yN = y + delta_m,
                 yS = y - delta_m;
    const double hNE = heightAt(t, g.east, g.north), hSE = heightAt(t, g.east, g.south);
    const double hNW = heightAt(t, g.west, g.north), hSW = heightAt(t, g.west, g.south);
    const glm::dvec3 nE =
        normalFrom(heightAt(t, latticeX(t, xE + delta_m), g.cy),
                   heightAt(t, latticeX(t, xE - delta_m), g.cy), hNE, hSE, delta_m);
    const glm::dvec3 nW =
        normalFrom(heightAt(t, latticeX(t, xW + delta_m), g.cy),
                   heightAt(t, latticeX(t, xW - delta_m), g.cy), hNW, hSW, delta_m);
    const glm::dvec3 nN = normalFrom(hNE, hNW, heightAt(t, g.cx, latticeY(t, yN + delta_m)),
                                     heightAt(t, g.cx, latticeY(t, yN - delta_m)), delta_m);
    const glm::dvec3 nS = normalFrom(hSE, hSW, heightAt(t, g.cx, latticeY(t, yS + delta_m)),
                                     heightAt(t, g.cx, latticeY(t, yS - delta_m)), delta_m);
    const glm::dvec3 dNdx = (nE - nW) / (2.0 * delta_m);
    const glm::dvec3 dNdy = (nN - nS) / (2.0 * delta_m);
    const glm::dvec3& n = g.n;
    // A tangent vector w = a (1, 0, h_x) + b (0, 1, h_y) has a = w.x, b = w.y and S w = a dN/dx +
    // b dN/dy; for any w, S w = S (w - (w.N) N). So S = [dN/dx dN/dy] [e_x e_y]^T (I - N N^T).
    const glm::dmat3 tangent = glm::dmat3(1.0) - glm::outerProduct(n, n);
    glm::dmat3 s(0.0);
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
            s[col][row] = dNdx[row] * tangent[col][0] + dNdy[row] * tangent[col][1];
    return 0.5 *
           (s + glm::transpose(s));  // self-adjoint; the differences make it so only to rounding
}

double frobenius(const glm::dmat3& m) {
    double s = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) s += m[c][r] * m[c][r];
    return std::sqrt(s);
}

std::array<float, 9> pack(const glm::dmat3& m) {  // glm is column-major: m[col][row]
    std::array<float, 9> a{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a[size_t(3 * r + c)] = float(m[c][r]);
    return a;
}

NearGroundRead asItIs(const glm::dvec3& p) {
    return {glm::vec3(p), glm::vec3(p), pack(glm::dmat3(1.0))};
}

// The solved-face test from the kept flags when there are some, else from the field.
bool readsOnlySolved(const sim::WindField& field, const SolvedFaces* faces, const glm::dvec3& q,
                     unsigned components) {
    return faces ? faces->readsOnlySolvedFaces(q.x, q.y, q.z, components)
                 : field.readsOnlySolvedFaces(q.x, q.y, q.z, components);
}

bool solvedAt(const sim::WindField& field, const SolvedFaces* faces, const glm::dvec3& q,
              unsigned components) {
    // The cheaper test first: with kept flags the faces (a few byte reads), else the ground (one
    // terrain sample against one per face).
    if (faces)
        return faces->readsOnlySolvedFaces(q.x, q.y, q.z, components) &&
               !field.belowTerrain(q.x, q.y, q.z);
    return !field.belowTerrain(q.x, q.y, q.z) &&
           field.readsOnlySolvedFaces(q.x, q.y, q.z, components);
}

// The lowest s in [0, NEAR_GROUND_SEARCH_CELLS cells], to an eighth of a cell, at which p + s dir
// reads only solved faces for `components`; negative when there is none. Coarse steps of half a
// cell, then two halvings back down (the stencils only gain solved faces as they rise, within a
// cell).
double lowestSolved(const sim::WindField& field, const SolvedFaces* faces, const glm::dvec3& p,
                    const glm::dvec3& dir, unsigned components) {
    // The cell here: the voxel size, or on stretched layers the (thinner) layer at p.
    const sim::GridLayout& g = field.layout();
    const int layer = int(std::clamp(std::floor(g.isZFromWs(p.z)), 0.0, double(g.nz - 1)));
    const double h = std::min(field.voxelSize_m(), g.dz_m(layer));
    if (solvedAt(field, faces, p, components)) return 0.0;
    for (int step = 1; step <= 2 * NEAR_GROUND_SEARCH_CELLS; ++step) {
        double s = 0.5 * step * h;
        if (!solvedAt(field, faces, p + s * dir, components)) continue;
        for (double back : {0.25 * h, 0.125 * h})
            if (solvedAt(field, faces, p + (s - back) * dir, components)) s -= back;
        return s;
    }
    return -1.0;
}

// The linear map from the readings to V(n_P) for V(n) = T(n) + beta g(n) N, with T(n_W) = G T(n_Q)
// and T(n_P) = C T(n_Q) the near-wall law's carries from Q and g the normal wind's growth from the
// wall (gQ = g(n_Q) etc.). Unknowns: T(n_Q) = a t1 + b t2 and beta;
//   u = e_x . (T + beta gQ N),  v = e_y . (T + beta gQ N),  w = e_z . (G T + beta gW N).
// False when the readings do not fix the unknowns well (a near-vertical wall, where u and v no
// longer tell the tangential wind from the normal one).
bool readingMap(const glm::dvec3& n, const glm::dmat3& G, const glm::dmat3& C, double gQ, double gW,
                double gP, glm::dmat3& out) {
    const glm::dvec3 ref = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t1 = glm::normalize(ref - glm::dot(ref, n) * n), t2 = glm::cross(n, t1);
    const glm::dvec3 gt1 = G * t1, gt2 = G * t2;
    glm::dmat3 B;  // rows: readings; columns: a, b, beta (glm: B[col][row])
    B[0] = glm::dvec3(t1.x, t1.y, gt1.z);
    B[1] = glm::dvec3(t2.x, t2.y, gt2.z);
    B[2] = glm::dvec3(gQ * n.x, gQ * n.y, gW * n.z);
    if (!(gW > 0.0 && std::abs(glm::determinant(B)) >= MIN_READING_DETERMINANT * gW)) return false;
    glm::dmat3 Cfull;
    Cfull[0] = C * t1;
    Cfull[1] = C * t2;
    Cfull[2] = gP * n;
    out = Cfull * glm::inverse(B);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!(std::abs(out[c][r]) <= MAX_MAP_ENTRY)) return false;
    return true;
}

// Mass-consistent: Q and Q' on the normal; T carried by T(n) = (I - (n - n_Q) S) T(n_Q).
NearGroundRead tangentialRead(const sim::WindField& field, const SolvedFaces* faces,
                              const sim::Heightfield& t, const glm::dvec3& p) {
    const double delta = FRAME_DIFFERENCE_CELLS * field.voxelSize_m();
    // The foot F of the normal through P (not the ground straight below P: on a slope that point's
    // normal misses P, and the wall condition would be applied along a tilted line). Found by
    // fixed-point steps from the point below, each a correction of order (n_P / radius)^2.
    GroundPoint ground = groundAt(t, p.x, p.y, delta);
    for (int step = 0; step < FOOT_STEPS; ++step) {
        const double dist = glm::dot(p - glm::dvec3(ground.x, ground.y, ground.z), ground.n);
        ground = groundAt(t, p.x - dist * ground.n.x, p.y - dist * ground.n.y, delta);
    }
    const glm::dvec3 foot(ground.x, ground.y, ground.z), n = ground.n;
    const double nP = std::max(0.0, glm::dot(p - foot, n));
    const double sUV = lowestSolved(field, faces, p, n, UV),
                 sW = lowestSolved(field, faces, p, n, W);
    if (sUV < 0.0 || sW < 0.0) return asItIs(p);
    glm::dmat3 shape = shapeOperator(t, ground, delta);
    const double reach = std::max(nP + sUV, nP + sW) * frobenius(shape);
    if (!(reach <= MAX_CURVATURE_CORRECTION))
        shape *= reach > 0.0 ? MAX_CURVATURE_CORRECTION / reach : 0.0;
    const glm::dmat3 I(1.0);
    // The normal wind: the flux through the parallel surface at distance n, whose area grows as
    // det(I + n S), fed by the tangential divergence: u_n(n) = beta n / det(I + n S) to first order
    // in the curvature (exact where it is the same in every direction).
    auto normalGrowth = [&](double dist) { return dist / glm::determinant(I + dist * shape); };
    glm::dmat3 a;
    if (!readingMap(n, I - (sW - sUV) * shape, I + sUV * shape, normalGrowth(nP + sUV),
                    normalGrowth(nP + sW), normalGrowth(nP), a))
        return asItIs(p);
    // w is read straight above Q where its faces are solved there, at the normal distance it would
    // have on the normal (the step then shares u's and v's horizontal stencils); the offset along
    // the ground, (s_W - s_UV) tan(slope), is left out of the model (on the hemisphere's cap it
    // changed the error by less than 0.01 %).
    const glm::dvec3 q = p + sUV * n, above = q + glm::dvec3(0.0, 0.0, (sW - sUV) / n.z);
    if (sW >= sUV && solvedAt(field, faces, above, W))
        return {glm::vec3(q), glm::vec3(above), pack(a)};
    return {glm::vec3(q), glm::vec3(p + sW * n), pack(a)};
}

// The lowest air layer of the cell column over (x, y) (world metres), -1 when the column has no
// air or the point lies outside the box.
int firstAirLayer(const sim::WindField& field, double x, double y) {
    const double h = field.voxelSize_m();
    const auto o = field.wsMin_m();
    const int i = int(std::floor((x - o[0]) / h)), j = int(std::floor((y - o[1]) / h));
    if (i < 0 || j < 0 || i >= field.nx() || j >= field.ny()) return -1;
    for (int k = 0; k < field.nz(); ++k)
        if (field.isAir(i, j, k)) return k;
    return -1;
}

// Momentum with wall stress: Q at the lowest solved cell centre straight above P at least
// MIN_LOG_CENTRE_CELLS above the ground, Q' straight above P; T carried by the log law. The
// height the log law gives Q's reading is where the solver holds it: a layer's centre above the
// ground, except in the column's first open layer, whose faces the wall function reads at the
// centroid of their open part (sim::surface::wallSampleHeight_m, the solver's own definition):
// reading a cut first cell as if its value sat at its centre, lower than the centroid, carried it
// down to the grass 2-34 % too fast.
NearGroundRead logLawRead(const sim::WindField& field, const SolvedFaces* faces,
                          const sim::Heightfield& t, const glm::dvec3& p,
                          const NearGround& nearGround) {
    const double h = field.voxelSize_m();
    const sim::GridLayout& g = field.layout();
    const GroundPoint below = groundAt(t, p.x, p.y, FRAME_DIFFERENCE_CELLS * h);
    const double ground = below.z, zP = std::max(0.0, p.z - ground);
    const glm::dvec3 n = below.n, up(0.0, 0.0, 1.0);
    const double z0 = nearGround.roughness_m, d = nearGround.displacement_m;
    const double sW = lowestSolved(field, faces, p, up, W);
    if (sW < 0.0) return asItIs(p);
    const double lowest =
        std::max(MIN_LOG_CENTRE_CELLS * h, sim::surface::lowestLogHeight_m(z0, d));
    const int first = int(std::clamp(std::ceil(g.isZFromWs(p.z) - 0.5), 0.0, double(field.nz())));
    const int wallLayer = firstAirLayer(field, p.x, p.y);
    for (int k = first; k <= first + NEAR_GROUND_SEARCH_CELLS && k < field.nz(); ++k) {
        const glm::dvec3 q(p.x, p.y, g.zCentre_m(k));
        if (q.z - ground < lowest || !solvedAt(field, faces, q, UV)) continue;
        const double zQ =
            k == wallLayer ? sim::surface::wallSampleHeight_m(g.zFace_m(k + 1) - ground, g.dz_m(k))
                           : q.z - ground;
        auto carry = [&](double z) { return sim::surface::logLawRescale_mps(1.0, z, zQ, z0, d); };
        glm::dmat3 a;
        if (!readingMap(n, carry(zP + sW) * glm::dmat3(1.0), carry(zP) * glm::dmat3(1.0), zQ,
                        zP + sW, zP, a))
            return asItIs(p);
        return {glm::vec3(q), glm::vec3(p + sW * up), pack(a)};
    }
    return asItIs(p);
}

// planNearGroundRead, with the solved-face test from `faces` when not null.
NearGroundRead planRead(const sim::WindField& field, const SolvedFaces* faces, const glm::dvec3& p,
                        const NearGround& nearGround) {
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
        return asItIs(p);  // reads zero
    if (field.belowTerrain(p.x, p.y, p.z)) return {glm::vec3(p), glm::vec3(p), {}};
    const sim::Heightfield* terrain = field.terrain();
    if (nearGround.model == NearGroundModel::Interpolated || !terrain) return asItIs(p);
    // Inside the roughness layer the log law's wind is zero, whatever the field holds.
    if (nearGround.model == NearGroundModel::LogLaw &&
        p.z - terrain->sample(p.x, p.y) <= nearGround.displacement_m + nearGround.roughness_m)
        return {glm::vec3(p), glm::vec3(p), {}};
    if (readsOnlySolved(field, faces, p, sim::WindField::ALL_COMPONENTS)) return asItIs(p);
    if (nearGround.model == NearGroundModel::LogLaw)
        return logLawRead(field, faces, *terrain, p, nearGround);
    return tangentialRead(field, faces, *terrain, p);
}

}  // namespace

void validate(const NearGround& g) {
    if (!std::isfinite(g.roughness_m) || g.roughness_m <= 0.0)
        throw ParameterError("wind.roughness_m", formatG(g.roughness_m),
                             "must be > 0 m and finite");
    if (!std::isfinite(g.displacement_m) || g.displacement_m < 0.0)
        throw ParameterError("solver.displacement_height_m", formatG(g.displacement_m),
                             "must be >= 0 m and finite");
}

namespace {

// The face layers SolvedFaces keeps for `axis`: up to two above the terrain's highest sample
// (higher faces are never cut by it); none without terrain (the field's own test is cheap there).
int keptLayers(const sim::WindField& field, int axis) {
    const sim::GridLayout& g = field.layout();
    const sim::Heightfield* t = field.terrain();
    if (g.nx == 0 || !t || t->height_m.empty()) return 0;
    const double top_m = *std::max_element(t->height_m.begin(), t->height_m.end());
    const double layer = std::clamp(std::floor(g.isZFromWs(top_m)), 0.0, double(g.nz));
    return std::min(g.dims(sim::Placement(axis))[2], int(layer) + 3);
}

}  // namespace

size_t SolvedFaces::keptFaceCount(const sim::WindField& field) {
    size_t count = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const auto d = field.layout().dims(sim::Placement(axis));
        count += size_t(d[0]) * size_t(d[1]) * size_t(keptLayers(field, axis));
    }
    return count;
}

SolvedFaces::SolvedFaces(const sim::WindField& field) : mField(field) {
    const sim::GridLayout& g = field.layout();
    for (int axis = 0; axis < 3; ++axis) {
        const auto d = g.dims(sim::Placement(axis));
        mLayers[axis] = keptLayers(field, axis);
        mSolved[axis].resize(size_t(d[0]) * size_t(d[1]) * size_t(mLayers[axis]));
        uint8_t* out = mSolved[axis].data();
        tbb::parallel_for(0, mLayers[axis], [&, axis, out](int k) {
            for (int j = 0; j < d[1]; ++j)
                for (int i = 0; i < d[0]; ++i)
                    out[size_t(i) + size_t(d[0]) * (size_t(j) + size_t(d[1]) * size_t(k))] =
                        field.isSolvedFace(axis, i, j, k) ? 1 : 0;
        });
    }
}

bool SolvedFaces::solved(int axis, int i, int j, int k) const {
    if (k >= mLayers[axis]) return mField.isSolvedFace(axis, i, j, k);
    const auto d = mField.layout().dims(sim::Placement(axis));
    return mSolved[axis][size_t(i) + size_t(d[0]) * (size_t(j) + size_t(d[1]) * size_t(k))] != 0;
}

bool SolvedFaces::readsOnlySolvedFaces(double x, double y, double z, unsigned components) const {
    // WindField::readsOnlySolvedFaces, step for step, with isSolvedFace from the kept flags.
    const sim::GridLayout& g = mField.layout();
    if (g.nx == 0) return false;
    const sim::Vec3d is = g.isFromWs({x, y, z});
    if (!g.containsIs(is)) return false;
    if ((components & UV) && !(is[2] >= 0.5 && is[2] <= g.nz - 0.5)) return false;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(components & (1u << axis))) continue;
        const sim::AxisStencil a = g.stencil(0, axis == 0, is[0]);
        const sim::AxisStencil b = g.stencil(1, axis == 1, is[1]);
        const sim::AxisStencil c = g.stencil(2, axis == 2, is[2]);
        for (int k : {c.i0, c.i1})
            for (int j : {b.i0, b.i1})
                for (int i : {a.i0, a.i1})
                    if (!solved(axis, i, j, k)) return false;
    }
    return true;
}

NearGroundRead planNearGroundRead(const sim::WindField& field, const glm::dvec3& p,
                                  const NearGround& nearGround) {
    return planRead(field, nullptr, p, nearGround);
}

NearGroundRead planNearGroundRead(const SolvedFaces& solved, const glm::dvec3& p,
                                  const NearGround& nearGround) {
    return planRead(solved.field(), &solved, p, nearGround);
}

}  // namespace gale::coupling

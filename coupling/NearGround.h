#pragma once
/// \file NearGround.h
/// What the grass reads between the ground and the lowest faces where a solved field holds solved
/// values (docs/coupling.md, "Near the ground").
///
/// Grass lives 0.25-1 m above the ground, usually below the first cell centre. There the field's
/// trilinear interpolation reads faces that the terrain closes, and those hold values copied from
/// the faces above (sim/FaceExtrapolation.h), not the flow; cut faces whose centre lies under the
/// ground carry the flux through their open sliver, not the flow at their centre. Instead, each
/// component is read where every face its interpolation stencil reads is solved (it carries flux
/// and its centre is in the air; WindField::isSolvedFace): u and v at Q, w at Q' (w's faces are
/// solved only higher up: a cut cell's bottom face is closed). A model of the velocity between
/// the ground and those points,
///
///   V(n) = T(n) + beta n N,   n the distance from the ground, N the ground's unit normal,
///
/// a tangential wind T and a normal wind growing linearly from zero at the wall (the wall is
/// impermeable in both models), is fixed by the three readings (T at Q: two components; beta) and
/// gives the velocity at the grass point P as a fixed linear map of them:
///
///   u(P) = A (u(Q), v(Q), w(Q')),   A 3 x 3, made once per field geometry and kept.
///
/// How T changes between the wall and Q is the model's near-wall law:
/// - Mass-consistent (free slip, potential flow): Q lies on the normal through P, Q' on it too or,
///   where w's faces are solved there, straight above Q at the same distance from the ground. An
///   irrotational flow with u.N = 0 on the wall has dT/dn = -S T there, S the shape operator of
///   the ground (the derivative of N along the surface): differentiate u.N = 0 along the wall, then
///   swap the derivatives by the symmetry of grad u that curl u = 0 gives (docs/coupling.md writes
///   it out). So to first order T(n) = (I - (n - n_Q) S) T(n_Q): over flat ground the tangential
///   wind is constant with height, over a crest (S > 0) it grows towards the ground. |(n - n_Q) S|
///   is capped, for cliffs and needles.
/// - Momentum model with wall stress: the neutral log law (sim/SurfaceLayer.h), T(z) proportional
///   to ln((z - d)/z0), z0 and d the scene's roughness length and displacement height, heights
///   above the local ground standing in for n; zero at and below z0 + d. Q is the lowest solved
///   cell centre straight above P (the first cell, where the model's wall function holds), Q'
///   straight above P too.
/// - Interpolated: the field's trilinear interpolation as it stands (what the grass read before;
///   kept for comparisons and for OpenVDB's sampler, which reads the same faces).
///
/// A point whose own stencils are solved is read as it is (A = I) in every model; a point below
/// the terrain, or (log law) at or below z0 + d, reads zero (A = 0). The ground's normal and
/// curvature come from the field's own terrain (the heightfield the solver cut its cells with), by
/// central differences half a cell apart.

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "sim/WindField.h"

namespace gale::coupling {

enum class NearGroundModel {
    Interpolated,  ///< the field's trilinear interpolation as it stands
    Tangential,    ///< mass-consistent, free slip: tangential wind, curvature-corrected
    LogLaw,        ///< momentum with wall stress: the neutral log law below the first cell centre
};

/// The near-ground treatment of a GrassSampler: which model made the field, and for the log law
/// the ground's roughness.
struct NearGround {
    NearGroundModel model = NearGroundModel::Tangential;
    double roughness_m = 0.03;    ///< z0, metres (LogLaw): > 0 and finite (wind.roughness_m)
    double displacement_m = 0.0;  ///< d, metres (LogLaw): >= 0 and finite (wind.displacement_m)
};

/// Throws gale::ParameterError naming wind.roughness_m or solver.displacement_height_m when the
/// log-law parameters are out of range (checked for every model, so a scene's mistake shows at
/// once).
void validate(const NearGround& nearGround);

/// How one point is read: u and v interpolated at wsUV_m, w at wsW_m (world metres), and
/// u(P) = A (u, v, w) with `map` = A (row-major, dimensionless).
struct NearGroundRead {
    glm::vec3 wsUV_m{0.0f};
    glm::vec3 wsW_m{0.0f};
    std::array<float, 9> map{};
};

/// Which faces of a field geometry are solved (WindField::isSolvedFace), one byte per face in the
/// layers the terrain reaches into (up to two layers above its highest point; faces higher up are
/// asked of the field). Made once per geometry so that planning many points does not test the air
/// flags and the ground again for each of the 24 faces of every candidate point. Multithreaded;
/// O(faces in those layers). Keeps a reference to `field`, which must outlive it.
class SolvedFaces {
  public:
    explicit SolvedFaces(const sim::WindField& field);
    /// How many faces SolvedFaces(field) would test and keep (its cost), without making them.
    static size_t keptFaceCount(const sim::WindField& field);
    /// As field.readsOnlySolvedFaces(wsX_m, wsY_m, wsZ_m, components) (world metres), from the
    /// kept flags.
    bool readsOnlySolvedFaces(double wsX_m, double wsY_m, double wsZ_m,
                              unsigned components = sim::WindField::ALL_COMPONENTS) const;
    const sim::WindField& field() const { return mField; }

  private:
    bool solved(int axis, int i, int j, int k) const;
    const sim::WindField& mField;
    int mLayers[3] = {0, 0, 0};       // face layers k < mLayers[axis] are kept
    std::vector<uint8_t> mSolved[3];  // per axis, the face grid's index order
};

/// The read for world point wsPoint_m (metres) in `field`'s geometry; depends on the field's
/// cells, air flags and terrain only, not on its velocities. Read as it is (A = I) in the
/// Interpolated model, in a field without terrain, where the point's own stencils are solved, or
/// where no solved point lies within NEAR_GROUND_SEARCH_CELLS cells of it. Never NaN for finite
/// input. Requires a validated `nearGround`.
NearGroundRead planNearGroundRead(const sim::WindField& field, const glm::dvec3& wsPoint_m,
                                  const NearGround& nearGround);
/// The same read from the solved faces' kept flags (for many points of one geometry): the same
/// result as planNearGroundRead(solved.field(), wsPoint_m, nearGround), faster.
NearGroundRead planNearGroundRead(const SolvedFaces& solved, const glm::dvec3& wsPoint_m,
                                  const NearGround& nearGround);

/// How far (cells) the read points may lie from P before the sampler gives up and reads P.
constexpr int NEAR_GROUND_SEARCH_CELLS = 4;

/// A v for a NearGroundRead's map (row-major).
inline glm::vec3 applyNearGroundMap(const std::array<float, 9>& a, const glm::vec3& v) {
    return {a[0] * v.x + a[1] * v.y + a[2] * v.z, a[3] * v.x + a[4] * v.y + a[5] * v.z,
            a[6] * v.x + a[7] * v.y + a[8] * v.z};
}

}  // namespace gale::coupling

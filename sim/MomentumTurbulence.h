#pragma once
/// \file MomentumTurbulence.h
/// The Reynolds stresses of gale's momentum models: a mixing-length eddy viscosity and a log-law
/// wall stress on the AirDomain's MAC grid, applied as one implicit step. Used by the unsteady
/// solver (UnsteadySettings::surfaceLayer) and therefore by the steady momentum model, which is
/// the unsteady solver driven to a steady state (sim/MomentumWind.h).
///
/// Closure (Prandtl's mixing length with Blackadar's 1962 length, sim/SurfaceLayer.h):
///   nu_t = nu + l^2 |S|,  |S| = sqrt(2 S_ij S_ij),  l = kappa z / (1 + kappa z / l_max),
/// z the height above the local ground (minus the displacement height d). nu_t lives on the
/// horizontal (z) faces of the cells, where the dominant vertical shear du/dz, dv/dz is a plain
/// difference of two face velocities; kappa z is replaced there by the discrete length of
/// surface::discreteMixingLength_m, so a sampled log profile carries exactly u*^2.
///
/// Stress divergence, per velocity component, in Laplacian form d/dx_j (nu_t du_i/dx_j) (the
/// transposed part nu_t du_j/dx_i, which vanishes for constant nu_t in incompressible flow, is
/// left out). One step of length dt treats each vertical column of faces implicitly (a
/// tridiagonal solve: backward Euler in z, the direction of the stiff near-ground terms) and the
/// horizontal neighbours point-implicitly (their values from the start of the step, the own value
/// at the end):
///   (u' - u) / dt = [tau_top - tau_bottom] / Delta + sum_nb nu_nb (u_nb - u') / h^2 + F.
/// Every new value is a weighted mean of old ones plus the force: bounded for any nu_t and dt
/// (an M-matrix), and a fixed point of the step solves the steady stress balance exactly.
///
/// Wall (the lowest open face of each column of x- and y-faces): the log-law wall function of
/// sim/SurfaceLayer.h, u*^2 = [kappa |U_t| / ln((z_p - d) / z0)]^2 along the horizontal velocity
/// U_t of the face, z_p the centroid of the face's open part above the ground, implicit in u
/// (tau_bottom = C |U_t| u', a drag that can only slow the face). Delta, the face's
/// control-volume height, is the layer's thickness above the wall (h on cubic cells) and the open
/// height of the face at the wall, clamped to [0.05, 1.5] times that layer's thickness.
/// Vertical velocity: no stress at the ground (the normal velocity is the projection's).
///
/// Stretched layers (GridLayout level heights): the same finite-volume balance with variable
/// spacing (Patankar 1980). x- and y-faces sit at layer centres and own their layer (dz_k), w
/// sits on the levels and owns the span between the two centres it separates
/// (GridLayout::centreGap_m); the vertical gradients (the stress through an edge, du/dz in |S|)
/// divide by the distance between the two samples. The discrete mixing length on a z-face uses
/// the two adjacent centres at their own (unequal) distances, and the balance force and top
/// stress are the discrete divergence of the log profile sampled at the layer centres, so flat
/// ground keeps the ambient profile exactly on layers too. On layers all h thick every quantity
/// is the cubic one.
///
/// Top (face above the last row): a prescribed shear stress, the ambient profile's (Richards and
/// Hoxey 1993 drive their boundary layer by a top shear stress in the same way), so the top can
/// speed up over a hill. Equilibrium: with the balanced ambient wind set
/// (SurfaceLayerSettings::balanced), a body force F(z) along the wind equal to minus the discrete
/// stress divergence of that ambient log profile over flat ground at the face's height: the force
/// that holds the undisturbed surface layer steady where Blackadar's l falls below kappa z (a
/// stand-in for the large-scale pressure gradient that drives the real boundary layer). Over
/// flat ground the ambient profile is then an exact steady state of the scheme; the force is
/// small (about 2 u*^2 kappa / l_max aloft).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/SurfaceLayer.h"

namespace gale::sim {

class TwoEquationTransport;

/// Throws ParameterError naming solver.displacement_height_m (m, must be >= 0) or
/// solver.mixing_length_max_m (m, must be > 0), each finite: the checks both the momentum model and
/// the surface-layer stresses need.
void validateWallAndMixing(double displacementHeight_m, double mixingLengthMax_m);

/// The turbulence closure of the surface-layer stresses (scene key solver.turbulence).
enum class TurbulenceClosure {
    /// Prandtl's mixing length with Blackadar's (1962) length and the balance force of the
    /// ambient profile (the file comment).
    MixingLength,
    /// The standard k-epsilon model (Launder and Spalding 1974) with Richards and Hoxey's (1993)
    /// inflow and rough-wall functions: transported k and epsilon on the cells, no balance force.
    KEpsilon,
    /// Menter's (1994) k-omega SST model with the same inflow, top and wall functions: k-omega
    /// near the ground, k-epsilon away from it, and the eddy viscosity limited where the shear
    /// stress would exceed a1 k (sim/TwoEquation.h).
    KOmegaSst,
};

/// true for the closures that transport k (sim/TwoEquation.h).
inline bool isTwoEquation(TurbulenceClosure c) { return c != TurbulenceClosure::MixingLength; }

/// "mixing_length", "k_epsilon", "k_omega_sst" and back; fromName throws gale::ParameterError
/// (solver.turbulence) listing the valid names.
const char* turbulenceClosureName(TurbulenceClosure c);
TurbulenceClosure turbulenceClosureFromName(const std::string& name);

struct SurfaceLayerSettings {
    bool enabled = false;  ///< false: no eddy viscosity, no wall stress
    TurbulenceClosure closure = TurbulenceClosure::MixingLength;
    double roughness_m = 0.03;  ///< aerodynamic roughness length z0, metres, > 0
    double displacementHeight_m =
        0.0;  ///< displacement height d (about 2/3 of tall grass), m, >= 0
    double mixingLengthMax_m = surface::BLACKADAR_MAX_MIXING_LENGTH_M;  ///< l_max, metres, > 0
    /// The ambient wind whose log profile (with roughness_m and displacementHeight_m; the wind's
    /// own profile and roughness are not used) is held in equilibrium by the top stress and the
    /// body force. Unset: a stress-free top and no force.
    std::optional<AmbientWind> balanced;
    /// Diagnostics (no scene key reaches them; docs/validation.md, the crest experiments):
    /// false turns the mixing-length eddy viscosity off (nu_t = the molecular viscosity) or the
    /// wall function's drag off (a free-slip ground). validate() throws std::logic_error for the
    /// wall stress without the eddy viscosity, or either off with a balanced profile.
    bool eddyViscosity = true;
    bool wallStress = true;

    /// Throws gale::ParameterError naming the scene key (wind.roughness_m, ...).
    void validate() const;
};

/// What one stress step did.
struct TurbulenceReport {
    double maxEddyViscosity_m2ps = 0;  ///< largest nu_t over the air, m^2/s
    double maxFrictionVelocity_mps =
        0;  ///< largest wall-function u* over wall faces >= h/2 high, m/s
};

/// The stress step on one domain. Geometry (ground heights, wall faces, mixing lengths, the
/// balance force) is computed once in the constructor. Keeps a reference to the domain, which
/// must outlive it, and copies of the masks.
class TurbulentStress {
  public:
    /// masks: the faces of u, v, w that are unknowns (between air cells or on the box), as the
    /// unsteady solver's projection uses them. molecularViscosity_m2ps (>= 0) is added to nu_t.
    /// Throws gale::ParameterError on bad settings, std::logic_error on mask sizes.
    TurbulentStress(const AirDomain& domain, const SurfaceLayerSettings& settings,
                    double molecularViscosity_m2ps, const std::vector<uint8_t>& okX,
                    const std::vector<uint8_t>& okY, const std::vector<uint8_t>& okZ);
    ~TurbulentStress();
    TurbulentStress(const TurbulentStress&) = delete;
    TurbulentStress& operator=(const TurbulentStress&) = delete;

    /// One step of dt_s (> 0) seconds on the face velocities (m/s, WindField layout), in place.
    /// Faces outside the masks are not changed.
    TurbulenceReport apply(double dt_s, std::vector<double>& u, std::vector<double>& v,
                           std::vector<double>& w);

    /// nu_t (m^2/s) on the z-faces of the last apply() (WindField's w layout), 0 before.
    const std::vector<double>& eddyViscosityZ_m2ps() const { return mNuZ; }
    /// Turbulent kinetic energy k (m^2/s^2) on the cells of the last apply() (GridIndex's cell
    /// layout, 0 in solid cells; empty before the first apply). The mixing-length closure carries
    /// no k of its own: it reports the local-equilibrium value (production equals dissipation, so
    /// the shear stress nu_t |S| is sqrt(C_mu) k as in the log layer; Pope 2000, section 10.3),
    ///   k = (nu_t - nu) |S| / sqrt(C_mu),  C_mu = TKE_EQUILIBRIUM_CMU,
    /// averaged from the two z-faces of each cell.
    const std::vector<double>& turbulentKineticEnergy_m2ps2() const { return mTke; }
    /// C_mu of the equilibrium k above (the standard k-epsilon value, Launder and Spalding 1974).
    static constexpr double TKE_EQUILIBRIUM_CMU = 0.09;
    /// Bytes per cell of the box this object holds and uses while applying (memory estimates).
    static constexpr double BYTES_PER_CELL = 8.0 * 8 + 4.0 + 3.0;
    /// Bytes per cell a two-equation closure adds (0 for the mixing length): k-epsilon's five
    /// cell arrays of its transport (k, epsilon, nu_t, the step's copy, the diffusivity) and the
    /// stress's six (rotation, vorticity, production on faces and cells, the log-law correction
    /// and energy split in floats); SST also F1, F2, the cross gradient and the limiter on faces
    /// and cells.
    static constexpr double closureBytesPerCell(TurbulenceClosure c) {
        return c == TurbulenceClosure::MixingLength ? 0.0
               : c == TurbulenceClosure::KEpsilon   ? 5 * 8.0 + 4 * 8.0 + 2 * 4.0
                                                    : 5 * 8.0 + 4 * 8.0 + 2 * 4.0 + 5 * 8.0;
    }

  private:
    void setUpTwoEquation(double uStar_mps, double windX, double windY);
    void twoEquationStep(double dt_s, const std::vector<double>& u, const std::vector<double>& v,
                         const std::vector<double>& w);
    void faceEddyViscosityFromTransport();
    void computeEddyViscosity(double dt_s, const std::vector<double>& u,
                              const std::vector<double>& v, const std::vector<double>& w);

    const AirDomain& mDomain;
    SurfaceLayerSettings mSettings;
    double mNuMol = 0.0;
    std::vector<uint8_t> mOkX, mOkY, mOkZ;                // copies: the owner may move
    std::vector<double> mGroundCell, mGroundX, mGroundY;  // terrain height under cells / faces, m
    std::vector<int> mLowX, mLowY, mLowZ;  // lowest unknown face per column, -1: none
    // dh/dx, dh/dy of the terrain under each cell, x-face and y-face column (the wall's normal)
    std::vector<std::array<double, 2>> mSlopeCell, mSlopeX, mSlopeY;
    std::vector<float> mL2Z;               // l^2 on z-faces, m^2
    std::vector<double> mForceX, mForceY;  // balance force on x- and y-faces, m/s^2
    std::vector<double> mTopX, mTopY;      // top stress per column, m^2/s^2
    std::vector<double> mNuZ, mStrainH, mOld, mNuFace;
    std::vector<double> mShearZ, mTke;            // |S| on z-faces (1/s), k on cells (m^2/s^2)
    std::vector<double> mRotationH, mVorticityZ;  // (du/dy - dv/dx)^2 on cells, |Omega| on z-faces
    // Two-equation closures: the transport, and per z-face the log-law correction of nu_t and
    // the upper cell's share of the face's production; SST's stress limiter per cell (the mean
    // of its z-faces' factors).
    std::unique_ptr<TwoEquationTransport> mTwoEquation;
    std::vector<float> mLogCorrectionZ, mUpperShareZ;
    std::vector<double> mProductionZ, mProductionCell, mLimiterZ, mLimiterCell;
};

}  // namespace gale::sim

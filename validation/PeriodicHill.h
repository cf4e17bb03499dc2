#pragma once
/// \file PeriodicHill.h
/// The ERCOFTAC periodic hill (UFR 3-30; Almeida, Durao and Heitor 1993; Mellen, Froehlich and
/// Rodi 2000): its hill shape, its channel, its Reynolds number and the smooth-wall roughness gale
/// stands in for the smooth walls (docs/validation.md, section 4). Lengths are in hill heights h
/// unless a name says metres; PeriodicHillStudy.h solves it.
///
/// The hill shape is the published piecewise cubic in millimetres for a hill 28 mm high (Mellen,
/// Froehlich and Rodi 2000, section 2; the ERCOFTAC page of UFR 3-30 prints the same
/// coefficients): six cubics from the crest (x = 0) to the foot (x = 54 mm = 1.929 h), mirrored
/// about the period's middle (x = 4.5 h) so that the next crest stands at 9 h.

#include <algorithm>
#include <cmath>

namespace gale::validation::periodichill {

inline constexpr double HILL_MM = 28.0;              ///< the published hill height, mm
inline constexpr double FOOT_MM = 54.0;              ///< the hill's foot from its crest, mm
inline constexpr double PERIOD_OVER_H = 9.0;         ///< crest to crest, hill heights
inline constexpr double CHANNEL_TOP_OVER_H = 3.036;  ///< the upper wall above the flat floor
inline constexpr double REYNOLDS_H = 5600.0;         ///< Ub h / nu of the reference (Xiao 2020)
/// Smooth-wall log law u+ = ln(y+) / kappa + B; B between 5.0 and 5.2 in the literature (Pope
/// 2000, section 7.1.3): 5.0 is taken. With kappa = 0.41 it is a rough-wall law over the
/// equivalent z0 = nu exp(-kappa B) / u_tau (docs/validation.md, section 4).
inline constexpr double SMOOTH_WALL_B = 5.0;
/// Channel height over the crest (the bulk velocity's section), hill heights.
inline constexpr double CREST_GAP_OVER_H = CHANNEL_TOP_OVER_H - 1.0;

/// Height of the hill above the flat floor, hill heights, at xFromCrest_h hill heights from the
/// crest (0 <= x <= FOOT_MM / HILL_MM; 0 beyond, 1 at the crest). The published cubics, each on
/// [x0, x1) mm: y = a + b x + c x^2 + d x^3 with x and y in millimetres.
inline double lowerHillHeight_h(double xFromCrest_h) {
    const double x = std::abs(xFromCrest_h) * HILL_MM;
    if (x >= FOOT_MM) return 0.0;
    struct Cubic {
        double x1_mm, a, b, c, d;
    };
    static constexpr Cubic CUBICS[] = {
        {9.0, 2.800000000000e+01, 0.000000000000e+00, 6.775070969851e-03, -2.124527775800e-03},
        {14.0, 2.507355893131e+01, 9.754803562315e-01, -1.016116352781e-01, 1.889794677828e-03},
        {20.0, 2.579601052357e+01, 8.206693007457e-01, -9.055370274339e-02, 1.626510569859e-03},
        {30.0, 4.046435022819e+01, -1.379581654948e+00, 1.945884504128e-02, -2.070318932190e-04},
        {40.0, 1.792461334664e+01, 8.743920332081e-01, -5.567361123058e-02, 6.277731764683e-04},
        {FOOT_MM, 5.639011190988e+01, -2.010520359035e+00, 1.644919857549e-02, 2.674976141766e-05},
    };
    for (const Cubic& p : CUBICS)
        if (x < p.x1_mm) {
            const double y = p.a + x * (p.b + x * (p.c + x * p.d));
            return std::clamp(y, 0.0, HILL_MM) / HILL_MM;  // the published min(28, .), max(0, .)
        }
    return 0.0;
}

/// Height of the floor above its flat part, hill heights, at x_h hill heights along a chain of
/// hills whose crests stand at x = 0, 9, 18, ... (any x: the shape repeats every period).
inline double floorHeight_h(double x_h) {
    double s = std::fmod(x_h, PERIOD_OVER_H);
    if (s < 0) s += PERIOD_OVER_H;
    return lowerHillHeight_h(std::min(s, PERIOD_OVER_H - s));
}

/// Friction velocity over bulk velocity of a smooth channel at bulk Reynolds number
/// reBulk = Ub H / nu (H the full channel height), by Dean's (1978) correlation of the skin
/// friction, c_f = tau_w / (rho Ub^2 / 2) = 0.073 Re^(-1/4): u_tau / Ub = sqrt(c_f / 2).
inline double deanFrictionRatio(double reBulk) {
    return std::sqrt(0.5 * 0.073 * std::pow(reBulk, -0.25));
}

/// The smooth wall as an equivalent roughness, hill heights: the log law u / u_tau =
/// ln(y u_tau / nu) / kappa + B equals ln(y / z0) / kappa for z0 = nu exp(-kappa B) / u_tau. With
/// nu = Ub h / Re_h and u_tau from Dean's law over the crest gap (Re = Re_h 2.036), not from the
/// flow over the hills.
inline double smoothWallZ0_h(double kappa) {
    const double uTauOverUb = deanFrictionRatio(REYNOLDS_H * CREST_GAP_OVER_H);
    return std::exp(-kappa * SMOOTH_WALL_B) / (REYNOLDS_H * uTauOverUb);
}

}  // namespace gale::validation::periodichill

#pragma once
/// \file ExactSolutions.h
/// The exact flows that the benchmarks and the tests measure the solvers against, in one place.
/// Header-only, the standard library and base/ only: it knows nothing of the solvers it judges.
/// Units: metres, seconds, m/s; positions in world space.

#include <array>
#include <cmath>
#include <vector>

#include "base/Numbers.h"

namespace gale::validation::exact {

/// A hemisphere of radius R on flat ground at (cx, cy, 0) in a uniform wind U along +x. By
/// symmetry about the ground plane it is half of the sphere in a free stream (potential flow):
///
///   u = U e_x + grad(phi),   phi = U R^3 cos(theta) / (2 r^2) = U R^3 X / (2 r^3),
///
/// with r measured from the centre and theta from the wind axis (Lamb 1932, the sphere in a
/// uniform stream; docs/design.md 4.1). The surface speed is 1.5 U sin(theta).
struct HemisphereFlow {
    double R_m = 1.0;    ///< radius
    double U_mps = 1.0;  ///< free stream along +x
    double cx_m = 3.0;   ///< centre
    double cy_m = 3.0;

    /// The disturbance potential phi (m^2/s) at a point outside the hemisphere.
    double phi(double x, double y, double z) const {
        const double X = x - cx_m, Y = y - cy_m, r2 = X * X + Y * Y + z * z;
        return 0.5 * U_mps * R_m * R_m * R_m * X / (r2 * std::sqrt(r2));
    }
    /// The velocity (m/s) at a point outside the hemisphere.
    std::array<double, 3> velocity(double x, double y, double z) const {
        const double X = x - cx_m, Y = y - cy_m, r2 = X * X + Y * Y + z * z, r = std::sqrt(r2);
        const double r5 = r2 * r2 * r, k = 0.5 * U_mps * R_m * R_m * R_m;
        return {U_mps + k * (1.0 / (r2 * r) - 3.0 * X * X / r5), -3.0 * k * X * Y / r5,
                -3.0 * k * X * z / r5};
    }
    /// Fixed points 0.1 R from the surface, where grass lives: on the shell r = 1.1 R (polar
    /// angles 0..80 degrees by 10, 16 azimuths) and 0.1 R above the ground at 1.2, 1.5, 2 and
    /// 2.5 R from the axis (16 azimuths). 193 points, the same physical points at every grid.
    std::vector<std::array<double, 3>> nearPoints() const {
        std::vector<std::array<double, 3>> p;
        for (int ia = 0; ia <= 8; ++ia)
            for (int ib = 0; ib < (ia == 0 ? 1 : 16); ++ib) {
                const double al = radiansFromDegrees(ia * 10.0), be = ib * 2.0 * PI / 16.0;
                const double rr = 1.1 * R_m;
                p.push_back({cx_m + rr * std::sin(al) * std::cos(be),
                             cy_m + rr * std::sin(al) * std::sin(be), rr * std::cos(al)});
            }
        for (double rho : {1.2, 1.5, 2.0, 2.5})
            for (int ib = 0; ib < 16; ++ib)
                p.push_back({cx_m + rho * R_m * std::cos(ib * PI / 8),
                             cy_m + rho * R_m * std::sin(ib * PI / 8), 0.1 * R_m});
        return p;
    }
};

/// The Lamb-Oseen vortex of circulation Gamma (m^2/s) whose squared core radius has grown to
/// rc2 (m^2; r0^2 + 4 nu t under viscosity nu from core r0): the azimuthal speed (m/s) at radius
/// r > 0, v(r) = Gamma / (2 pi r) (1 - exp(-r^2 / rc2)) (Oseen 1911, Lamb 1932).
inline double lambOseenSpeed_mps(double circulation_m2ps, double rc2_m2, double r_m) {
    return circulation_m2ps / (2.0 * PI * r_m) * -std::expm1(-r_m * r_m / rc2_m2);
}

}  // namespace gale::validation::exact

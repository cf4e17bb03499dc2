#pragma once
/// \file HemisphereStudy.h
/// The mass-consistent solver against the hemisphere's exact potential flow (ExactSolutions.h;
/// docs/validation.md, "Error against run time"): R = 1 m at (3, 3) in a 6 x 6 x 3 m box, U = 1
/// m/s, the exact potential on the open faces, the error at the 193 fixed points 0.1 R up.

#include <vector>

namespace gale::validation {

struct HemisphereOptions {
    int cellsPerRadius = 4;  ///< R / h (>= 1)
};

struct HemisphereStudy {
    int nx = 0, ny = 0, nz = 0;
    int iterations = 0;
    bool converged = false;
    double seconds = 0;
    /// sqrt(sum |u - u_exact|^2 / sum |u_exact|^2) over the near points (dimensionless).
    double nearL2 = 0;
};

/// Solves and measures. Throws std::invalid_argument if cellsPerRadius < 1.
HemisphereStudy runHemisphere(const HemisphereOptions& options);

/// Least-squares slope of -log(error) against log(cells per radius): the observed order.
/// Requires at least two points with positive errors (std::invalid_argument otherwise).
double observedOrder(const std::vector<int>& cellsPerRadius, const std::vector<double>& errors);

}  // namespace gale::validation

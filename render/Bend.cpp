#include "render/Bend.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include "base/Numbers.h"

namespace gale::render {

void bendBladeInto(int shells, float height_m, float intensity, float stiffness, ShellOffset* out) {
    // DESIGN 5.1 (corrected from Bakay et al. 2002, section 3): segment j of N, length S, tilts by
    // theta_j = (pi/2) I (j/N)^gamma. The table is tiny (N + 1 entries per group per frame).
    const double s = static_cast<double>(height_m) / shells;
    const double halfPiI = 0.5 * PI * intensity;
    double n = 0.0, w = 0.0;
    out[0] = {0.0, 0.0};
    for (int j = 1; j <= shells; ++j) {
        const double x = static_cast<double>(j) / shells;
        const double theta = halfPiI * (stiffness == 1.0f ? x : std::pow(x, double(stiffness)));
        n += s * std::cos(theta);
        w += s * std::sin(theta);
        out[j] = {n, w};
    }
}

std::vector<ShellOffset> bendBlade(int shells, float height_m, float intensity, float stiffness) {
    if (shells < 1) throw std::invalid_argument("shells must be >= 1, got " + std::to_string(shells));
    if (!std::isfinite(height_m) || height_m < 0.0f)
        throw std::invalid_argument("blade height must be finite and >= 0, got " +
                                    std::to_string(height_m));
    if (!std::isfinite(intensity))
        throw std::invalid_argument("intensity must be finite, got " + std::to_string(intensity));
    if (!std::isfinite(stiffness) || stiffness <= 0.0f)
        throw std::invalid_argument("stiffness must be finite and > 0, got " +
                                    std::to_string(stiffness));
    std::vector<ShellOffset> out(static_cast<size_t>(shells) + 1);
    bendBladeInto(shells, height_m, intensity, stiffness, out.data());
    return out;
}

}  // namespace gale::render

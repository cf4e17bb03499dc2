#include "render/Bend.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"

namespace gale::render {

double tipTilt_rad(double intensity) {
    // The paper's tilt (Bakay et al. 2002, section 3) up to the knee; above it a tanh shoulder
    // whose slope at the knee is 1 and whose curvature there is 0, so the bend changes smoothly
    // with the drive and approaches, never reaches, the ground margin.
    const double x = 0.5 * PI * intensity;
    const double ax = std::abs(x);
    if (ax <= TIP_TILT_KNEE_RAD) return x;
    const double room = MAX_TIP_TILT_RAD - TIP_TILT_KNEE_RAD;
    const double tilt = TIP_TILT_KNEE_RAD + room * std::tanh((ax - TIP_TILT_KNEE_RAD) / room);
    return x < 0.0 ? -tilt : tilt;
}

void bendBladeByTiltInto(int shells, float height_m, double tipTilt, float stiffness,
                         ShellOffset* out) {
    // Bakay et al. 2002, section 3, with the tilt growing segment by segment as their text and
    // Figure 6 describe: segment j of N, length S, tilts by theta_j = theta_tip (j/N)^gamma.
    const double s = static_cast<double>(height_m) / shells;
    double n = 0.0, w = 0.0;
    out[0] = {0.0, 0.0};
    for (int j = 1; j <= shells; ++j) {
        const double x = static_cast<double>(j) / shells;
        const double theta = tipTilt * (stiffness == 1.0f ? x : std::pow(x, double(stiffness)));
        n += s * std::cos(theta);
        w += s * std::sin(theta);
        out[j] = {n, w};
    }
}

void bendBladeInto(int shells, float height_m, float intensity, float stiffness, ShellOffset* out) {
    bendBladeByTiltInto(shells, height_m, tipTilt_rad(intensity), stiffness, out);
}

std::vector<ShellOffset> bendBlade(int shells, float height_m, float intensity, float stiffness) {
    if (shells < 1)
        throw ParameterError("grass.shells", std::to_string(shells), "must be >= 1 to bend");
    if (!std::isfinite(height_m) || height_m < 0.0f)
        throw ParameterError("grass.height_m", formatG(height_m), "must be finite and >= 0");
    if (!std::isfinite(intensity))
        throw std::logic_error("bendBlade: intensity must be finite, got " + formatG(intensity));
    if (!std::isfinite(stiffness) || stiffness <= 0.0f)
        throw ParameterError("grass.stiffness", formatG(stiffness), "must be finite and > 0");
    std::vector<ShellOffset> out(static_cast<size_t>(shells) + 1);
    bendBladeInto(shells, height_m, intensity, stiffness, out.data());
    return out;
}

}  // namespace gale::render

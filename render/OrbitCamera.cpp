#include "render/OrbitCamera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "base/Numbers.h"

namespace gale::render {
namespace {

constexpr double DEG_PER_PIXEL = 0.3;
constexpr double MAX_ELEVATION_DEG = 89.0;
constexpr double ZOOM_PER_STEP = 0.85;

glm::dvec3 offsetOf(double azimuth_deg, double elevation_deg, double distance_m) {
    const double a = radiansFromDegrees(azimuth_deg), e = radiansFromDegrees(elevation_deg);
    return distance_m *
           glm::dvec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

}  // namespace

OrbitCamera::OrbitCamera(const Camera& home) : mHome(home) { reset(); }

void OrbitCamera::reset() {
    mAtHome = true;
    mTarget_m = glm::dvec3(mHome.wsTarget_m);
    const glm::dvec3 d = glm::dvec3(mHome.wsPosition_m) - mTarget_m;
    mDistance_m = std::max(1e-3, glm::length(d));
    mAzimuth_deg = degreesFromRadians(std::atan2(d.y, d.x));
    mElevation_deg =
        std::clamp(degreesFromRadians(std::asin(std::clamp(d.z / mDistance_m, -1.0, 1.0))),
                   -MAX_ELEVATION_DEG, MAX_ELEVATION_DEG);
}

void OrbitCamera::orbit(double dx_px, double dy_px) {
    mAtHome = false;
    // Dragging right swings the eye left around the target (the scene turns with the mouse).
    mAzimuth_deg = std::fmod(mAzimuth_deg - DEG_PER_PIXEL * dx_px, 360.0);
    mElevation_deg =
        std::clamp(mElevation_deg + DEG_PER_PIXEL * dy_px, -MAX_ELEVATION_DEG, MAX_ELEVATION_DEG);
}

void OrbitCamera::pan(double dx_px, double dy_px, int viewportHeight_px) {
    mAtHome = false;
    const glm::dvec3 back = glm::normalize(offsetOf(mAzimuth_deg, mElevation_deg, 1.0));
    const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), back));
    const glm::dvec3 up = glm::cross(back, right);
    // Metres per pixel at the target's distance.
    const double perPixel = 2.0 * mDistance_m * std::tan(0.5 * radiansFromDegrees(mHome.fovY_deg)) /
                            std::max(1, viewportHeight_px);
    mTarget_m += perPixel * (-dx_px * right + dy_px * up);
}

void OrbitCamera::zoom(double steps) {
    mAtHome = false;
    mDistance_m = std::clamp(mDistance_m * std::pow(ZOOM_PER_STEP, steps),
                             2.0 * double(mHome.near_m), 0.5 * double(mHome.far_m));
}

Camera OrbitCamera::camera() const {
    if (mAtHome) return mHome;
    Camera c = mHome;
    c.wsTarget_m = glm::vec3(mTarget_m);
    c.wsPosition_m = glm::vec3(mTarget_m + offsetOf(mAzimuth_deg, mElevation_deg, mDistance_m));
    return c;
}

}  // namespace gale::render

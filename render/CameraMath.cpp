/// \file CameraMath.cpp

#include "render/CameraMath.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"

namespace gale::render {
namespace {

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

glm::mat4 cameraFromWorld(const Camera& camera) {
    if (!finite3(camera.wsPosition_m) || !finite3(camera.wsTarget_m)) {
        throw ParameterError("camera.position_m", "a non-finite position or target",
                             "camera.position_m and camera.target_m must be finite");
    }
    const glm::vec3 forward = camera.wsTarget_m - camera.wsPosition_m;
    const float length = glm::length(forward);
    if (!(length > 0.0f)) {
        throw ParameterError("camera.target_m", "the camera's position",
                             "must differ from camera.position_m (no view direction)");
    }
    // Within ~0.06 degrees of vertical the z-up hint is too close to the view direction.
    const bool vertical = std::abs(forward.z / length) > 0.999999f;
    const glm::vec3 up = vertical ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    return glm::lookAt(camera.wsPosition_m, camera.wsTarget_m, up);
}

glm::mat4 clipFromCamera(const Camera& camera, float aspect) {
    if (!(camera.fovY_deg > 0.0f && camera.fovY_deg < 180.0f)) {
        throw ParameterError("camera.fov_deg", formatG(camera.fovY_deg), "must be in (0, 180)");
    }
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) {
        throw std::logic_error("Camera: aspect (width / height) must be > 0, got " +
                               std::to_string(aspect));
    }
    if (!(camera.near_m > 0.0f && camera.far_m > camera.near_m && std::isfinite(camera.far_m))) {
        throw ParameterError(
            !(camera.near_m > 0.0f) ? "camera.near_m" : "camera.far_m",
            "near_m " + formatG(camera.near_m) + ", far_m " + formatG(camera.far_m),
            "need 0 < near_m < far_m, both finite");
    }
    return glm::perspective(float(radiansFromDegrees(camera.fovY_deg)), aspect, camera.near_m,
                            camera.far_m);
}

glm::mat4 clipFromWorld(const Camera& camera, float aspect) {
    return clipFromCamera(camera, aspect) * cameraFromWorld(camera);
}

float focalLength_px(const Camera& camera, int height_px) {
    return static_cast<float>(height_px) /
           (2.0f * std::tan(0.5f * float(radiansFromDegrees(camera.fovY_deg))));
}

WorldRay pixelRay(const Camera& camera, int width_px, int height_px, double x_px, double y_px) {
    if (width_px < 1 || height_px < 1)
        throw std::logic_error("pixelRay: the view must be at least 1 x 1 pixels, got " +
                               std::to_string(width_px) + " x " + std::to_string(height_px));
    const glm::mat4 worldFromClip =
        glm::inverse(clipFromWorld(camera, float(width_px) / float(height_px)));
    // Normalised device coordinates: x right, y up, z -1 on the near plane and +1 on the far one.
    const float xNdc = float(2.0 * x_px / width_px - 1.0);
    const float yNdc = float(1.0 - 2.0 * y_px / height_px);
    const glm::vec4 nearH = worldFromClip * glm::vec4(xNdc, yNdc, -1.0f, 1.0f);
    const glm::vec4 farH = worldFromClip * glm::vec4(xNdc, yNdc, 1.0f, 1.0f);
    WorldRay ray;
    ray.wsOrigin_m = glm::vec3(nearH) / nearH.w;
    ray.wsDirection = glm::normalize(glm::vec3(farH) / farH.w - ray.wsOrigin_m);
    return ray;
}

}  // namespace gale::render

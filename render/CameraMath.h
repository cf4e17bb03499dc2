#pragma once
/// \file CameraMath.h
/// The camera's transforms, shared by the renderers and the tests.

#include <glm/mat4x4.hpp>

#include "render/GrassInput.h"

namespace gale::render {

/// View matrix (camera from world), right-handed, z up. When the camera looks straight up or down
/// the z-up hint is degenerate and +y serves as "up" on screen instead. Throws
/// gale::ParameterError (camera.position_m, camera.target_m) if the position equals the target
/// or a value is not finite.
glm::mat4 cameraFromWorld(const Camera& camera);

/// Perspective projection (clip from camera) with camera.fovY_deg, the given aspect
/// (width / height) and camera.near_m / far_m. Throws gale::ParameterError (camera.fov_deg,
/// camera.near_m, camera.far_m) on fovY_deg outside (0, 180) or not 0 < near_m < far_m, and
/// std::logic_error on aspect <= 0.
glm::mat4 clipFromCamera(const Camera& camera, float aspect);

/// clipFromCamera * cameraFromWorld.
glm::mat4 clipFromWorld(const Camera& camera, float aspect);

/// The focal length in pixels of a view height_px tall: height_px / (2 tan(fovY / 2)), the size
/// on screen of one metre seen from one metre away.
float focalLength_px(const Camera& camera, int height_px);

/// A ray in world space (metres): wsOrigin_m + s wsDirection, s >= 0, wsDirection unit length.
struct WorldRay {
    glm::vec3 wsOrigin_m{0.0f};
    glm::vec3 wsDirection{0.0f, 0.0f, -1.0f};
};

/// The ray through window point (x_px, y_px) (pixels, origin at the top-left corner, as input
/// events give it; a pixel's centre is at +0.5) of a width_px x height_px view, from the near plane
/// away from the camera. Throws as clipFromWorld does, and std::logic_error on a size below 1
/// pixel.
WorldRay pixelRay(const Camera& camera, int width_px, int height_px, double x_px, double y_px);

}  // namespace gale::render

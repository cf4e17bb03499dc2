#pragma once
/// \file CameraMath.h
/// The camera's transforms, shared by the renderers and the tests.

#include <glm/mat4x4.hpp>

#include "render/GrassInput.h"

namespace gale::render {

/// View matrix (camera from world), right-handed, z up. When the camera looks straight up or down
/// the z-up hint is degenerate and +y serves as "up" on screen instead. Throws
/// std::invalid_argument if the position equals the target or a value is not finite.
glm::mat4 cameraFromWorld(const Camera& camera);

/// Perspective projection (clip from camera) with camera.fovY_deg, the given aspect
/// (width / height) and camera.near_m / far_m. Throws std::invalid_argument on
/// fovY_deg outside (0, 180), aspect <= 0 or not 0 < near_m < far_m.
glm::mat4 clipFromCamera(const Camera& camera, float aspect);

/// clipFromCamera * cameraFromWorld.
glm::mat4 clipFromWorld(const Camera& camera, float aspect);

}  // namespace gale::render

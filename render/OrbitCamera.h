#pragma once
/// \file OrbitCamera.h
/// The viewer's mouse camera: orbit about a target (left drag), pan the target in the view plane
/// (right drag), zoom towards it (scroll). Angles and distance are kept, not the position, so
/// orbiting never drifts. World space, metres, z up.

#include "render/GrassInput.h"

namespace gale::render {

class OrbitCamera {
  public:
    /// Starts from `home` (position, target, fov, near, far); reset() returns there.
    explicit OrbitCamera(const Camera& home);

    /// Rotates by the drag (dx_px, dy_px) in window pixels: 0.3 degrees per pixel, azimuth about
    /// +z, elevation kept within (-89, 89) degrees.
    void orbit(double dx_px, double dy_px);
    /// Moves the target (and the eye with it) so the point under the cursor follows a drag of
    /// (dx_px, dy_px) pixels in a window viewportHeight_px tall.
    void pan(double dx_px, double dy_px, int viewportHeight_px);
    /// Scroll steps: each step up moves 15 % closer (down: further); distance stays within
    /// [near_m * 2, far_m / 2].
    void zoom(double steps);
    void reset();

    /// The camera for rendering (exactly `home` until the first move, so a viewer screenshot
    /// matches the headless render).
    Camera camera() const;

    double azimuth_deg() const { return mAzimuth_deg; }
    double elevation_deg() const { return mElevation_deg; }
    double distance_m() const { return mDistance_m; }

  private:
    Camera mHome;
    glm::dvec3 mTarget_m;
    double mAzimuth_deg = 0.0, mElevation_deg = 0.0, mDistance_m = 1.0;
    bool mAtHome = true;  // untouched since reset: camera() returns home exactly
};

}  // namespace gale::render

#pragma once
/// The viewer's camera: orbits a target point at a distance, so mouse drags turn, zoom and pan
/// around what the scene's own camera looked at.

#include "render/render_scene.h"

namespace substep::view {

class OrbitCamera {
  public:
    /// Starts where `start` is, looking at its target (its up must be +Y, the scene convention).
    explicit OrbitCamera(const render::Camera& start);

    /// Turns around the target by a drag of (dx, dy) pixels.
    void orbit(float dx, float dy);
    /// Moves the target across the view by a drag of (dx, dy) pixels in a view `viewHeight` high,
    /// so the point under the cursor follows it.
    void pan(float dx, float dy, float viewHeight);
    /// Moves toward the target by wheel `steps` (positive in); the distance changes by a factor
    /// per step, so zooming feels the same near and far.
    void zoom(float steps);

    render::Camera camera() const;

  private:
    render::Vec3f target_;
    float distance_ = 1.0f;
    float yaw_ = 0.0f;    ///< about +Y, radians
    float pitch_ = 0.0f;  ///< above the horizon, radians
    float fovY_ = 0.8f;
};

}  // namespace substep::view

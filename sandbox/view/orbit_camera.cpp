#include "view/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace substep::view {

namespace {

constexpr float kRadiansPerPixel = 0.005f;
/// Short of ±90°, where the view direction would be parallel to up and lookAt undefined.
constexpr float kMaxPitch = 1.55f;
constexpr float kZoomPerStep = 0.9f;
constexpr float kMinDistance = 0.01f;
constexpr float kMaxDistance = 1e5f;

}  // namespace

OrbitCamera::OrbitCamera(const render::Camera& start) : target_(start.target), fovY_(start.fovY) {
    const render::Vec3f offset = start.position - start.target;
    distance_ = std::clamp(offset.norm(), kMinDistance, kMaxDistance);
    yaw_ = std::atan2(offset.x(), offset.z());
    pitch_ = std::clamp(std::asin(std::clamp(offset.y() / distance_, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
}

void OrbitCamera::orbit(float dx, float dy) {
    yaw_ -= dx * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dx, float dy, float viewHeight) {
    const render::Camera view = camera();
    const render::Vec3f forward = (view.target - view.position).normalized();
    const render::Vec3f right = forward.cross(render::Vec3f::UnitY()).normalized();
    const render::Vec3f up = right.cross(forward);
    // The height of the view at the target's depth, spread over the window's pixels.
    const float metresPerPixel = 2.0f * distance_ * std::tan(0.5f * fovY_) / std::max(viewHeight, 1.0f);
    target_ += (-dx * right + dy * up) * metresPerPixel;
}

void OrbitCamera::zoom(float steps) {
    distance_ = std::clamp(distance_ * std::pow(kZoomPerStep, steps), kMinDistance, kMaxDistance);
}

render::Camera OrbitCamera::camera() const {
    render::Camera camera;
    const render::Vec3f direction(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                                  std::cos(pitch_) * std::cos(yaw_));
    camera.target = target_;
    camera.position = target_ + distance_ * direction;
    camera.up = render::Vec3f::UnitY();
    camera.fovY = fovY_;
    return camera;
}

}  // namespace substep::view

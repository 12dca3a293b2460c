#include "render/camera_framing.h"

#include <algorithm>
#include <cmath>

namespace substep::render {

Camera framingCamera(const Vec3f& centre, float radius, float fovY, float aspect) {
    const float fovX = 2.0f * std::atan(std::tan(fovY / 2.0f) * aspect);
    const float halfAngle = std::min(fovY, fovX) / 2.0f;
    // The radius comes from a bounding box, which is generous already: fit it by the tangent
    // rather than the exact sphere fit (sine), so the content fills the frame.
    const float distance = std::max(radius, 1e-3f) / std::tan(halfAngle);
    const float elevation = 0.35f;  // rad, about 20 degrees
    const Vec3f direction(0.0f, std::sin(elevation), std::cos(elevation));
    return {.position = centre + distance * direction, .target = centre, .up = Vec3f::UnitY(), .fovY = fovY};
}

}  // namespace substep::render

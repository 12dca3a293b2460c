#pragma once
/// A joint's frame [a, b, c] from its axis and optional normal, in one body's user frame: the
/// world builds its joints with it, and the engine layer uses it to measure joints from the
/// bodies' poses.

#include "physics/math.h"

#include <optional>

namespace substep {

/// Columns a (the axis), b (the normal made perpendicular to a) and c = a × b. A missing or
/// degenerate normal is the same fixed perpendicular of the axis on both sides, so equal axes
/// on equally oriented bodies give angle 0.
inline Quat jointFrame(const Vec3& axis, const std::optional<Vec3>& normal) {
    const Vec3 a = axis.normalized();
    Vec3 b = normal ? (*normal - normal->dot(a) * a) : anyPerpendicular(a);
    b = b.norm() > kDirectionEpsilon ? b.normalized() : anyPerpendicular(a);
    Mat3 frame;
    frame.col(0) = a;
    frame.col(1) = b;
    frame.col(2) = a.cross(b);
    return Quat(frame).normalized();
}

}  // namespace substep

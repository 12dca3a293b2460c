#pragma once
/// World-space bounds of a shape at a pose, and the shape's reach from its origin: what the
/// broadphase needs to box a body and to grow that box for rotation.

#include "physics/collision/aabb.h"
#include "physics/collision/shape.h"
#include "physics/math.h"

namespace substep {

/// Tight world box of `shape` with its user frame at `position`, turned by the unit quaternion
/// `orientation`. Sphere, box and capsule use closed forms; mesh, heightfield and spline shapes
/// turn their `localBounds` (a mesh without them falls back to its vertices). A plane is
/// unbounded and gets the infinite box; ShapeType::None and shapes without data get the empty
/// box. Negative sizes are taken by magnitude.
Aabb shapeBounds(const Shape& shape, const Vec3& position, const Quat& orientation);

/// Bounds in the shape's own frame (the box shapeBounds turns into the world); the infinite box
/// for a plane, the empty box for ShapeType::None.
Aabb shapeLocalBounds(const Shape& shape);

/// Largest distance from the shape's user-frame origin to a point of the shape, taken from its
/// local bounds (exact for spheres and capsules, the half diagonal for boxes). Infinite for a
/// plane, 0 for ShapeType::None.
double shapeReach(const Shape& shape);

/// World box of a local box `local` under the pose (position, rotation): the tight box around
/// the turned box, centre R c + p and half extents |R| h.
Aabb transformedBounds(const Aabb& local, const Vec3& position, const Mat3& rotation);

}  // namespace substep

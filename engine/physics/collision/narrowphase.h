#pragma once
/// The narrowphase entry: contacts of one pair of shapes, dispatched through a table indexed by
/// the two shape types (MuJoCo's pattern). Each pair is implemented once, for one order of the
/// types; the other order calls the same function with the shapes swapped and flips the result.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"

namespace substep {

/// A pair function: appends to `out` the contacts of shape a (shape 0) against shape b
/// (shape 1), the normal from b towards a, points with a gap up to `margin` included.
using CollideFunction = void (*)(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                                 double margin, ContactManifold& out);

/// Fills `out` (cleared first) with the contacts of shape a against shape b, normal from b
/// towards a. Pairs the table has no function for leave `out` empty.
void collide(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
             ContactManifold& out);

/// Whether the table has a function for the pair (in either order).
bool canCollide(ShapeType a, ShapeType b);

}  // namespace substep

#pragma once
/// Any convex shape (sphere, capsule, box, cylinder, convex mesh: shape a) against the static
/// shapes that are not convex (shape b): triangle meshes, heightfields and spline tubes, through
/// the general convex pair (convex_manifold.h). The narrowphase table uses them for the pairs
/// that have no special routine (cylinders and hulls on meshes, heightfields and splines;
/// boxes on splines). Conventions as collide_curved.h: `out` cleared and filled in world
/// coordinates, the normal from b towards a, at most 4 points: those spanning the patch.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"

namespace substep {

/// Convex shape against a static triangle mesh: the general pair per triangle near it (the
/// mesh's BVH), one-sided like the special routines: a shape wholly behind a triangle is let
/// go, and a contact found on an internal (inactive) edge or vertex, or one that would push
/// the shape through the triangle, takes the triangle's face normal.
void collideConvexTriangleMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                               double margin, ContactManifold& out);

/// Convex shape against a heightfield: the triangles of the cells under the shape, solid
/// beneath (a shape sunk below the surface is pushed up along the face normal).
void collideConvexHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                              double margin, ContactManifold& out);

/// Convex shape against a spline tube. Solid tube (a rail): along every segment near the shape
/// the curve is sampled at spacings finer than the shape and the tube's radius, each sample's
/// ball of the tube's radius meets the shape through the general pair, and the closest point of
/// the curve to the shape (alternating closest points, cubic_segment.h) is added, so a box
/// lying along a rail rests on the ends of its stretch and a hull on a wire at its lowest point.
/// Hollow tube (a pipe): the shape's farthest point across the curve's tangent at each sample,
/// pushed back inside where it reaches beyond the wall, reported by the sample whose slab across
/// the curve holds it; nothing holds a shape past an open end.
void collideConvexSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);

}  // namespace substep

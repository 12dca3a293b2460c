#pragma once
/// Narrowphase pairs of a convex hull (a mesh shape with convex = true) against the other
/// convex shapes. Shape a is always the hull (shape 0 of the manifold); each function appends
/// at most 4 points to `out` (plane: the 4 spanning the support polygon best), with the normal
/// from shape b towards the hull and points whose gap is up to `margin` included.
///
/// Hull against hull and box: the separating-axis test over both hulls' face normals and the
/// edge pairs that form a face of the Minkowski difference (Gregorius, "The Separating Axis
/// Test between Convex Polyhedra", GDC 2013), then, for a face axis, the incident face clipped
/// against the reference face's side planes as for two boxes. Sphere and capsule: closest
/// points between the hull and the sphere's centre or the capsule's segment.
///
/// A hull that is not solid (degenerate input) collides with nothing.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"

namespace substep {

/// Convex hull (a) against a plane (b): the hull's vertices below the plane plus margin.
void collideConvexPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out);
/// Convex hull (a) against a sphere (b): the hull's closest point to the centre.
void collideConvexSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);
/// Convex hull (a) against a capsule (b): the closest points to its segment; two points when
/// the segment lies along a face.
void collideConvexCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out);
/// Convex hull (a) against a box (b), the box taken as an eight-vertex hull.
void collideConvexBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                      ContactManifold& out);
/// Convex hull (a) against convex hull (b).
void collideConvexConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);

// The same pairs with the primitive first (shape a) and the hull second (shape b), the normal
// from the hull towards the primitive: for a dispatch table whose (primitive, mesh) slot must
// choose between a convex and a triangle mesh by `b.convex`.

/// Sphere (a) against convex hull (b).
void collideSphereConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);
/// Capsule (a) against convex hull (b).
void collideCapsuleConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out);
/// Box (a) against convex hull (b).
void collideBoxConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                      ContactManifold& out);

}  // namespace substep

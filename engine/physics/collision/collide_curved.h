#pragma once
/// Narrowphase pair functions for the shapes beyond the primitives: tubes around splines, static
/// triangle meshes and heightfields. Shape a is the primitive (sphere, capsule, box), shape b the
/// complex one; the signature is the narrowphase table's CollideFunction. Each clears `out` and
/// fills it in world coordinates with the contact convention of contact_manifold.h (normal from
/// b towards a, depth > 0 overlapping, points with gaps up to `margin` included), the deepest
/// kMaxContactPoints when there are more. Missing collision data (a null pointer) gives no contact.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"

namespace substep {

/// Solid tube: contact where the sphere comes within the tube radius of the curve, one point per
/// local minimum of the distance (a sphere cradled by a ring gets several). Hollow tube: the
/// sphere's centre runs inside; contact where it reaches the wall, normal towards the curve;
/// a sphere leaving an open pipe through its end is let go.
void collideSphereSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);

/// Capsule against a tube: the closest pair of axis and curve per nearby segment, plus the two
/// cap spheres (so a capsule lying along a rail has support at both ends).
void collideCapsuleSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out);

/// Sphere against a static triangle mesh (MeshCollider). Triangles are one-sided: they push
/// along their front normal (counter-clockwise seen from the front). Contacts on edges between
/// near-coplanar or concave neighbours use the face normal, so no bumps at internal edges.
void collideSphereMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                       double margin, ContactManifold& out);
void collideCapsuleMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out);
void collideBoxMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                    ContactManifold& out);

/// Primitives against a heightfield: the triangles of the cells under the primitive's bounds,
/// with everything below the surface pushed up (a heightfield is solid underneath).
void collideSphereHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                              double margin, ContactManifold& out);
void collideCapsuleHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                               double margin, ContactManifold& out);
void collideBoxHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out);

}  // namespace substep

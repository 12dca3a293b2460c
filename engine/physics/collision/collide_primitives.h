#pragma once
/// Narrowphase pairs of the primitive shapes (sphere, box, capsule, plane). Every function
/// appends to `out` the contacts of shape a (shape 0) against shape b (shape 1), the normal from
/// b towards a, depth = (point1 − point0)·normal, and keeps points whose depth is at least
/// −margin (speculative points). A plane is n·x = offset in world coordinates; its pose is
/// ignored. Nothing allocates; collide() in narrowphase.h dispatches to these.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"

namespace substep {

/// Sphere (a) against sphere (b): one point on the line of centres.
void collideSphereSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);
/// Sphere (a) against plane (b): one point below the centre.
void collideSpherePlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out);
/// Sphere (a) against box (b): the box's closest point, or the nearest face when the centre
/// is inside the box.
void collideSphereBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                      ContactManifold& out);
/// Sphere (a) against capsule (b): the closest point of the capsule's segment.
void collideSphereCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out);

/// Capsule (a) against capsule (b): the closest points of the segments; two points (the ends
/// of the overlap) when the segments are near parallel and overlap.
void collideCapsuleCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out);
/// Capsule (a) against plane (b): one point per end (feature 0 and 1).
void collideCapsulePlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out);
/// Capsule (a) against box (b): the segment's point nearest the box; two points (the segment
/// clipped to the face, features 0 and 1) when the capsule lies along a box face. A segment
/// entering the box leaves by its least-penetration axis (box faces, box edges × segment).
void collideCapsuleBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                       double margin, ContactManifold& out);

/// Box (a) against plane (b): the corners within margin, at most the 4 deepest; feature =
/// corner index (bit 0, 1, 2 set for the +x, +y, +z half extent).
void collideBoxPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                     ContactManifold& out);
/// Box (a) against box (b): separating axes over the 15 candidates, then the incident face
/// clipped against the reference face (at most 4 points) or one edge-edge point. Feature of a
/// face point: reference face << 12 | incident face << 8 | vertex id (faces 0-5 of a, 6-11 of
/// b, as 2·axis + (0 for +, 1 for −); vertex ids 0-3 incident corners, 8 and up cut points);
/// of an edge point: 1 << 16 | (3·a's edge axis + b's edge axis).
void collideBoxBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ContactManifold& out);

}  // namespace substep

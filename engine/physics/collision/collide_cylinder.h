#pragma once
/// Narrowphase pairs of a solid cylinder (shape a, its axis along local y, flat faces at
/// y = ±length/2) against planes, boxes and spheres. Conventions as collide_primitives.h: the
/// normal from shape b towards the cylinder, depth = (point1 − point0)·normal, points with a gap
/// up to `margin` kept. The rim is treated exactly, not as a polygon, so a coin rolling on its
/// rim touches at the true deepest rim point of every substep (paper Fig. 15).
///
/// Against a flat surface the contact depends on how the cylinder lies on it:
/// - tilted (a coin on its rim): one point, the deepest point of the lower face's rim;
/// - lying flat (axis within kFlatSine of the normal): six points of the lower rim at fixed
///   angles of the cylinder's frame, so it rests on an area without rocking;
/// - on its side (axis within kSideSine of the surface): the deepest rim point of each face,
///   the ends of the line it rests on, so a wheel rolls without tipping.
/// Cylinder–cylinder, cylinder–capsule, cylinder–hull and cylinder against meshes, heightfields
/// and splines go through the general convex pair (convex_manifold.h, collide_general.h).

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"

namespace substep {

/// |sin| of the angle between axis and surface normal below which a cylinder lies flat.
inline constexpr double kCylinderFlatSine = 0.01;
/// |cos| of that angle below which a cylinder lies on its side (two points, one per face).
inline constexpr double kCylinderSideCosine = 0.02;
/// Rim points of a cylinder lying flat.
inline constexpr int kCylinderFlatRimPoints = 6;

/// Cylinder (a) against plane (b): see the cases above.
void collideCylinderPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out);
/// Cylinder (a) against box (b): separating axes over the box's faces, the cylinder's axis and
/// the box edges crossed with it. A box face (a table) gets the plane cases, kept to the face's
/// rectangle; the cylinder's face gets the box corners over it; an edge axis one point between
/// the box edge and the cylinder's side. Rim against box edge is approximated by these axes.
void collideCylinderBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out);
/// Cylinder (a) against sphere (b): the cylinder's closest point to the centre (exact), or the
/// nearest face or side when the centre is inside.
void collideCylinderSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out);

}  // namespace substep

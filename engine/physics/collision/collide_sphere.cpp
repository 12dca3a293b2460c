// Narrowphase pairs of a sphere (shape a) against sphere, plane, box and capsule: each is the
// distance from the centre to the other shape's closest point, minus the radius. The sphere and
// plane pairs are repeated expression for expression by the pile's fast path
// (physics/contact_spheres.h), which shares the box pair's sphereBoxPoints;
// contact_spheres_test.cpp compares the two bit for bit.

#include "physics/collision/collide_primitives.h"
#include "physics/collision/primitive_geometry.h"

namespace substep {

using namespace primitive;

void collideSphereSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out) {
    const Vec3 d = pa.position - pb.position;
    const double distance = d.norm();
    if (distance - a.radius - b.radius > margin) return;
    // Coincident centres: any direction separates them; +y is as good as another.
    const Vec3 n = distance > kDirectionEpsilon ? Vec3(d / distance) : Vec3::UnitY();
    addContact(out, pa.position - a.radius * n, pb.position + b.radius * n, n, margin, 0);
}

void collideSpherePlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& /*pb*/,
                        double margin, ContactManifold& out) {
    const UnitPlane plane = unitPlane(b);
    const double height = plane.normal.dot(pa.position) - plane.offset;
    const Vec3 point0 = pa.position - a.radius * plane.normal;
    addContact(out, point0, pa.position - height * plane.normal, plane.normal, margin, 0);
}

void collideSphereBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                      ContactManifold& out) {
    SphereBoxPoints points;
    if (!sphereBoxPoints(pa.position, a.radius, pb, halfExtents(b), margin, points)) return;
    addContact(out, points.onSphere, points.onBox, points.normal, margin, 0);
}

void collideSphereCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out) {
    const CapsuleAxis capsule = capsuleAxis(b, pb);
    const double t = closestParameterOnSegment(capsule.start, capsule.delta, pa.position);
    const Vec3 d = pa.position - capsule.at(t);
    const double distance = d.norm();
    if (distance - a.radius - b.radius > margin) return;
    Vec3 n;
    if (distance > kDirectionEpsilon) {
        n = d / distance;
    } else {
        // Centre on the axis: leave sideways.
        n = capsule.unit.squaredNorm() > 0.0 ? anyPerpendicular(capsule.unit) : Vec3(Vec3::UnitY());
    }
    addContact(out, pa.position - a.radius * n, capsuleSurfacePoint(capsule, t, n), n, margin, 0);
}

}  // namespace substep

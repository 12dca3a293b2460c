// Narrowphase pairs of a sphere (shape a) against sphere, plane, box and capsule: each is the
// distance from the centre to the other shape's closest point, minus the radius. The sphere,
// plane and box pairs are repeated expression for expression by the pile's fast path
// (physics/contact_spheres.h); contact_spheres_test.cpp compares the two bit for bit.

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
    const Mat3 rotation = pb.rotation.toRotationMatrix();
    const Vec3 half = halfExtents(b);
    const Vec3 centre = rotation.transpose() * (pa.position - pb.position);
    Vec3 closest = centre.cwiseMax(-half).cwiseMin(half);
    const Vec3 outside = centre - closest;
    const double distance2 = outside.squaredNorm();
    Vec3 localNormal;
    if (distance2 > kTinySquared) {
        const double distance = std::sqrt(distance2);
        if (distance - a.radius > margin) return;
        localNormal = outside / distance;
    } else {
        // Centre inside (or on the surface): leave through the nearest face, the first axis
        // on ties so that a centred sphere gets a definite normal.
        int axis = 0;
        double nearest = half[0] - std::abs(centre[0]);
        for (int k = 1; k < 3; ++k) {
            const double gap = half[k] - std::abs(centre[k]);
            if (gap < nearest) {
                nearest = gap;
                axis = k;
            }
        }
        const double sign = centre[axis] >= 0.0 ? 1.0 : -1.0;
        closest[axis] = sign * half[axis];
        localNormal = sign * Vec3::Unit(axis);
    }
    const Vec3 n = rotation * localNormal;
    addContact(out, pa.position - a.radius * n, pb.position + rotation * closest, n, margin, 0);
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

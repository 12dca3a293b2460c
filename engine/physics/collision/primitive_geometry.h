#pragma once
/// Small geometric queries shared by the primitive pair functions (internal to the
/// narrowphase): closest points on segments, a capsule's axis and surface points, a plane in
/// unit form, and the margin filter every pair applies.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"
#include "physics/math.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace substep::primitive {

/// Squared lengths below this are treated as zero (a point, not a segment or direction).
inline constexpr double kTinySquared = kDirectionEpsilon * kDirectionEpsilon;

/// Parameter in [0, 1] of the point of segment start + s·delta closest to x.
inline double closestParameterOnSegment(const Vec3& start, const Vec3& delta, const Vec3& x) {
    const double dd = delta.squaredNorm();
    if (dd <= kTinySquared) return 0.0;
    return std::clamp((x - start).dot(delta) / dd, 0.0, 1.0);
}

/// Parameters s, t in [0, 1] of the closest points of segments p + s·d and q + t·e (Ericson,
/// Real-Time Collision Detection 5.1.9). Parallel segments take s = 0 (any point of the
/// overlap is as close).
inline void closestParametersBetweenSegments(const Vec3& p, const Vec3& d, const Vec3& q,
                                             const Vec3& e, double& s, double& t) {
    const Vec3 r = p - q;
    const double dd = d.squaredNorm();
    const double ee = e.squaredNorm();
    const double er = e.dot(r);
    if (dd <= kTinySquared && ee <= kTinySquared) {
        s = t = 0.0;
        return;
    }
    if (dd <= kTinySquared) {
        s = 0.0;
        t = std::clamp(er / ee, 0.0, 1.0);
        return;
    }
    const double dr = d.dot(r);
    if (ee <= kTinySquared) {
        t = 0.0;
        s = std::clamp(-dr / dd, 0.0, 1.0);
        return;
    }
    const double de = d.dot(e);
    const double denominator = dd * ee - de * de;  // |d × e|², >= 0
    s = denominator > 1e-14 * dd * ee ? std::clamp((de * er - dr * ee) / denominator, 0.0, 1.0)
                                      : 0.0;
    t = (de * s + er) / ee;
    if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-dr / dd, 0.0, 1.0);
    } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((de - dr) / dd, 0.0, 1.0);
    }
}

/// A capsule's segment in world coordinates: from end 0 (local −y) to end 1 (local +y).
struct CapsuleAxis {
    Vec3 start;  ///< end 0
    Vec3 delta;  ///< end 1 − end 0
    Vec3 unit;   ///< delta normalised; zero for a zero-length capsule
    double radius;

    Vec3 at(double t) const { return start + t * delta; }
};

inline CapsuleAxis capsuleAxis(const Shape& capsule, const Pose& pose) {
    const double length = std::max(capsule.length, 0.0);
    const Vec3 unit = pose.rotation * Vec3::UnitY();
    const Vec3 delta = length * unit;
    return {pose.position - 0.5 * delta, delta, length > 0.0 ? unit : Vec3::Zero(), capsule.radius};
}

/// The capsule's surface point around segment point at(t) that faces the unit direction u:
/// on an end cap when u points out of that end, else on the cylinder (u's component across
/// the axis). Always on the surface, also when u is not perpendicular to the axis.
inline Vec3 capsuleSurfacePoint(const CapsuleAxis& capsule, double t, const Vec3& u) {
    const Vec3 centre = capsule.at(t);
    const double along = u.dot(capsule.unit);
    const bool capFaces = (t <= 0.0 && along <= 0.0) || (t >= 1.0 && along >= 0.0);
    if (!capFaces) {
        const Vec3 across = u - along * capsule.unit;
        const double length = across.norm();
        if (length > kDirectionEpsilon) return centre + (capsule.radius / length) * across;
        // u along the axis into the capsule: every rim point is as far that way.
        return centre + capsule.radius * anyPerpendicular(capsule.unit);
    }
    return centre + capsule.radius * u;
}

/// A plane n·x = offset with n of unit length (a zero normal falls back to +y).
struct UnitPlane {
    Vec3 normal;
    double offset;
};

inline UnitPlane unitPlane(const Shape& plane) {
    const double length = plane.normal.norm();
    if (!(length > kDirectionEpsilon)) return {Vec3::UnitY(), plane.offset};
    return {plane.normal / length, plane.offset / length};
}

/// Half extents of a box (its size is the full extents).
inline Vec3 halfExtents(const Shape& box) {
    return 0.5 * box.size.cwiseAbs();
}

/// A sphere's point pair against a box: the sphere's point along the normal and the box's
/// closest point to the centre (from inside, its point on the nearest face, the first axis on
/// ties), the normal from the box towards the sphere.
struct SphereBoxPoints {
    Vec3 onSphere;
    Vec3 onBox;
    Vec3 normal;
};

/// The points of a sphere (centre, radius) against a box (pose, half extents); false when the
/// centre lies more than radius + margin outside it. Shared by collideSphereBox and the sphere
/// pile's fast path (physics/contact_spheres.h), which must give the same bits.
[[gnu::always_inline]] inline bool sphereBoxPoints(const Vec3& sphereCentre, double radius, const Pose& box,
                                                   const Vec3& half, double margin, SphereBoxPoints& points) {
    const Mat3 rotation = box.rotation.toRotationMatrix();
    const Vec3 centre = rotation.transpose() * (sphereCentre - box.position);
    Vec3 closest = centre.cwiseMax(-half).cwiseMin(half);
    const Vec3 outside = centre - closest;
    const double distance2 = outside.squaredNorm();
    Vec3 localNormal;
    if (distance2 > kTinySquared) {
        const double distance = std::sqrt(distance2);
        if (distance - radius > margin) return false;
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
    points.normal = rotation * localNormal;
    points.onSphere = sphereCentre - radius * points.normal;
    points.onBox = box.position + rotation * closest;
    return true;
}

/// Adds the point pair with depth = (point1 − point0)·normal when the depth is at least
/// −margin; returns whether it was added.
inline bool addContact(ContactManifold& out, const Vec3& point0, const Vec3& point1,
                       const Vec3& normal, double margin, uint32_t feature) {
    const double depth = (point1 - point0).dot(normal);
    if (!(depth >= -margin)) return false;
    return out.add(
        {.point0 = point0, .point1 = point1, .normal = normal, .depth = depth, .feature = feature});
}

}  // namespace substep::primitive

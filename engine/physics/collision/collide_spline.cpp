/// Sphere and capsule against a tube around a Hermite spline (collide_curved.h).
///
/// Solid tube of radius R, sphere of radius r at distance d from the curve: depth R + r − d,
/// normal from the curve to the centre. Hollow tube: depth d + r − R, normal from the centre
/// towards the curve. Every segment near the query reports its own closest point, kept only if
/// it is a local minimum of the distance along the whole curve, so a sphere resting in a ring
/// or between the coils of a spring gets one point per support and no duplicates at joints.

#include "physics/collision/collide_curved.h"
#include "physics/collision/contact_buffer.h"
#include "physics/collision/spline_tube.h"

namespace substep {

namespace {

/// Whether a segment's closest point (at parameter t, `offset` = curve point − query point) is
/// a local minimum of the distance along the whole curve. Inside the segment it is; at a joint
/// only where the distance is level there (else the neighbouring segment holds the minimum and
/// reports it), and at the ends of an open curve always.
bool isLocalMinimum(const SplineTube& tube, int segment, double t, const Vec3& offset) {
    if (t > 0.0 && t < 1.0) return true;
    if (tube.isCurveStart(segment, t) || tube.isCurveEnd(segment, t)) return true;
    const Vec3 tangent = tube.segments[segment].tangent(t);
    // Level: the slope of the distance, cosine of the angle to the tangent, near zero.
    return std::abs(offset.dot(tangent)) <= 1e-9 * offset.norm() * tangent.norm();
}

/// A unit direction across the curve at (segment, t) when the query sits on the curve itself.
Vec3 acrossCurve(const SplineTube& tube, int segment, double t) {
    const Vec3 tangent = tube.segments[segment].tangent(t);
    const double length = tangent.norm();
    return length > kDirectionEpsilon ? anyPerpendicular(tangent / length) : Vec3(Vec3::UnitY());
}

/// The contact of a sphere (centre c, radius r) with the tube at curve point x of (segment, t).
/// Returns false when it is farther than `margin` apart.
bool tubeContact(const SplineTube& tube, int segment, double t, const Vec3& x, const Vec3& c,
                 double r, double margin, ContactPoint& contact) {
    const double R = tube.radius;
    const Vec3 offset = c - x;
    const double d = offset.norm();
    const Vec3 outward = d > kDirectionEpsilon ? Vec3(offset / d) : acrossCurve(tube, segment, t);
    if (!tube.hollow) {
        contact.normal = outward;
        contact.depth = R + r - d;
        contact.point1 = x + R * outward;
    } else {
        // Past an open end the pipe is gone: a centre beyond the end cap leaves freely.
        if (tube.isCurveStart(segment, t) &&
            offset.dot(tube.segments[segment].tangent(0.0)) < 0.0) {
            return false;
        }
        if (tube.isCurveEnd(segment, t) && offset.dot(tube.segments[segment].tangent(1.0)) > 0.0) {
            return false;
        }
        contact.normal = -outward;
        contact.depth = d + r - R;
        contact.point1 = x + R * outward;
    }
    contact.point0 = c - r * contact.normal;
    return contact.depth >= -margin;
}

/// How far from the curve a sphere centre can be and still touch (within margin).
double searchRange(const SplineTube& tube, double r, double margin) {
    // Inside a pipe the centre stays within R of the curve; beyond that it is outside the pipe.
    return tube.hollow ? tube.radius : tube.radius + r + margin;
}

void addSphereContacts(const SplineTube& tube, const Vec3& c, double r, double margin,
                       uint32_t featureBase, ContactBuffer& buffer) {
    const double range = searchRange(tube, r, margin);
    const double range2 = range * range;
    tube.forSegmentsNear(c, range, [&](int i) {
        const Aabb& box = tube.segmentBounds[i];
        if ((box.min - c).cwiseMax(c - box.max).cwiseMax(0.0).squaredNorm() > range2) return;
        // Newton from the chord's projection where the piece is short and gently bent against
        // the distance (a marble on a wire); the scan elsewhere (closestOnCubicFrom).
        const CubicSegment& segment = tube.segments[i];
        const SegmentClosest closest = closestOnCubicFrom(segment, c, chordParameter(segment, c));
        if (closest.distanceSquared > range2) return;
        const Vec3 x = tube.segments[i].point(closest.t);
        if (!isLocalMinimum(tube, i, closest.t, x - c)) return;
        ContactPoint contact;
        if (!tubeContact(tube, i, closest.t, x, c, r, margin, contact)) return;
        contact.feature = featureBase + 4u * static_cast<uint32_t>(i);
        buffer.add(contact);
    });
}

double mergeDistance(const SplineTube& tube, double r) {
    return 1e-4 * (tube.radius + r);
}

}  // namespace

void collideSphereSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out) {
    out.clear();
    if (!b.spline) return;
    const SplineTube& tube = *b.spline;
    ContactBuffer buffer(mergeDistance(tube, a.radius));
    addSphereContacts(tube, pb.applyInverse(pa.position), a.radius, margin, 1, buffer);
    buffer.emit(pb, out);
}

void collideCapsuleSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out) {
    out.clear();
    if (!b.spline) return;
    const SplineTube& tube = *b.spline;
    const double r = a.radius;
    const Vec3 halfAxis = 0.5 * a.length * Vec3::UnitY();
    const Vec3 e0 = pb.applyInverse(pa.apply(-halfAxis));
    const Vec3 e1 = pb.applyInverse(pa.apply(halfAxis));
    ContactBuffer buffer(mergeDistance(tube, r));

    // The cap spheres: support at both ends of a capsule lying along a rail or inside a pipe.
    addSphereContacts(tube, e0, r, margin, 2, buffer);
    addSphereContacts(tube, e1, r, margin, 3, buffer);
    if (tube.hollow) {
        addSphereContacts(tube, 0.5 * (e0 + e1), r, margin, 4, buffer);
        buffer.emit(pb, out);
        return;
    }

    // The closest pair between the axis and each nearby segment: a capsule lying across a wire.
    const double range = searchRange(tube, r, margin);
    const double range2 = range * range;
    Aabb query;
    query.grow(e0);
    query.grow(e1);
    tube.tree.query(query.inflated(range), [&](int i) {
        const SegmentClosest closest = closestOnCubicToSegment(tube.segments[i], e0, e1);
        if (closest.distanceSquared > range2) return;
        const Vec3 x = tube.segments[i].point(closest.t);
        const Vec3 c = e0 + closest.s * (e1 - e0);
        if (!isLocalMinimum(tube, i, closest.t, x - c)) return;
        ContactPoint contact;
        if (!tubeContact(tube, i, closest.t, x, c, r, margin, contact)) return;
        contact.feature = 1u + 4u * static_cast<uint32_t>(i);
        buffer.add(contact);
    });
    buffer.emit(pb, out);
}

}  // namespace substep

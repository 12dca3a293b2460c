// Narrowphase pairs of a capsule (shape a) against capsule, plane and box. A capsule is the
// set of points within its radius of a segment, so each pair finds the segment's closest
// (deepest) point to the other shape; where a single point would let the capsule roll about
// a line contact (parallel capsules, a capsule lying on a face or a plane) it reports the two
// ends of that line instead.

#include "physics/collision/collide_primitives.h"
#include "physics/collision/primitive_geometry.h"

#include <cmath>
#include <limits>

namespace substep {

using namespace primitive;

namespace {

/// Below this sine of the angle between two axes, capsules get the two-point line contact.
constexpr double kParallelSine = 0.05;
/// Below this |axis · face normal| a capsule lies along a box face (two points).
constexpr double kLyingSine = 0.1;
/// A penetrating segment takes a box edge's axis over a face's only when it penetrates less
/// by this fraction, so the contact does not flip between near-equal axes.
constexpr double kPreferFaceFraction = 0.05;

/// A direction across both axes, for segments whose closest points coincide.
Vec3 fallbackNormal(const CapsuleAxis& a, const CapsuleAxis& b) {
    const Vec3 across = a.unit.cross(b.unit);
    const double length = across.norm();
    if (length > 1e-6) return across / length;
    if (a.unit.squaredNorm() > 0.0) return anyPerpendicular(a.unit);
    if (b.unit.squaredNorm() > 0.0) return anyPerpendicular(b.unit);
    return Vec3::UnitY();
}

/// Adds the contact between segment points a.at(s) and b.at(t), the normal along their
/// difference; returns its depth (added or not).
double addSegmentPair(const CapsuleAxis& a, double s, const CapsuleAxis& b, double t, double margin,
                      uint32_t feature, ContactManifold& out) {
    const Vec3 d = a.at(s) - b.at(t);
    const double distance = d.norm();
    const Vec3 n = distance > kDirectionEpsilon ? Vec3(d / distance) : fallbackNormal(a, b);
    const Vec3 point0 = capsuleSurfacePoint(a, s, -n);
    const Vec3 point1 = capsuleSurfacePoint(b, t, n);
    addContact(out, point0, point1, n, margin, feature);
    return (point1 - point0).dot(n);
}

/// Signed distance from a point to a box centred at the origin with half extents `half`.
double boxSignedDistance(const Vec3& p, const Vec3& half) {
    const Vec3 q = p.cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

/// The capsule's segment in a box's frame, with what the contacts need to go back to world.
struct SegmentInBox {
    const CapsuleAxis& capsule;
    const Mat3& rotation;  ///< the box's axes in world coordinates
    const Vec3& boxPosition;
    const Vec3& half;
    Vec3 start;  ///< end 0, box frame
    Vec3 delta;  ///< end 1 − end 0, box frame
};

/// Contacts of the segment with the box face on axis `axis`, side `sign`: the segment clipped
/// to the face's rectangle, both clipped ends when `bothEnds`, else the one deeper under the
/// face. Returns false when nothing of the segment lies over the face.
bool addFaceContacts(const SegmentInBox& s, int axis, double sign, bool bothEnds, double margin,
                     ContactManifold& out) {
    const double length = s.delta.norm();
    double lo = 0.0;
    double hi = 1.0;
    for (int k = 0; k < 3; ++k) {
        if (k == axis) continue;
        if (std::abs(s.delta[k]) > kDirectionEpsilon * length) {
            double ta = (-s.half[k] - s.start[k]) / s.delta[k];
            double tb = (s.half[k] - s.start[k]) / s.delta[k];
            if (ta > tb) std::swap(ta, tb);
            lo = std::max(lo, ta);
            hi = std::min(hi, tb);
        } else if (std::abs(s.start[k]) > s.half[k]) {
            return false;  // parallel to the slab and outside it
        }
    }
    if (lo > hi) return false;
    const Vec3 n = sign * s.rotation.col(axis);
    double params[2] = {lo, hi};
    int count = (hi - lo) * length > 1e-9 * (1.0 + length) ? 2 : 1;
    if (!bothEnds && count == 2) {
        // Keep the end lower under the face.
        if (sign * s.delta[axis] < 0.0) params[0] = hi;
        count = 1;
    }
    for (int k = 0; k < count; ++k) {
        Vec3 onFace = (s.start + params[k] * s.delta).cwiseMax(-s.half).cwiseMin(s.half);
        onFace[axis] = sign * s.half[axis];
        addContact(out, capsuleSurfacePoint(s.capsule, params[k], -n),
                   s.boxPosition + s.rotation * onFace, n, margin,
                   static_cast<uint32_t>(params[k] == hi && count == 2 ? 1 : 0));
    }
    return true;
}

/// The segment itself enters the box: the least-penetration axis among the box's face normals
/// and the box edges crossed with the segment (a separating-axis test of segment and box),
/// preferring faces on near-ties. A face gives the segment clipped to it; an edge the closest
/// points of that box edge and the segment.
void addPenetratingContacts(const SegmentInBox& s, double margin, ContactManifold& out) {
    const Vec3 middle = s.start + 0.5 * s.delta;
    const Vec3 halfDelta = 0.5 * s.delta;
    const double length = s.delta.norm();
    int bestFace = 0;
    double faceOverlap = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double overlap = s.half[k] + std::abs(halfDelta[k]) - std::abs(middle[k]);
        if (k == 0 || overlap < faceOverlap) {
            faceOverlap = overlap;
            bestFace = k;
        }
    }
    int bestEdge = -1;
    double edgeOverlap = 0.0;
    Vec3 edgeAxis = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
        const Vec3 axis = Vec3::Unit(k).cross(s.delta);
        const double axisLength = axis.norm();
        // Along the box edge (or a point segment): a face axis covers it.
        if (axisLength <= 1e-6 * length || axisLength <= kDirectionEpsilon) continue;
        const Vec3 unit = axis / axisLength;
        const double overlap = s.half.dot(unit.cwiseAbs()) - std::abs(middle.dot(unit));
        if (bestEdge < 0 || overlap < edgeOverlap) {
            edgeOverlap = overlap;
            bestEdge = k;
            edgeAxis = unit;
        }
    }
    const double tolerance = kPreferFaceFraction * faceOverlap + 1e-9 * s.half.maxCoeff();
    if (bestEdge < 0 || edgeOverlap >= faceOverlap - tolerance) {
        const double sign = middle[bestFace] >= 0.0 ? 1.0 : -1.0;
        const bool lying = std::abs(s.delta[bestFace]) < kLyingSine * length;
        if (addFaceContacts(s, bestFace, sign, lying, margin, out)) return;
        if (bestEdge < 0) return;
    }
    // Box edge along bestEdge, on the box's side towards the capsule.
    const Vec3 n = middle.dot(edgeAxis) >= 0.0 ? edgeAxis : Vec3(-edgeAxis);
    Vec3 edgeStart;
    for (int k = 0; k < 3; ++k)
        edgeStart[k] = n[k] >= 0.0 ? s.half[k] : -s.half[k];
    edgeStart[bestEdge] = -s.half[bestEdge];
    const Vec3 edgeDelta = (2.0 * s.half[bestEdge]) * Vec3::Unit(bestEdge);
    double onEdge = 0.0;
    double t = 0.0;
    closestParametersBetweenSegments(edgeStart, edgeDelta, s.start, s.delta, onEdge, t);
    const Vec3 nWorld = s.rotation * n;
    addContact(out, capsuleSurfacePoint(s.capsule, t, -nWorld),
               s.boxPosition + s.rotation * (edgeStart + onEdge * edgeDelta), nWorld, margin, 0);
}

}  // namespace

void collideCapsuleCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out) {
    const CapsuleAxis ca = capsuleAxis(a, pa);
    const CapsuleAxis cb = capsuleAxis(b, pb);
    double s = 0.0;
    double t = 0.0;
    closestParametersBetweenSegments(ca.start, ca.delta, cb.start, cb.delta, s, t);
    const double gap = (ca.at(s) - cb.at(t)).norm() - ca.radius - cb.radius;
    if (gap > margin) return;

    const double aLength2 = ca.delta.squaredNorm();
    const bool bothSegments = aLength2 > kTinySquared && cb.delta.squaredNorm() > kTinySquared;
    if (bothSegments && ca.unit.cross(cb.unit).norm() < kParallelSine) {
        // Near parallel: the overlap of b's projection onto a, in a's parameter.
        const double b0 = (cb.start - ca.start).dot(ca.delta) / aLength2;
        const double b1 = (cb.start + cb.delta - ca.start).dot(ca.delta) / aLength2;
        const double lo = std::max(0.0, std::min(b0, b1));
        const double hi = std::min(1.0, std::max(b0, b1));
        if ((hi - lo) * std::sqrt(aLength2) > 1e-6 * (ca.radius + cb.radius)) {
            double deepestEnd = -std::numeric_limits<double>::infinity();
            const double ends[2] = {lo, hi};
            for (uint32_t k = 0; k < 2; ++k) {
                const double tk = closestParameterOnSegment(cb.start, cb.delta, ca.at(ends[k]));
                deepestEnd =
                    std::max(deepestEnd, addSegmentPair(ca, ends[k], cb, tk, margin, k, out));
            }
            // Slightly crossing axes are closest in between: keep that point too.
            if (-gap > deepestEnd + 1e-6 * (ca.radius + cb.radius)) {
                addSegmentPair(ca, s, cb, t, margin, 2, out);
            }
            return;
        }
    }
    addSegmentPair(ca, s, cb, t, margin, 0, out);
}

void collideCapsulePlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& /*pb*/,
                         double margin, ContactManifold& out) {
    const CapsuleAxis capsule = capsuleAxis(a, pa);
    const UnitPlane plane = unitPlane(b);
    const int ends = capsule.delta.squaredNorm() > kTinySquared ? 2 : 1;
    for (int end = 0; end < ends; ++end) {
        // The lowest point of the end's half: on the cap, or on the rim when the cap faces up.
        const Vec3 point0 = capsuleSurfacePoint(capsule, end, -plane.normal);
        const double height = plane.normal.dot(point0) - plane.offset;
        addContact(out, point0, point0 - height * plane.normal, plane.normal, margin, end);
    }
}

void collideCapsuleBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                       double margin, ContactManifold& out) {
    const CapsuleAxis capsule = capsuleAxis(a, pa);
    const Mat3 rotation = pb.rotation.toRotationMatrix();
    const Vec3 half = halfExtents(b);
    // The segment in the box's frame.
    const SegmentInBox segment{capsule,
                               rotation,
                               pb.position,
                               half,
                               rotation.transpose() * (capsule.start - pb.position),
                               rotation.transpose() * capsule.delta};
    const Vec3& start = segment.start;
    const Vec3& delta = segment.delta;

    // The segment point nearest the box: the box's signed distance is convex, so along the
    // segment it has one minimum (or a flat run); golden-section search brackets it.
    double t = 0.0;
    if (delta.squaredNorm() > kTinySquared) {
        constexpr double kInvPhi = 0.6180339887498949;
        double lo = 0.0;
        double hi = 1.0;
        double x1 = hi - kInvPhi * (hi - lo);
        double x2 = lo + kInvPhi * (hi - lo);
        double f1 = boxSignedDistance(start + x1 * delta, half);
        double f2 = boxSignedDistance(start + x2 * delta, half);
        for (int iteration = 0; iteration < 40; ++iteration) {
            if (f1 <= f2) {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - kInvPhi * (hi - lo);
                f1 = boxSignedDistance(start + x1 * delta, half);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + kInvPhi * (hi - lo);
                f2 = boxSignedDistance(start + x2 * delta, half);
            }
        }
        t = 0.5 * (lo + hi);
        // The ends are the usual minimum of a capsule resting on its cap: take them exactly.
        const double fEnd0 = boxSignedDistance(start, half);
        const double fEnd1 = boxSignedDistance(start + delta, half);
        const double fMid = boxSignedDistance(start + t * delta, half);
        if (fEnd0 <= fMid && fEnd0 <= fEnd1)
            t = 0.0;
        else if (fEnd1 < fMid)
            t = 1.0;
    }

    const Vec3 centre = start + t * delta;
    const Vec3 closest = centre.cwiseMax(-half).cwiseMin(half);
    const Vec3 outside = centre - closest;
    const double distance2 = outside.squaredNorm();
    if (!(distance2 > kTinySquared)) {
        addPenetratingContacts(segment, margin, out);
        return;
    }
    const double distance = std::sqrt(distance2);
    if (distance - capsule.radius > margin) return;
    const Vec3 localNormal = outside / distance;
    // Over a face (the normal is the face's, within the search's rounding) and lying along it:
    // the segment clipped to the face, both ends.
    int axis = 0;
    localNormal.cwiseAbs().maxCoeff(&axis);
    const double length = delta.norm();
    if (std::abs(localNormal[axis]) > 1.0 - 1e-6 && length > kDirectionEpsilon &&
        std::abs(delta[axis]) < kLyingSine * length) {
        const double sign = localNormal[axis] > 0.0 ? 1.0 : -1.0;
        if (addFaceContacts(segment, axis, sign, true, margin, out)) return;
    }
    const Vec3 n = rotation * localNormal;
    addContact(out, capsuleSurfacePoint(capsule, t, -n), pb.position + rotation * closest, n,
               margin, 0);
}

}  // namespace substep

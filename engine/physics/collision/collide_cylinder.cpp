// Narrowphase pairs of a solid cylinder (shape a) against plane, box and sphere. The work is
// done in a frame where the other shape is simple (world for a plane, the box's frame for a
// box, the cylinder's own frame for a sphere); the cylinder there is a centre, an axis, two
// perpendicular rim directions, a radius and a half length.

#include "physics/collision/collide_cylinder.h"

#include "physics/collision/primitive_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace substep {

using namespace primitive;

namespace {

/// A box face's axis is taken over the cylinder's own axes unless they overlap less by this
/// fraction, so a coin lying on a table (a tie) does not flip between near-equal axes.
constexpr double kPreferFaceFraction = 0.05;

/// The cylinder in a working frame.
struct CylinderFrame {
    Vec3 centre;
    Vec3 axis;   ///< local y
    Vec3 rimX;   ///< local x
    Vec3 rimZ;   ///< local z
    double radius;
    double halfLength;

    /// Centre of face `side` (−1: local −y, +1: local +y).
    Vec3 faceCentre(double side) const { return centre + (side * halfLength) * axis; }
    /// The rim point of face `side` farthest along direction w (any rim point when w is along
    /// the axis: every one is as far).
    Vec3 rimPoint(double side, const Vec3& w) const {
        const Vec3 across = w - w.dot(axis) * axis;
        const double length = across.norm();
        const Vec3 unit = length > kDirectionEpsilon ? Vec3(across / length) : rimX;
        return faceCentre(side) + radius * unit;
    }
    /// Extent of the cylinder along unit n from its centre (its support distance).
    double reach(const Vec3& n) const {
        const double along = n.dot(axis);
        return halfLength * std::abs(along) + radius * std::sqrt(std::max(0.0, 1.0 - along * along));
    }
};

CylinderFrame cylinderFrame(const Shape& cylinder, const Vec3& centre, const Quat& rotation) {
    const Mat3 r = rotation.toRotationMatrix();
    return {centre, r.col(1), r.col(0), r.col(2), std::abs(cylinder.radius),
            0.5 * std::abs(cylinder.length)};
}

/// A point of the cylinder's surface that may touch a flat surface.
struct Candidate {
    Vec3 point;
    uint32_t feature;
};

/// The cylinder's points that may touch the plane n·x = c from above (n unit, pointing out of
/// the surface), by the cases of collide_cylinder.h. Returns the count (at most
/// kCylinderFlatRimPoints). Features: the face (0: −y, 1: +y) for rim points under a tilted
/// cylinder, 2 + k for the k-th fixed rim point of a flat one.
int flatSurfaceCandidates(const CylinderFrame& cylinder, const Vec3& n, Candidate* out) {
    const double cosine = cylinder.axis.dot(n);
    const double sine = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
    // The face whose outward normal points into the surface is the lower one.
    const double lower = cosine > 0.0 ? -1.0 : 1.0;
    const uint32_t lowerFeature = lower < 0.0 ? 0u : 1u;
    if (sine < kCylinderFlatSine) {
        // Fixed angles of the cylinder's frame: the points stay put on the body while it rests.
        for (int k = 0; k < kCylinderFlatRimPoints; ++k) {
            const double angle = 2.0 * std::numbers::pi * k / kCylinderFlatRimPoints;
            out[k] = {cylinder.faceCentre(lower) +
                          cylinder.radius * (std::cos(angle) * cylinder.rimX + std::sin(angle) * cylinder.rimZ),
                      static_cast<uint32_t>(2 + k)};
        }
        return kCylinderFlatRimPoints;
    }
    // The exact deepest rim point: the lower face's rim point farthest along −n.
    out[0] = {cylinder.rimPoint(lower, -n), lowerFeature};
    if (std::abs(cosine) < kCylinderSideCosine && cylinder.halfLength > 0.0) {
        out[1] = {cylinder.rimPoint(-lower, -n), 1u - lowerFeature};
        return 2;
    }
    return 1;
}

/// Box corner `corner` (bit 0, 1, 2 set for the +x, +y, +z half extent), box frame.
Vec3 boxCorner(const Vec3& half, int corner) {
    return {(corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
            (corner & 4) ? half.z() : -half.z()};
}

/// Σ half_i |n_i|: the box's extent along unit n from its centre.
double boxReach(const Vec3& half, const Vec3& n) { return half.dot(n.cwiseAbs()); }

/// Box-frame contact to world, appended when within margin.
void addBoxFrameContact(ContactManifold& out, const Pose& box, const Mat3& rotation,
                        const Vec3& point0, const Vec3& point1, const Vec3& normal, double margin,
                        uint32_t feature) {
    addContact(out, box.position + rotation * point0, box.position + rotation * point1,
               rotation * normal, margin, feature);
}

/// The cylinder (box frame) on box face `axis`, side `sign`: the flat-surface candidates whose
/// foot lies on the face's rectangle; when none does (the cylinder hangs over an edge), the
/// deepest candidate with its foot clamped to the rectangle.
void addBoxFaceContacts(const CylinderFrame& cylinder, const Vec3& half, int axis, double sign,
                        const Pose& box, const Mat3& rotation, double margin, ContactManifold& out) {
    Vec3 n = Vec3::Zero();
    n[axis] = sign;
    Candidate candidates[kCylinderFlatRimPoints];
    const int count = flatSurfaceCandidates(cylinder, n, candidates);
    const double faceLevel = half[axis];
    int added = 0;
    int deepest = 0;
    for (int k = 0; k < count; ++k) {
        const Vec3& p = candidates[k].point;
        if (n.dot(p) < n.dot(candidates[deepest].point)) deepest = k;
        Vec3 foot = p;
        foot[axis] = sign * faceLevel;
        if ((foot.cwiseAbs() - half).maxCoeff() > 1e-12 * (1.0 + half.maxCoeff())) continue;
        addBoxFrameContact(out, box, rotation, p, foot, n, margin, candidates[k].feature);
        ++added;
    }
    if (added > 0) return;
    const Vec3& p = candidates[deepest].point;
    Vec3 foot = p.cwiseMax(-half).cwiseMin(half);
    foot[axis] = sign * faceLevel;
    addBoxFrameContact(out, box, rotation, p, foot, n, margin, candidates[deepest].feature);
}

/// The box (its corners) against the cylinder's face that faces it, n = the face's inward
/// direction seen from the box (from box towards cylinder, along the axis): the corners over
/// the face's disc, at most the 4 deepest; when none lies over it, the deepest corner with its
/// foot pulled onto the disc.
void addCylinderFaceContacts(const CylinderFrame& cylinder, const Vec3& half, const Vec3& n,
                             const Pose& box, const Mat3& rotation, double margin,
                             ContactManifold& out) {
    const Vec3 face = cylinder.centre - cylinder.halfLength * n;
    int order[8];
    double depth[8];
    int count = 0;
    int deepestAnywhere = 0;
    double deepestDepth = -std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 v = boxCorner(half, corner);
        const double d = (v - face).dot(n);
        if (d > deepestDepth) deepestDepth = d, deepestAnywhere = corner;
        const Vec3 across = (v - face) - d * n;
        if (across.norm() > cylinder.radius || !(d >= -margin)) continue;
        int k = count++;
        while (k > 0 && depth[k - 1] < d) {
            depth[k] = depth[k - 1];
            order[k] = order[k - 1];
            --k;
        }
        depth[k] = d;
        order[k] = corner;
    }
    const auto addCorner = [&](int corner) {
        const Vec3 v = boxCorner(half, corner);
        const double d = (v - face).dot(n);
        Vec3 across = (v - face) - d * n;
        const double length = across.norm();
        if (length > cylinder.radius) across *= cylinder.radius / length;
        addBoxFrameContact(out, box, rotation, face + across, v, n, margin,
                           static_cast<uint32_t>(16 + corner));
    };
    if (count == 0) {
        addCorner(deepestAnywhere);
        return;
    }
    for (int k = 0; k < std::min(count, 4); ++k) addCorner(order[k]);
}

}  // namespace

void collideCylinderPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& /*pb*/,
                          double margin, ContactManifold& out) {
    const UnitPlane plane = unitPlane(b);
    const CylinderFrame cylinder = cylinderFrame(a, pa.position, pa.rotation);
    Candidate candidates[kCylinderFlatRimPoints];
    const int count = flatSurfaceCandidates(cylinder, plane.normal, candidates);
    for (int k = 0; k < count; ++k) {
        const Vec3& point0 = candidates[k].point;
        const double height = plane.normal.dot(point0) - plane.offset;
        addContact(out, point0, point0 - height * plane.normal, plane.normal, margin,
                   candidates[k].feature);
    }
}

void collideCylinderBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out) {
    const Mat3 rotation = pb.rotation.toRotationMatrix();
    const Vec3 half = halfExtents(b);
    // The cylinder in the box's frame.
    const CylinderFrame cylinder = cylinderFrame(
        a, rotation.transpose() * (pa.position - pb.position), pb.rotation.conjugate() * pa.rotation);
    const Vec3& c = cylinder.centre;

    // Separation along each candidate axis (oriented from the box towards the cylinder): the
    // largest is the least overlap, or a gap.
    int bestFace = 0;
    double faceSeparation = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        Vec3 n = Vec3::Zero();
        n[k] = c[k] >= 0.0 ? 1.0 : -1.0;
        const double separation = std::abs(c[k]) - half[k] - cylinder.reach(n);
        if (separation > faceSeparation) faceSeparation = separation, bestFace = k;
    }
    if (faceSeparation > margin) return;

    const Vec3 axisNormal = c.dot(cylinder.axis) >= 0.0 ? cylinder.axis : Vec3(-cylinder.axis);
    const double axisSeparation = c.dot(axisNormal) - boxReach(half, axisNormal) - cylinder.halfLength;
    if (axisSeparation > margin) return;

    int bestEdge = -1;
    Vec3 edgeNormal = Vec3::Zero();
    double edgeSeparation = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const Vec3 cross = Vec3::Unit(k).cross(cylinder.axis);
        const double length = cross.norm();
        if (length < 1e-6) continue;  // axis along a box edge: a face axis covers it
        Vec3 n = cross / length;
        if (c.dot(n) < 0.0) n = -n;
        const double separation = c.dot(n) - boxReach(half, n) - cylinder.radius;
        if (separation > margin) return;
        if (separation > edgeSeparation) edgeSeparation = separation, bestEdge = k, edgeNormal = n;
    }

    // Box faces win near-ties: a coin lying on a table stays on the table's face.
    const double tolerance = kPreferFaceFraction * std::abs(faceSeparation) +
                             1e-9 * std::max(cylinder.radius, cylinder.halfLength);
    if (faceSeparation >= std::max(axisSeparation, edgeSeparation) - tolerance) {
        addBoxFaceContacts(cylinder, half, bestFace, c[bestFace] >= 0.0 ? 1.0 : -1.0, pb, rotation,
                           margin, out);
        return;
    }
    if (axisSeparation >= edgeSeparation) {
        addCylinderFaceContacts(cylinder, half, axisNormal, pb, rotation, margin, out);
        return;
    }
    // A box edge against the cylinder's side: the box edge along bestEdge farthest towards the
    // cylinder, and the side's line nearest the box.
    Vec3 edgeStart;
    for (int k = 0; k < 3; ++k) edgeStart[k] = edgeNormal[k] >= 0.0 ? half[k] : -half[k];
    edgeStart[bestEdge] = -half[bestEdge];
    const Vec3 edgeDelta = (2.0 * half[bestEdge]) * Vec3::Unit(bestEdge);
    const Vec3 sideStart = c - cylinder.radius * edgeNormal - cylinder.halfLength * cylinder.axis;
    const Vec3 sideDelta = (2.0 * cylinder.halfLength) * cylinder.axis;
    double onEdge = 0.0;
    double onSide = 0.0;
    closestParametersBetweenSegments(edgeStart, edgeDelta, sideStart, sideDelta, onEdge, onSide);
    addBoxFrameContact(out, pb, rotation, sideStart + onSide * sideDelta,
                       edgeStart + onEdge * edgeDelta, edgeNormal, margin,
                       static_cast<uint32_t>(32 + bestEdge));
}

void collideCylinderSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out) {
    const double radius = std::abs(a.radius);
    const double halfLength = 0.5 * std::abs(a.length);
    const double sphereRadius = std::abs(b.radius);
    // The sphere's centre in the cylinder's frame, its distance from the axis and the direction
    // across the axis towards it.
    const Vec3 q = pa.applyInverse(pb.position);
    const double fromAxis = std::hypot(q.x(), q.z());
    const Vec3 across = fromAxis > kDirectionEpsilon ? Vec3(q.x() / fromAxis, 0.0, q.z() / fromAxis)
                                                     : Vec3(Vec3::UnitX());
    Vec3 onCylinder;
    Vec3 normal;  // cylinder frame, from the sphere towards the cylinder
    const bool inside = fromAxis < radius && std::abs(q.y()) < halfLength;
    if (!inside) {
        // The closest point of the solid: the centre clamped to the slab and to the radius.
        onCylinder = Vec3(0.0, std::clamp(q.y(), -halfLength, halfLength), 0.0) +
                     std::min(fromAxis, radius) * across;
        const Vec3 d = onCylinder - q;
        const double distance = d.norm();
        if (distance - sphereRadius > margin) return;
        normal = distance > kDirectionEpsilon ? Vec3(d / distance) : Vec3(-across);
    } else if (radius - fromAxis < halfLength - std::abs(q.y())) {
        // Nearer the side: out through it.
        onCylinder = Vec3(0.0, q.y(), 0.0) + radius * across;
        normal = -across;
    } else {
        // Nearer a face: out through it.
        const double side = q.y() >= 0.0 ? 1.0 : -1.0;
        onCylinder = Vec3(q.x(), side * halfLength, q.z());
        normal = Vec3(0.0, -side, 0.0);
    }
    const Vec3 worldNormal = pa.rotation * normal;
    addContact(out, pa.apply(onCylinder), pb.position + sphereRadius * worldNormal, worldNormal,
               margin, 0);
}

}  // namespace substep

#pragma once
/// The narrowphase's fast path for the pairs of a sphere pile: sphere – sphere, sphere – plane
/// and sphere – box contacts written straight into the solver's Contact list, in the bodies'
/// frames, without the dispatch table, the manifold and its copy (World::findPairContacts). The
/// arithmetic is collideSphereSphere's and collideSpherePlane's expression for expression, and
/// collideSphereBox's own primitive::sphereBoxPoints, followed by the frame change World::findPairContacts makes, so the contacts
/// are bit-identical to the general path's (tests/physics/contact_spheres_test.cpp compares
/// them). Every function is always inlined: its callers are compiled for AVX2 too
/// (target_clones), and a copy left out of line would be the base ISA's.

#include "physics/body.h"
#include "physics/collision/contact_manifold.h"
#include "physics/collision/primitive_geometry.h"
#include "physics/collision/shape.h"
#include "physics/contact.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace substep {

/// The contact of one point as World::findPairContacts stores it: each body's point in its
/// principal frame (paper 3.5: r1, r2), q0⁻¹ (p0 − x0) and q1⁻¹ (p1 − x1), the normal from body
/// 1 towards body 0. The two points are turned side by side in the lanes of two doubles, each
/// lane with Eigen's operations on a quaternion's conjugate and a vector in Eigen's order
/// (u = 2 q⃗ × v, then (v + w u) + q⃗ × u, a cross product row by row), so the bits are Eigen's
/// in half the instructions.
[[gnu::always_inline]] inline void appendContactInBodyFrames(const Body& b0, const Body& b1,
                                                             const Vec3& point0, const Vec3& point1,
                                                             const Vec3& normal,
                                                             std::vector<Contact>& out,
                                                             uint32_t feature = 0) {
    using Two = double __attribute__((vector_size(2 * sizeof(double))));
    // The conjugates' vector parts, −q⃗ (a sign flip, as Eigen's conjugate()).
    const Two qx{-b0.q.x(), -b1.q.x()};
    const Two qy{-b0.q.y(), -b1.q.y()};
    const Two qz{-b0.q.z(), -b1.q.z()};
    const Two w{b0.q.w(), b1.q.w()};
    const Two vx{point0.x() - b0.x.x(), point1.x() - b1.x.x()};
    const Two vy{point0.y() - b0.x.y(), point1.y() - b1.x.y()};
    const Two vz{point0.z() - b0.x.z(), point1.z() - b1.x.z()};
    Two ux = qy * vz - qz * vy;
    Two uy = qz * vx - qx * vz;
    Two uz = qx * vy - qy * vx;
    ux = ux + ux;
    uy = uy + uy;
    uz = uz + uz;
    const Two rx = (vx + w * ux) + (qy * uz - qz * uy);
    const Two ry = (vy + w * uy) + (qz * ux - qx * uz);
    const Two rz = (vz + w * uz) + (qx * uy - qy * ux);
    out.push_back({.local0 = Vec3(rx[0], ry[0], rz[0]),
                   .local1 = Vec3(rx[1], ry[1], rz[1]),
                   .normal = normal,
                   .feature = feature});
}

/// Sphere (a, pose pa) against sphere (b, pose pb): collideSphereSphere's point on the line of
/// centres, kept while its gap is within `margin`. Returns the points added (0 or 1).
[[gnu::always_inline]] inline int appendSphereSphereContact(const Body& b0, const Pose& pa,
                                                            const Body& b1, const Pose& pb,
                                                            double margin,
                                                            std::vector<Contact>& out) {
    const double ra = b0.shape.radius;
    const double rb = b1.shape.radius;
    const Vec3 d = pa.position - pb.position;
    const double distance = d.norm();
    if (distance - ra - rb > margin) return 0;
    // Coincident centres: any direction separates them; +y is as good as another.
    const Vec3 n = distance > kDirectionEpsilon ? Vec3(d / distance) : Vec3::UnitY();
    const Vec3 point0 = pa.position - ra * n;
    const Vec3 point1 = pb.position + rb * n;
    const double depth = (point1 - point0).dot(n);
    if (!(depth >= -margin)) return 0;
    appendContactInBodyFrames(b0, b1, point0, point1, n, out);
    return 1;
}

/// The sphere's point `onSphere` and the other body's `onOther`, with the normal n from the
/// other body to the sphere, kept when they overlap or lie within the margin, in the pair's
/// order: `sphereFirst` says whether the sphere is the pair's body 0; otherwise the point is
/// stored the other way round with the normal flipped, as the dispatch table's swapped slot
/// does. Returns the points added (0 or 1).
[[gnu::always_inline]] inline int appendSphereContact(const Body& sphere, const Body& other, const Vec3& onSphere,
                                                      const Vec3& onOther, const Vec3& n, bool sphereFirst,
                                                      double margin, std::vector<Contact>& out) {
    const double depth = (onOther - onSphere).dot(n);
    if (!(depth >= -margin)) return 0;
    if (sphereFirst)
        appendContactInBodyFrames(sphere, other, onSphere, onOther, n, out);
    else
        appendContactInBodyFrames(other, sphere, onOther, onSphere, Vec3(-n), out);
    return 1;
}

/// Sphere body `sphere` (pose ps) against plane body `plane`: collideSpherePlane's point below
/// the centre, stored as appendSphereContact says. Returns the points added (0 or 1).
[[gnu::always_inline]] inline int appendSpherePlaneContact(const Body& sphere, const Pose& ps,
                                                           const Body& plane, bool sphereFirst,
                                                           double margin,
                                                           std::vector<Contact>& out) {
    // unitPlane (primitive_geometry.h): a zero normal means +y.
    const Shape& shape = plane.shape;
    const double length = shape.normal.norm();
    const bool unit = length > kDirectionEpsilon;
    const Vec3 normal = unit ? Vec3(shape.normal / length) : Vec3(Vec3::UnitY());
    const double offset = unit ? shape.offset / length : shape.offset;
    const double height = normal.dot(ps.position) - offset;
    return appendSphereContact(sphere, plane, ps.position - sphere.shape.radius * normal,
                               ps.position - height * normal, normal, sphereFirst, margin, out);
}

/// Sphere body `sphere` (pose ps) against box body `box` (pose pb): collideSphereBox's point
/// (primitive::sphereBoxPoints), the sphere's centre against its closest point of the box (or, from inside, of the nearest
/// face), stored as appendSphereContact says. Returns the points added (0 or 1).
[[gnu::always_inline]] inline int appendSphereBoxContact(const Body& sphere, const Pose& ps,
                                                         const Body& box, const Pose& pb,
                                                         bool sphereFirst, double margin,
                                                         std::vector<Contact>& out) {
    primitive::SphereBoxPoints points;
    if (!primitive::sphereBoxPoints(ps.position, sphere.shape.radius, pb, primitive::halfExtents(box.shape), margin,
                                    points))
        return 0;
    return appendSphereContact(sphere, box, points.onSphere, points.onBox, points.normal, sphereFirst, margin, out);
}

/// The fast path's pairs: sphere – sphere, sphere – plane and sphere – box in either order.
/// Appends their point and returns its count, or −1 for any other pair (the general
/// narrowphase's).
[[gnu::always_inline]] inline int appendSpherePairContacts(const Body& b0, const Pose& pose0,
                                                           const Body& b1, const Pose& pose1,
                                                           double margin,
                                                           std::vector<Contact>& out) {
    const ShapeType t0 = b0.shape.type;
    const ShapeType t1 = b1.shape.type;
    if (t0 == ShapeType::Sphere) {
        if (t1 == ShapeType::Sphere)
            return appendSphereSphereContact(b0, pose0, b1, pose1, margin, out);
        if (t1 == ShapeType::Plane)
            return appendSpherePlaneContact(b0, pose0, b1, true, margin, out);
        if (t1 == ShapeType::Box)
            return appendSphereBoxContact(b0, pose0, b1, pose1, true, margin, out);
    } else if (t1 == ShapeType::Sphere) {
        if (t0 == ShapeType::Plane)
            return appendSpherePlaneContact(b1, pose1, b0, false, margin, out);
        if (t0 == ShapeType::Box)
            return appendSphereBoxContact(b1, pose1, b0, pose0, false, margin, out);
    }
    return -1;
}

}  // namespace substep

// Tests engine/physics/collision/narrowphase.cpp and the primitive pair functions
// (collide_sphere.cpp, collide_capsule.cpp, collide_box.cpp, collide_box_box.cpp): depths and
// normals of configurations with known answers, both argument orders, and on random poses the
// geometric facts every contact must satisfy (points on the two surfaces, unit normals,
// depth = (point1 − point0)·normal).

#include "physics/collision/narrowphase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace substep {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTol = 1e-9;

Pose at(const Vec3& position, const Quat& rotation = Quat::Identity()) {
    return {position, rotation};
}

Quat turn(double angle, const Vec3& axis) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

/// Signed distance from p to the shape's surface, written from the shape's definition.
double signedDistance(const Shape& shape, const Pose& pose, const Vec3& p) {
    const Vec3 local = pose.applyInverse(p);
    switch (shape.type) {
        case ShapeType::Sphere:
            return local.norm() - shape.radius;
        case ShapeType::Box: {
            const Vec3 q = local.cwiseAbs() - 0.5 * shape.size;
            return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
        }
        case ShapeType::Capsule: {
            const double y = std::clamp(local.y(), -0.5 * shape.length, 0.5 * shape.length);
            return (local - Vec3(0, y, 0)).norm() - shape.radius;
        }
        case ShapeType::Plane: {
            const double n = shape.normal.norm();
            return (shape.normal.dot(p) - shape.offset) / n;
        }
        default:
            return 0.0;
    }
}

/// The facts every contact satisfies, whatever the configuration.
void expectValidContacts(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, const ContactManifold& m) {
    ASSERT_GE(m.count, 0);
    ASSERT_LE(m.count, kMaxContactPoints);
    for (int k = 0; k < m.count; ++k) {
        const ContactPoint& c = m.points[k];
        ASSERT_TRUE(c.point0.allFinite() && c.point1.allFinite() && c.normal.allFinite());
        ASSERT_TRUE(std::isfinite(c.depth));
        EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
        EXPECT_NEAR(c.depth, (c.point1 - c.point0).dot(c.normal), 1e-12);
        EXPECT_GE(c.depth, -margin - 1e-12);
        EXPECT_NEAR(signedDistance(a, pa, c.point0), 0.0, kTol) << "point0 off shape 0, k=" << k;
        EXPECT_NEAR(signedDistance(b, pb, c.point1), 0.0, kTol) << "point1 off shape 1, k=" << k;
    }
}

/// What collide() in the two argument orders must agree on. Different shape types go through
/// the same pair function, so the second order is the exact mirror of the first. Two shapes of
/// the same type go through it with the roles exchanged: the features chosen may differ (box a's
/// faces are preferred as reference), the deepest penetration may not.
enum class Orders { Mirror, SameDepth, Independent };

/// collide() in both orders, both checked for the facts of every contact and against each
/// other as `orders` says (by default Mirror for different types, SameDepth for equal ones).
/// Returns the manifold for (a, b).
ContactManifold collideBothOrders(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                                  double margin = 0.0, std::optional<Orders> orders = {}) {
    ContactManifold ab;
    ContactManifold ba;
    collide(a, pa, b, pb, margin, ab);
    collide(b, pb, a, pa, margin, ba);
    expectValidContacts(a, pa, b, pb, margin, ab);
    expectValidContacts(b, pb, a, pa, margin, ba);
    const Orders check = orders.value_or(a.type == b.type ? Orders::SameDepth : Orders::Mirror);
    if (check == Orders::Independent) return ab;
    EXPECT_EQ(ab.count, ba.count);
    if (check == Orders::SameDepth) {
        if (ab.count > 0 && ba.count > 0) {
            double deepestAB = -1e300;
            double deepestBA = -1e300;
            for (int k = 0; k < ab.count; ++k)
                deepestAB = std::max(deepestAB, ab.points[k].depth);
            for (int k = 0; k < ba.count; ++k)
                deepestBA = std::max(deepestBA, ba.points[k].depth);
            EXPECT_NEAR(deepestAB, deepestBA, 1e-6);  // tilted faces measure alike, not equal
        }
        return ab;
    }
    for (int k = 0; k < std::min(ab.count, ba.count); ++k) {
        EXPECT_NEAR((ab.points[k].normal + ba.points[k].normal).norm(), 0.0, 1e-12);
        EXPECT_NEAR(ab.points[k].depth, ba.points[k].depth, 1e-12);
        EXPECT_NEAR((ab.points[k].point0 - ba.points[k].point1).norm(), 0.0, 1e-12);
        EXPECT_NEAR((ab.points[k].point1 - ba.points[k].point0).norm(), 0.0, 1e-12);
        EXPECT_EQ(ab.points[k].feature, ba.points[k].feature);
    }
    return ab;
}

/// Against a plane, whose pose is ignored.
ContactManifold collideBothOrders(const Shape& a, const Pose& pa, const Shape& plane,
                                  double margin = 0.0) {
    return collideBothOrders(a, pa, plane, Pose{}, margin);
}

void expectVecNear(const Vec3& actual, const Vec3& expected, double tol = 1e-9) {
    EXPECT_NEAR((actual - expected).norm(), 0.0, tol)
        << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

double maxDepth(const ContactManifold& m) {
    double d = -1e300;
    for (int k = 0; k < m.count; ++k)
        d = std::max(d, m.points[k].depth);
    return d;
}

// ---- Dispatch -----------------------------------------------------------------------------

TEST(NarrowphaseDispatch, PrimitivePairsInBothOrders) {
    const ShapeType primitives[] = {ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule};
    for (ShapeType x : primitives) {
        for (ShapeType y : primitives)
            EXPECT_TRUE(canCollide(x, y));
        EXPECT_TRUE(canCollide(x, ShapeType::Plane));
        EXPECT_TRUE(canCollide(ShapeType::Plane, x));
    }
}

TEST(NarrowphaseDispatch, PlanePlaneAndNoneNeverCollide) {
    EXPECT_FALSE(canCollide(ShapeType::Plane, ShapeType::Plane));
    for (int t = 0; t <= static_cast<int>(ShapeType::Spline); ++t) {
        EXPECT_FALSE(canCollide(ShapeType::None, static_cast<ShapeType>(t)));
        EXPECT_FALSE(canCollide(static_cast<ShapeType>(t), ShapeType::None));
    }
    ContactManifold m;
    m.count = 3;  // collide() clears even when the pair has no function
    collide(planeShape(Vec3::UnitY(), 0), Pose{}, planeShape(Vec3::UnitY(), 0), Pose{}, 1.0, m);
    EXPECT_EQ(m.count, 0);
}

// ---- Sphere -------------------------------------------------------------------------------

TEST(SphereSphere, OverlapAlongTheLineOfCentres) {
    const ContactManifold m = collideBothOrders(sphereShape(1.0), at(Vec3(0, 0, 0)),
                                                sphereShape(1.0), at(Vec3(1.5, 0, 0)));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.5, 1e-12);
    expectVecNear(m.points[0].normal, Vec3(-1, 0, 0));
    expectVecNear(m.points[0].point0, Vec3(1, 0, 0));
    expectVecNear(m.points[0].point1, Vec3(0.5, 0, 0));
}

TEST(SphereSphere, SpeculativeWithinMarginOnly) {
    const Shape s = sphereShape(0.5);
    ContactManifold m;
    collide(s, at(Vec3(0, 0, 0)), s, at(Vec3(0, 1.03, 0)), 0.05, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, -0.03, 1e-12);
    collide(s, at(Vec3(0, 0, 0)), s, at(Vec3(0, 1.03, 0)), 0.02, m);
    EXPECT_EQ(m.count, 0);
}

TEST(SphereSphere, CoincidentCentresGiveAFiniteUnitNormal) {
    const ContactManifold m =
        collideBothOrders(sphereShape(0.3), at(Vec3(1, 2, 3)), sphereShape(0.2), at(Vec3(1, 2, 3)));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.5, 1e-12);
}

TEST(SpherePlane, DepthBelowThePlane) {
    // Non-unit normal: 2y = 0.4 is the plane y = 0.2.
    const ContactManifold m =
        collideBothOrders(sphereShape(1.0), at(Vec3(3, 0.8, -1)), planeShape(Vec3(0, 2, 0), 0.4));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.4, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitY());
    expectVecNear(m.points[0].point1, Vec3(3, 0.2, -1));
}

TEST(SphereBox, FaceEdgeAndInside) {
    const Shape box = boxShape(Vec3(2, 2, 2));
    const Shape ball = sphereShape(0.5);
    // Beside the +x face.
    ContactManifold m = collideBothOrders(ball, at(Vec3(1.3, 0.2, -0.4)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.2, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitX());
    // Over the edge x = y = 1.
    m = collideBothOrders(ball, at(Vec3(1.2, 1.2, 0)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.5 - 0.2 * std::sqrt(2.0), 1e-12);
    expectVecNear(m.points[0].normal, Vec3(1, 1, 0).normalized());
    // Centre inside, nearest the +x face.
    m = collideBothOrders(ball, at(Vec3(0.9, 0.1, 0)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.6, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitX());
}

TEST(SphereBox, RotatedBoxCorner) {
    // A 2 m cube turned 45° about z has a top edge at y = √2.
    const ContactManifold m =
        collideBothOrders(sphereShape(0.5), at(Vec3(0, std::sqrt(2.0) + 0.4, 0)),
                          boxShape(Vec3(2, 2, 2)), at(Vec3::Zero(), turn(kPi / 4, Vec3::UnitZ())));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitY());
}

TEST(SphereBox, CentreOnAFaceOrAtTheCentreIsFinite) {
    const Shape box = boxShape(Vec3(2, 4, 6));
    ContactManifold m =
        collideBothOrders(sphereShape(0.5), at(Vec3(0.3, 2.0, 0.1)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.5, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitY());
    // At the centre: leaves through the nearest face (x, half extent 1).
    m = collideBothOrders(sphereShape(0.5), at(Vec3::Zero()), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 1.5, 1e-12);
    EXPECT_NEAR(std::abs(m.points[0].normal.x()), 1.0, 1e-12);
}

TEST(SphereCapsule, SideEndAndAxis) {
    const Shape capsule = capsuleShape(0.5, 2.0);
    const Shape ball = sphereShape(0.5);
    ContactManifold m = collideBothOrders(ball, at(Vec3(0.9, 0.3, 0)), capsule, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitX());
    m = collideBothOrders(ball, at(Vec3(0, 1.9, 0)), capsule, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitY());
    // Centre on the axis: leaves sideways.
    m = collideBothOrders(ball, at(Vec3(0, 0.4, 0)), capsule, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 1.0, 1e-12);
    EXPECT_NEAR(m.points[0].normal.y(), 0.0, 1e-12);
}

// ---- Capsule ------------------------------------------------------------------------------

TEST(CapsuleCapsule, CrossingGivesOnePoint) {
    const Shape c = capsuleShape(0.5, 2.0);
    const ContactManifold m = collideBothOrders(
        c, at(Vec3::Zero()), c, at(Vec3(0.2, 0.3, 0.9), turn(kPi / 2, Vec3::UnitZ())));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    expectVecNear(m.points[0].normal, -Vec3::UnitZ());
    expectVecNear(m.points[0].point0, Vec3(0, 0.3, 0.5));
}

TEST(CapsuleCapsule, ParallelOverlapGivesTwoPoints) {
    const Shape c = capsuleShape(0.5, 2.0);
    // b's segment spans y in [-0.5, 1.5]; the overlap with a's [-1, 1] is [-0.5, 1].
    const ContactManifold m = collideBothOrders(c, at(Vec3::Zero()), c, at(Vec3(0.9, 0.5, 0)));
    ASSERT_EQ(m.count, 2);
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.1, 1e-12);
        expectVecNear(m.points[k].normal, -Vec3::UnitX());
    }
    std::vector<double> ys = {m.points[0].point0.y(), m.points[1].point0.y()};
    std::sort(ys.begin(), ys.end());
    EXPECT_NEAR(ys[0], -0.5, 1e-12);
    EXPECT_NEAR(ys[1], 1.0, 1e-12);
}

TEST(CapsuleCapsule, SlightlyCrossingKeepsTheDeepestPoint) {
    // Long capsules 1° apart, crossing in the middle 0.9 apart: the closest point is between
    // the overlap's ends.
    const Shape c = capsuleShape(0.5, 10.0);
    const ContactManifold m = collideBothOrders(
        c, at(Vec3::Zero()), c, at(Vec3(0, 0, 0.9), turn(kPi / 180, Vec3::UnitZ())), 0.1);
    ASSERT_GE(m.count, 1);
    EXPECT_NEAR(maxDepth(m), 0.1, 1e-9);
}

TEST(CapsuleCapsule, CoaxialAndZeroLengthAreFinite) {
    const Shape c = capsuleShape(0.5, 2.0);
    ContactManifold m = collideBothOrders(c, at(Vec3(1, 1, 1)), c, at(Vec3(1, 1, 1)));
    ASSERT_GE(m.count, 1);
    EXPECT_NEAR(maxDepth(m), 1.0, 1e-12);
    // A zero-length capsule is a sphere.
    m = collideBothOrders(capsuleShape(0.5, 0.0), at(Vec3(0.9, 0.3, 0)), c, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    m = collideBothOrders(capsuleShape(0.5, 0.0), at(Vec3(0, 0.3, 0)), capsuleShape(0.5, 0.0),
                          at(Vec3(0, 0.3, 0)));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 1.0, 1e-12);
}

TEST(CapsulePlane, LyingFlatGivesBothEnds) {
    const ContactManifold m =
        collideBothOrders(capsuleShape(0.5, 2.0), at(Vec3(0, 0.4, 0), turn(kPi / 2, Vec3::UnitZ())),
                          planeShape(Vec3::UnitY(), 0.0));
    ASSERT_EQ(m.count, 2);
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.1, 1e-12);
        expectVecNear(m.points[k].normal, Vec3::UnitY());
        EXPECT_NEAR(std::abs(m.points[k].point0.x()), 1.0, 1e-12);
    }
    EXPECT_NE(m.points[0].feature, m.points[1].feature);
}

TEST(CapsulePlane, StandingGivesTheLowerEnd) {
    const Shape c = capsuleShape(0.5, 2.0);
    ContactManifold m = collideBothOrders(c, at(Vec3(0, 1.4, 0)), planeShape(Vec3::UnitY(), 0.0));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    expectVecNear(m.points[0].point0, Vec3(0, -0.1, 0));
    // With a margin beyond the length, the upper end's lowest point comes too: its rim, 2.4 up.
    m = collideBothOrders(c, at(Vec3(0, 1.4, 0)), planeShape(Vec3::UnitY(), 0.0), 5.0);
    ASSERT_EQ(m.count, 2);
    EXPECT_NEAR(std::min(m.points[0].depth, m.points[1].depth), -2.4, 1e-12);
}

TEST(CapsuleBox, LyingOnAFaceGivesTwoPoints) {
    const Shape box = boxShape(Vec3(4, 1, 4));
    const Shape c = capsuleShape(0.5, 2.0);
    const Quat alongX = turn(kPi / 2, Vec3::UnitZ());
    ContactManifold m = collideBothOrders(c, at(Vec3(0, 0.9, 0.3), alongX), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 2);
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.1, 1e-12);
        expectVecNear(m.points[k].normal, Vec3::UnitY());
        EXPECT_NEAR(std::abs(m.points[k].point1.x()), 1.0, 1e-12);
    }
    // Hanging over the edge x = 2: the segment x in [0.5, 2.5] clipped to the face.
    m = collideBothOrders(c, at(Vec3(1.5, 0.9, 0), alongX), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 2);
    std::vector<double> xs = {m.points[0].point1.x(), m.points[1].point1.x()};
    std::sort(xs.begin(), xs.end());
    EXPECT_NEAR(xs[0], 0.5, 1e-12);
    EXPECT_NEAR(xs[1], 2.0, 1e-12);
}

TEST(CapsuleBox, StandingAndAcrossAnEdge) {
    const Shape box = boxShape(Vec3(4, 1, 4));
    const Shape c = capsuleShape(0.5, 2.0);
    ContactManifold m = collideBothOrders(c, at(Vec3(0.2, 1.9, 0)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
    expectVecNear(m.points[0].point1, Vec3(0.2, 0.5, 0));
    // Along z, beside the edge x = 2, y = 0.5.
    m = collideBothOrders(c, at(Vec3(2.3, 0.8, 0), turn(kPi / 2, Vec3::UnitX())), box,
                          at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.5 - 0.3 * std::sqrt(2.0), 1e-9);
    expectVecNear(m.points[0].normal, Vec3(1, 1, 0).normalized(), 1e-7);
}

TEST(CapsuleBox, SegmentEnteringTheBox) {
    const Shape box = boxShape(Vec3(2, 2, 2));
    const Shape c = capsuleShape(0.5, 2.0);
    // Standing with its lower end 0.2 inside the top face: the face, radius plus 0.2 deep.
    ContactManifold m = collideBothOrders(c, at(Vec3(0.3, 1.8, 0)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.7, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitY());
    // Along z, the axis just inside the edge x = y = 1: the least way out of the segment is
    // through the x face (the first of two equal ones), the segment lying along it: 2 points.
    // Just outside, the edge pushes along the diagonal; the depth is continuous across.
    const Quat alongZ = turn(kPi / 2, Vec3::UnitX());
    const double inside = 0.01 / std::sqrt(2.0);
    m = collideBothOrders(c, at(Vec3(1 - inside, 1 - inside, 0), alongZ), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 2);
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.5 + inside, 1e-12);
        expectVecNear(m.points[k].normal, Vec3::UnitX());
    }
    // A zero-length capsule inside the box is a sphere: out through the nearest face.
    m = collideBothOrders(capsuleShape(0.5, 0.0), at(Vec3(0.1, 0.2, 0)), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 1.3, 1e-12);
    expectVecNear(m.points[0].normal, Vec3::UnitY());
    // The segment cutting across the edge y = z = 1 at 0.01 inside both faces: the edge's
    // axis (the diagonal), √2·0.01 deep plus the radius, at the edge.
    m = collideBothOrders(c, at(Vec3(0.2, 0.99, 0.99), turn(-kPi / 4, Vec3::UnitX())), box,
                          at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.5 + std::sqrt(2.0) * 0.01, 1e-12);
    expectVecNear(m.points[0].normal, Vec3(0, 1, 1).normalized());
    expectVecNear(m.points[0].point1, Vec3(0.2, 1, 1));
    m = collideBothOrders(c, at(Vec3(1 + inside, 1 + inside, 0), alongZ), box, at(Vec3::Zero()));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.49, 1e-9);
    expectVecNear(m.points[0].normal, Vec3(1, 1, 0).normalized(), 1e-7);
}

// ---- Box ----------------------------------------------------------------------------------

TEST(BoxPlane, RestingFlatGivesFourCorners) {
    const ContactManifold m = collideBothOrders(boxShape(Vec3(1, 1, 1)), at(Vec3(2, 0.49, 3)),
                                                planeShape(Vec3::UnitY(), 0.0));
    ASSERT_EQ(m.count, 4);
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.01, 1e-12);
        EXPECT_NEAR(std::abs(m.points[k].point0.x() - 2.0), 0.5, 1e-12);
        EXPECT_NEAR(std::abs(m.points[k].point0.z() - 3.0), 0.5, 1e-12);
        EXPECT_NEAR(m.points[k].point1.y(), 0.0, 1e-12);
    }
}

TEST(BoxPlane, OnAnEdgeAndSpeculative) {
    const Shape box = boxShape(Vec3(1, 1, 1));
    const double halfDiagonal = std::sqrt(0.5);
    ContactManifold m =
        collideBothOrders(box, at(Vec3(0, halfDiagonal - 0.02, 0), turn(kPi / 4, Vec3::UnitZ())),
                          planeShape(Vec3::UnitY(), 0.0));
    ASSERT_EQ(m.count, 2);
    EXPECT_NEAR(m.points[0].depth, 0.02, 1e-12);
    m = collideBothOrders(box, at(Vec3(0, 0.52, 0)), planeShape(Vec3::UnitY(), 0.0), 0.05);
    ASSERT_EQ(m.count, 4);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(m.points[k].depth, -0.02, 1e-12);
    m = collideBothOrders(box, at(Vec3(0, 0.52, 0)), planeShape(Vec3::UnitY(), 0.0), 0.01);
    EXPECT_EQ(m.count, 0);
}

TEST(BoxBox, RestingGivesFourCornersEveryTime) {
    const Shape ground = boxShape(Vec3(4, 1, 4));
    const Shape crate = boxShape(Vec3(1, 1, 1));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-1e-6, 1e-6);
    uint32_t referenceFace = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Quat tilt =
            trial == 0 ? Quat::Identity()
                       : turn(jitter(rng),
                              Vec3(jitter(rng), 1e-6, jitter(rng)).normalized() + Vec3(1, 0, 0));
        const Pose crateAt = at(Vec3(0.3 + jitter(rng), 0.99 + jitter(rng), -0.2), tilt);
        const ContactManifold m = collideBothOrders(ground, at(Vec3::Zero()), crate, crateAt);
        ASSERT_EQ(m.count, 4) << "trial " << trial;
        for (int k = 0; k < 4; ++k) {
            EXPECT_NEAR(m.points[k].depth, 0.01, 1e-5);
            expectVecNear(m.points[k].normal, -Vec3::UnitY(), 1e-5);
            // point1 is on the crate: its bottom corners.
            EXPECT_NEAR(std::abs(m.points[k].point1.x() - 0.3), 0.5, 1e-5);
            EXPECT_NEAR(std::abs(m.points[k].point1.z() + 0.2), 0.5, 1e-5);
            if (trial == 0) referenceFace = m.points[0].feature >> 12;
            EXPECT_EQ(m.points[k].feature >> 12, referenceFace) << "reference face flipped";
        }
        // Four distinct features (the corners).
        std::vector<uint32_t> features;
        for (int k = 0; k < 4; ++k)
            features.push_back(m.points[k].feature);
        std::sort(features.begin(), features.end());
        EXPECT_EQ(std::unique(features.begin(), features.end()), features.end());
    }
}

TEST(BoxBox, StackOfEqualCubesKeepsItsFeatures) {
    // Equal cubes on each other: both boxes' faces are equally good reference faces, in both
    // argument orders; small settling motions must not change the choice or the features.
    const Shape cube = boxShape(Vec3(0.5, 0.5, 0.5));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(-5e-5, 5e-5);
    for (int order = 0; order < 2; ++order) {
        std::vector<uint32_t> firstFeatures;
        for (int trial = 0; trial < 200; ++trial) {
            const Pose lower = at(Vec3(jitter(rng), 0.25 + jitter(rng), jitter(rng)),
                                  turn(jitter(rng), Vec3(jitter(rng), jitter(rng), 5e-5)));
            const Pose upper = at(Vec3(jitter(rng), 0.749 + jitter(rng), jitter(rng)),
                                  turn(jitter(rng), Vec3(5e-5, jitter(rng), jitter(rng))));
            ContactManifold m;
            if (order == 0) {
                m = collideBothOrders(cube, upper, cube, lower);
            } else {
                m = collideBothOrders(cube, lower, cube, upper);
            }
            ASSERT_EQ(m.count, 4) << "order " << order << " trial " << trial;
            std::vector<uint32_t> features;
            for (int k = 0; k < 4; ++k) {
                EXPECT_NEAR(m.points[k].depth, 0.001, 1e-3);
                features.push_back(m.points[k].feature);
            }
            std::sort(features.begin(), features.end());
            if (trial == 0) firstFeatures = features;
            EXPECT_EQ(features, firstFeatures) << "order " << order << " trial " << trial;
        }
    }
}

TEST(BoxBox, BigOnSmallGivesTheSmallFaceCorners) {
    const ContactManifold m = collideBothOrders(boxShape(Vec3(3, 1, 3)), at(Vec3(0.1, 0.99, 0)),
                                                boxShape(Vec3(1, 1, 1)), at(Vec3::Zero()));
    ASSERT_EQ(m.count, 4);
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.01, 1e-12);
        expectVecNear(m.points[k].normal, Vec3::UnitY());
        EXPECT_NEAR(std::abs(m.points[k].point1.x()), 0.5, 1e-12);
        EXPECT_NEAR(std::abs(m.points[k].point1.z()), 0.5, 1e-12);
    }
}

TEST(BoxBox, TurnedFortyFiveDegreesKeepsAtMostFourPointsInBothFaces) {
    const Shape cube = boxShape(Vec3(1, 1, 1));
    const Pose lower = at(Vec3::Zero());
    const Pose upper = at(Vec3(0, 0.98, 0), turn(kPi / 4, Vec3::UnitY()));
    const ContactManifold m = collideBothOrders(cube, lower, cube, upper);
    ASSERT_GE(m.count, 3);
    ASSERT_LE(m.count, 4);
    std::vector<Vec3> onFace;
    for (int k = 0; k < m.count; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.02, 1e-12);
        // Inside the lower cube's top face and the upper cube's bottom face.
        const Vec3 inLower = lower.applyInverse(m.points[k].point0);
        const Vec3 inUpper = upper.applyInverse(m.points[k].point1);
        EXPECT_LE(std::max(std::abs(inLower.x()), std::abs(inLower.z())), 0.5 + 1e-12);
        EXPECT_LE(std::max(std::abs(inUpper.x()), std::abs(inUpper.z())), 0.5 + 1e-12);
        EXPECT_NEAR(inLower.y(), 0.5, 1e-12);
        EXPECT_NEAR(inUpper.y(), -0.5, 1e-12);
        onFace.push_back(inLower);
    }
    // The octagon (area 4(√2 − 1)/... = 0.828) reduced to 4 of its vertices keeps most of it.
    ASSERT_EQ(m.count, 4);
    // Order around the centre, then the shoelace area.
    std::sort(onFace.begin(), onFace.end(), [](const Vec3& p, const Vec3& q) {
        return std::atan2(p.z(), p.x()) < std::atan2(q.z(), q.x());
    });
    double area = 0.0;
    for (int k = 0; k < 4; ++k) {
        const Vec3& p = onFace[k];
        const Vec3& q = onFace[(k + 1) % 4];
        area += 0.5 * (p.x() * q.z() - q.x() * p.z());
    }
    const double octagon = 2.0 * (std::sqrt(2.0) - 1.0);
    EXPECT_GT(std::abs(area), 0.6 * octagon);
}

TEST(BoxBox, CrossingEdgesGiveOnePoint) {
    // a's top edge along z at y = √½, b's bottom edge along x at y = 2√½ − 0.01 − √½.
    const Shape cube = boxShape(Vec3(1, 1, 1));
    const double h = std::sqrt(0.5);
    const ContactManifold m =
        collideBothOrders(cube, at(Vec3::Zero(), turn(kPi / 4, Vec3::UnitZ())), cube,
                          at(Vec3(0, 2 * h - 0.01, 0), turn(kPi / 4, Vec3::UnitX())));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.01, 1e-12);
    expectVecNear(m.points[0].normal, -Vec3::UnitY());
    expectVecNear(m.points[0].point0, Vec3(0, h, 0));
    expectVecNear(m.points[0].point1, Vec3(0, h - 0.01, 0));
}

TEST(BoxBox, SpeculativeWithinMarginOnly) {
    const Shape cube = boxShape(Vec3(1, 1, 1));
    ContactManifold m =
        collideBothOrders(cube, at(Vec3::Zero()), cube, at(Vec3(0.2, 1.02, 0)), 0.05);
    ASSERT_EQ(m.count, 4);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(m.points[k].depth, -0.02, 1e-12);
    m = collideBothOrders(cube, at(Vec3::Zero()), cube, at(Vec3(0.2, 1.02, 0)), 0.01);
    EXPECT_EQ(m.count, 0);
}

TEST(BoxBox, IdenticalBoxesExactlyOverlappingAreFinite) {
    const Shape box = boxShape(Vec3(1, 2, 3));
    const Pose pose = at(Vec3(1, 2, 3), turn(0.3, Vec3(1, 2, 3)));
    const ContactManifold m = collideBothOrders(box, pose, box, pose);
    ASSERT_EQ(m.count, 4);
    // Separated the cheapest way: across the thinnest extent.
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(m.points[k].depth, 1.0, 1e-9);
}

// ---- Degenerate input ---------------------------------------------------------------------

TEST(NarrowphaseDegenerate, ZeroSizesAndHugeValuesStayFinite) {
    const std::vector<Shape> shapes = {sphereShape(0.0),
                                       boxShape(Vec3::Zero()),
                                       capsuleShape(0.0, 0.0),
                                       sphereShape(1.0),
                                       boxShape(Vec3(1, 0, 1)),
                                       capsuleShape(0.5, 0.0),
                                       planeShape(Vec3::UnitY(), 0.0)};
    const std::vector<Pose> poses = {at(Vec3::Zero()), at(Vec3(0, 1e-13, 0)),
                                     at(Vec3(1e6, -1e6, 1e6), turn(1.0, Vec3(1, 1, 0))),
                                     at(Vec3(0.5, 0.5, 0.5), turn(kPi / 2, Vec3::UnitX()))};
    for (const Shape& a : shapes) {
        for (const Shape& b : shapes) {
            if (!canCollide(a.type, b.type)) continue;
            for (const Pose& pa : poses) {
                for (const Pose& pb : poses) {
                    ContactManifold m;
                    collide(a, pa, b, pb, 1e7, m);
                    for (int k = 0; k < m.count; ++k) {
                        ASSERT_TRUE(m.points[k].point0.allFinite() &&
                                    m.points[k].point1.allFinite());
                        ASSERT_TRUE(std::isfinite(m.points[k].depth));
                        ASSERT_NEAR(m.points[k].normal.norm(), 1.0, 1e-12);
                    }
                }
            }
        }
    }
}

// ---- Random poses -------------------------------------------------------------------------

Quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    Quat q(g(rng), g(rng), g(rng), g(rng));
    return q.normalized();
}

Shape randomShape(ShapeType type, std::mt19937& rng) {
    std::uniform_real_distribution<double> size(0.1, 1.2);
    switch (type) {
        case ShapeType::Sphere:
            return sphereShape(size(rng));
        case ShapeType::Box:
            return boxShape(Vec3(size(rng), size(rng), size(rng)));
        case ShapeType::Capsule:
            return capsuleShape(0.5 * size(rng), size(rng));
        default:
            return planeShape(Vec3(0.2, 1.0, -0.3), 0.1);
    }
}

TEST(NarrowphaseRandom, PointsLieOnBothSurfaces) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> position(-0.8, 0.8);
    const ShapeType types[] = {ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule,
                               ShapeType::Plane};
    int contacts = 0;
    for (ShapeType ta : types) {
        for (ShapeType tb : types) {
            if (!canCollide(ta, tb)) continue;
            for (int trial = 0; trial < 300; ++trial) {
                const Shape a = randomShape(ta, rng);
                const Shape b = randomShape(tb, rng);
                const Pose pa =
                    at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
                const Pose pb =
                    at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
                const ContactManifold m = collideBothOrders(
                    a, pa, b, pb, 0.1, ta == tb ? Orders::Independent : Orders::Mirror);
                contacts += m.count;
                if (HasFailure()) {
                    ADD_FAILURE() << "pair " << static_cast<int>(ta) << "-" << static_cast<int>(tb)
                                  << " trial " << trial;
                    return;
                }
            }
        }
    }
    EXPECT_GT(contacts, 1000);
}

/// The deepest reported depth against the closed form for pairs with a sphere: the sphere's
/// radius minus the other shape's signed distance at the centre.
TEST(NarrowphaseRandom, SphereDepthIsRadiusMinusSignedDistance) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> position(-0.8, 0.8);
    const ShapeType others[] = {ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule,
                                ShapeType::Plane};
    for (ShapeType tb : others) {
        for (int trial = 0; trial < 300; ++trial) {
            const Shape a = randomShape(ShapeType::Sphere, rng);
            const Shape b = randomShape(tb, rng);
            const Pose pa = at(Vec3(position(rng), position(rng), position(rng)));
            const Pose pb =
                at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
            const double expected = a.radius - signedDistance(b, pb, pa.position);
            ContactManifold m;
            collide(a, pa, b, pb, 0.1, m);
            if (expected >= -0.1 + 1e-9) {
                ASSERT_EQ(m.count, 1);
                EXPECT_NEAR(m.points[0].depth, expected, 1e-9);
            } else if (expected < -0.1 - 1e-9) {
                EXPECT_EQ(m.count, 0);
            }
        }
    }
}

/// Boxes: whenever a corner of one box is inside the other, there are contacts, and the
/// deepest is at least as deep as that corner (the separating axis chosen penetrates least,
/// but never less than... any overlap means a contact).
TEST(NarrowphaseRandom, OverlappingBoxesAlwaysReportContacts) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> position(-0.9, 0.9);
    int overlapping = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Shape a = randomShape(ShapeType::Box, rng);
        const Shape b = randomShape(ShapeType::Box, rng);
        const Pose pa = at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
        const Pose pb = at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
        bool cornerInside = false;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 local(corner & 1 ? 0.5 : -0.5, corner & 2 ? 0.5 : -0.5,
                             corner & 4 ? 0.5 : -0.5);
            cornerInside |= signedDistance(a, pa, pb.apply(local.cwiseProduct(b.size))) < 0.0;
            cornerInside |= signedDistance(b, pb, pa.apply(local.cwiseProduct(a.size))) < 0.0;
        }
        ContactManifold m;
        collide(a, pa, b, pb, 0.0, m);
        if (cornerInside) {
            ++overlapping;
            EXPECT_GE(m.count, 1) << "trial " << trial;
            EXPECT_GT(maxDepth(m), 0.0) << "trial " << trial;
        }
    }
    EXPECT_GT(overlapping, 100);
}

/// Capsule against box: with the segment outside the box, the deepest depth is the radius
/// minus the least distance from the segment to the box (sampled finely); with the segment
/// entering the box, at least how deep the segment goes.
TEST(NarrowphaseRandom, CapsuleBoxDepthMatchesTheSegmentsDeepestPoint) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> position(-0.8, 0.8);
    int outsideCases = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        const Shape a = randomShape(ShapeType::Capsule, rng);
        const Shape b = randomShape(ShapeType::Box, rng);
        const Pose pa = at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
        const Pose pb = at(Vec3(position(rng), position(rng), position(rng)), randomRotation(rng));
        // The box's distance along the segment (a convex function): sampled, then refined by
        // ternary search next to the best sample.
        const auto distanceAt = [&](double u) {
            return signedDistance(b, pb, pa.apply(Vec3(0, (u - 0.5) * a.length, 0)));
        };
        double least = 1e300;
        int best = 0;
        for (int k = 0; k <= 2000; ++k) {
            const double d = distanceAt(k / 2000.0);
            if (d < least) {
                least = d;
                best = k;
            }
        }
        double lo = std::max(best - 1, 0) / 2000.0;
        double hi = std::min(best + 1, 2000) / 2000.0;
        for (int k = 0; k < 200; ++k) {
            const double u1 = lo + (hi - lo) / 3.0;
            const double u2 = hi - (hi - lo) / 3.0;
            if (distanceAt(u1) <= distanceAt(u2))
                hi = u2;
            else
                lo = u1;
        }
        least = std::min(least, distanceAt(0.5 * (lo + hi)));
        ContactManifold m;
        collide(a, pa, b, pb, 0.1, m);
        const double expected = a.radius - least;
        if (expected < -0.1 + 1e-3) continue;
        ASSERT_GE(m.count, 1) << "trial " << trial;
        if (least >= 0.0) {
            // Two-point contacts of a capsule lying at up to ~6° measure at the rim: r cos θ.
            ++outsideCases;
            EXPECT_LE(maxDepth(m), expected + 1e-9) << "trial " << trial;
            EXPECT_GE(maxDepth(m), expected - 1e-6 - 0.006 * a.radius) << "trial " << trial;
        } else {
            EXPECT_GE(maxDepth(m), -least - 1e-9) << "trial " << trial;
        }
    }
    EXPECT_GT(outsideCases, 100);
}

}  // namespace
}  // namespace substep

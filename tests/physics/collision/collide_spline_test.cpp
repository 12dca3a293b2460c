// Tests engine/physics/collision/collide_spline.cpp: sphere and capsule contacts with solid and
// hollow tubes against closed forms (straight wires, a ring), in world frames.

#include "physics/collision/collide_curved.h"
#include "physics/collision/spline_tube.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace substep {
namespace {

constexpr double kTol = 1e-9;

/// A straight wire along x through y = z = 0, from x = -2 to 2 in 1 m steps.
Shape straightWire(double radius, bool hollow = false) {
    return splineShape(makeSplineTube({{-2, 0, 0}, {-1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}},
                                      radius, false, hollow));
}

/// A closed ring of radius rho in the x–z plane through n points.
Shape ring(double rho, int n, double radius, bool hollow = false) {
    std::vector<Vec3> points;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * i / n;
        points.emplace_back(rho * std::cos(a), 0.0, rho * std::sin(a));
    }
    return splineShape(makeSplineTube(points, radius, true, hollow));
}

Pose at(const Vec3& p, const Quat& q = Quat::Identity()) {
    return {p, q};
}
const Pose kOrigin;  // identity

/// Every point obeys the manifold's convention.
void expectConsistent(const ContactManifold& m) {
    for (int i = 0; i < m.count; ++i) {
        const ContactPoint& p = m.points[i];
        EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
        EXPECT_NEAR((p.point1 - p.point0).dot(p.normal), p.depth, 1e-9);
        EXPECT_TRUE(p.point0.allFinite() && p.point1.allFinite());
    }
}

TEST(CollideSphereSpline, RestingOnAStraightWire) {
    const Shape wire = straightWire(0.01);
    const Shape ball = sphereShape(0.1);
    ContactManifold m;
    // Between control points, and exactly over one (where two segments meet).
    for (double x : {0.37, 0.0, 1.0}) {
        collideSphereSpline(ball, at({x, 0.109, 0}), wire, at(Vec3::Zero()), 0.0, m);
        ASSERT_EQ(m.count, 1) << "x = " << x;
        EXPECT_NEAR(m.points[0].depth, 0.001, kTol);
        EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitY(), 1e-12));
        EXPECT_TRUE(m.points[0].point1.isApprox(Vec3(x, 0.01, 0), 1e-12));
        EXPECT_TRUE(m.points[0].point0.isApprox(Vec3(x, 0.009, 0), 1e-12));
    }
}

TEST(CollideSphereSpline, FollowsThePoseOfTheWire) {
    // The wire turned 90° about z (now vertical) and moved: a sphere beside it at +x.
    const Quat turn(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
    const Vec3 origin(5, 1, -2);
    ContactManifold m;
    collideSphereSpline(sphereShape(0.2), at(origin + Vec3(0.25, 0.3, 0)), straightWire(0.1),
                        at(origin, turn), 0.0, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.05, kTol);
    EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitX(), 1e-12));
    expectConsistent(m);
}

TEST(CollideSphereSpline, MarginGivesSpeculativeContacts) {
    ContactManifold m;
    collideSphereSpline(sphereShape(0.1), at({0.5, 0.13, 0}), straightWire(0.01), kOrigin, 0.05, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, -0.02, kTol);
    collideSphereSpline(sphereShape(0.1), at({0.5, 0.13, 0}), straightWire(0.01), kOrigin, 0.01, m);
    EXPECT_EQ(m.count, 0);
}

TEST(CollideSphereSpline, BesideACurvedRing) {
    // 64 points on a unit circle: Catmull–Rom stays within ~1e-5 of the circle.
    const double rho = 1.0, R = 0.02, r = 0.1, delta = 0.003;
    const Shape wire = ring(rho, 64, R);
    ContactManifold m;
    for (double angle : {0.0, 0.3, 2.0, 4.5}) {
        const Vec3 radial(std::cos(angle), 0, std::sin(angle));
        // Outside the ring in its plane, inside it, and resting on top of the wire.
        collideSphereSpline(sphereShape(r), at((rho + R + r - delta) * radial), wire, kOrigin, 0.0,
                            m);
        ASSERT_EQ(m.count, 1);
        EXPECT_NEAR(m.points[0].depth, delta, 2e-5);
        EXPECT_NEAR(m.points[0].normal.dot(radial), 1.0, 1e-6);
        collideSphereSpline(sphereShape(r), at((rho - R - r + delta) * radial), wire, kOrigin, 0.0,
                            m);
        ASSERT_EQ(m.count, 1);
        EXPECT_NEAR(m.points[0].depth, delta, 2e-5);
        EXPECT_NEAR(m.points[0].normal.dot(-radial), 1.0, 1e-6);
        collideSphereSpline(sphereShape(r), at(rho * radial + Vec3(0, R + r - delta, 0)), wire,
                            kOrigin, 0.0, m);
        ASSERT_EQ(m.count, 1);
        EXPECT_NEAR(m.points[0].depth, delta, 2e-5);
        EXPECT_NEAR(m.points[0].normal.y(), 1.0, 1e-6);
        expectConsistent(m);
    }
}

TEST(CollideSphereSpline, CradledByARingGetsSymmetricSupport) {
    // A ball sitting in a small ring touches it all round: one point per local minimum of the
    // distance, with horizontal parts that cancel.
    const double rho = 0.1, R = 0.005, r = 0.2;
    const Shape wire = ring(rho, 8, R);
    const double h = 0.17;
    ContactManifold m;
    collideSphereSpline(sphereShape(r), at({0, h, 0}), wire, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 8);
    Vec3 sum = Vec3::Zero();
    for (int i = 0; i < m.count; ++i) {
        const ContactPoint& p = m.points[i];
        sum += p.normal;
        // Closed form for the curve point found: depth = R + r − |c − x|.
        const Vec3 onCurve = p.point1 - R * p.normal;
        EXPECT_NEAR(p.depth, R + r - (Vec3(0, h, 0) - onCurve).norm(), 1e-12);
        const double radial = std::hypot(onCurve.x(), onCurve.z());
        EXPECT_NEAR(radial, rho, 0.02 * rho);  // Catmull–Rom through 8 points of a circle
        EXPECT_NEAR(p.depth, R + r - std::hypot(rho, h), 0.002);
    }
    EXPECT_NEAR(sum.x(), 0.0, 1e-9);
    EXPECT_NEAR(sum.z(), 0.0, 1e-9);
    EXPECT_GT(sum.y(), 0.0);
    expectConsistent(m);
}

TEST(CollideSphereSpline, HollowPipeKeepsTheBallInside) {
    const double R = 0.1, r = 0.05;
    const Shape pipe = straightWire(R, true);
    ContactManifold m;
    // Centre 0.06 off the axis: depth e + r − R = 0.01, normal back towards the axis.
    const Vec3 off = Vec3(0, -0.6, 0.8) * 0.06;
    collideSphereSpline(sphereShape(r), at(Vec3(0.3, 0, 0) + off), pipe, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.01, kTol);
    EXPECT_TRUE(m.points[0].normal.isApprox(-off.normalized(), 1e-12));
    EXPECT_TRUE(m.points[0].point1.isApprox(Vec3(0.3, 0, 0) + R * off.normalized(), 1e-12));
    expectConsistent(m);
    // On the axis the ball is free.
    collideSphereSpline(sphereShape(r), at({0.3, 0, 0}), pipe, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
    // Past the open end the pipe no longer holds it.
    collideSphereSpline(sphereShape(r), at(Vec3(2.2, 0, 0) + off), pipe, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
}

TEST(CollideSphereSpline, HollowNormalsPointInwardsEverywhere) {
    const double R = 0.15, r = 0.1;
    const Shape pipe = ring(1.0, 12, R, true);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int contacts = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const Vec3 c(1.2 * u(rng), 0.15 * u(rng), 1.2 * u(rng));
        ContactManifold m;
        collideSphereSpline(sphereShape(r), at(c), pipe, kOrigin, 0.01, m);
        const SplinePoint axis = pipe.spline->closestPoint(c, 10.0);
        for (int i = 0; i < m.count; ++i) {
            ++contacts;
            // Towards the curve from the centre, and the centre within the pipe.
            EXPECT_GT(m.points[i].normal.dot(axis.point - c), 0.0);
            EXPECT_LE(std::sqrt(axis.distanceSquared), R + 1e-12);
        }
        expectConsistent(m);
    }
    EXPECT_GT(contacts, 50);
}

TEST(CollideCapsuleSpline, AcrossAWire) {
    const double R = 0.01, r = 0.05, delta = 0.002;
    // Capsule axis turned from y onto z: it lies across the wire (along x).
    const Quat across(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
    ContactManifold m;
    collideCapsuleSpline(capsuleShape(r, 0.6), at({0.3, R + r - delta, 0.1}, across),
                         straightWire(R), kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, delta, kTol);
    EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitY(), 1e-9));
    EXPECT_TRUE(m.points[0].point1.isApprox(Vec3(0.3, R, 0), 1e-9));
    EXPECT_TRUE(m.points[0].point0.isApprox(Vec3(0.3, R - delta, 0), 1e-9));
}

TEST(CollideCapsuleSpline, LyingAlongAWireIsSupportedAtBothEnds) {
    const double R = 0.01, r = 0.05, delta = 0.002;
    const Quat along(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));  // axis y -> -x
    ContactManifold m;
    collideCapsuleSpline(capsuleShape(r, 0.5), at({0.4, R + r - delta, 0}, along), straightWire(R),
                         kOrigin, 0.0, m);
    ASSERT_GE(m.count, 2);
    double lowest = 1e9, highest = -1e9;
    for (int i = 0; i < m.count; ++i) {
        EXPECT_NEAR(m.points[i].depth, delta, kTol);
        EXPECT_TRUE(m.points[i].normal.isApprox(Vec3::UnitY(), 1e-9));
        lowest = std::min(lowest, m.points[i].point1.x());
        highest = std::max(highest, m.points[i].point1.x());
    }
    EXPECT_NEAR(lowest, 0.15, 1e-9);
    EXPECT_NEAR(highest, 0.65, 1e-9);
    expectConsistent(m);
}

TEST(CollideSpline, DegenerateInputStaysFinite) {
    // All control points equal: a ball of the tube's radius. A sphere centred on it exactly.
    const Shape dot = splineShape(makeSplineTube({{0, 0, 0}, {0, 0, 0}}, 0.1, false));
    ContactManifold m;
    collideSphereSpline(sphereShape(0.2), at({0, 0, 0}), dot, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.3, kTol);
    expectConsistent(m);
    collideSphereSpline(sphereShape(0.2), at({0, 0.25, 0}), dot, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitY()));
    collideCapsuleSpline(capsuleShape(0.1, 0.0), at({0.5, 0.1, 0}), straightWire(0.1), kOrigin, 0.0,
                         m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.1, kTol);
    // A centre exactly on the wire's axis: some normal across the wire, full depth.
    collideSphereSpline(sphereShape(0.1), at({0.5, 0, 0}), straightWire(0.05), kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].normal.x(), 0.0, 1e-12);
    EXPECT_NEAR(m.points[0].depth, 0.15, kTol);
    expectConsistent(m);
    // No collision data: no contact.
    Shape empty{.type = ShapeType::Spline};
    collideSphereSpline(sphereShape(0.1), kOrigin, empty, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
}

}  // namespace
}  // namespace substep

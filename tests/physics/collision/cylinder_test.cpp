// Tests the cylinder shape: engine/physics/collision/collide_cylinder.cpp (its pairs through the
// narrowphase table), the cylinder cases of shape_bounds.cpp and mass_properties.cpp, and a
// cylinder in the world: resting flat and rolling down an incline, against closed forms.

#include "physics/collision/collide_cylinder.h"
#include "physics/collision/narrowphase.h"
#include "physics/collision/shape_bounds.h"
#include "physics/mass_properties.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace substep {
namespace {

constexpr double kPi = std::numbers::pi;

Quat turn(double angle, const Vec3& axis) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

/// The lowest point (along −n) of a cylinder's two rims, by sampling them finely: the geometry
/// the exact rim point must agree with.
Vec3 sampledLowestRimPoint(const Shape& cylinder, const Pose& pose, const Vec3& n) {
    constexpr int kSamples = 200000;
    Vec3 lowest = Vec3::Zero();
    double lowestHeight = std::numeric_limits<double>::infinity();
    for (const double side : {-1.0, 1.0}) {
        for (int k = 0; k < kSamples; ++k) {
            const double angle = 2.0 * kPi * k / kSamples;
            const Vec3 local(cylinder.radius * std::cos(angle), side * 0.5 * cylinder.length,
                             cylinder.radius * std::sin(angle));
            const Vec3 p = pose.apply(local);
            if (n.dot(p) < lowestHeight) lowestHeight = n.dot(p), lowest = p;
        }
    }
    return lowest;
}

/// Whether world point p lies on the cylinder's rim (a circle edge of a face).
void expectOnRim(const Shape& cylinder, const Pose& pose, const Vec3& p) {
    const Vec3 local = pose.applyInverse(p);
    EXPECT_NEAR(std::hypot(local.x(), local.z()), cylinder.radius, 1e-12);
    EXPECT_NEAR(std::abs(local.y()), 0.5 * cylinder.length, 1e-12);
}

// --- Mass properties and bounds ------------------------------------------------------------

TEST(CylinderMass, MatchesClosedFormAndATessellatedMesh) {
    const double r = 0.3, l = 0.8, density = 700.0;
    const MassProperties closed = shapeMassProperties(cylinderShape(r, l), density);
    const double mass = density * kPi * r * r * l;
    EXPECT_NEAR(closed.mass, mass, 1e-12 * mass);
    EXPECT_NEAR(closed.inertia(1, 1), 0.5 * mass * r * r, 1e-12 * mass);
    EXPECT_NEAR(closed.inertia(0, 0), mass * (3 * r * r + l * l) / 12.0, 1e-12 * mass);
    EXPECT_NEAR(closed.inertia(2, 2), mass * (3 * r * r + l * l) / 12.0, 1e-12 * mass);
    EXPECT_TRUE(closed.centerOfMass.isZero());

    // Independently: Blow–Binstock on a fine prism whose polygon has the circle's area (its
    // circumradius scaled so), which also has the circle's polar moment to O(1/N²).
    constexpr int kSides = 2000;
    TriangleMesh mesh;
    const double polygonArea = 0.5 * kSides * std::sin(2 * kPi / kSides);
    const double rr = r * std::sqrt(kPi / polygonArea);
    for (const double y : {-0.5 * l, 0.5 * l})
        for (int k = 0; k < kSides; ++k)
            mesh.vertices.emplace_back(rr * std::cos(2 * kPi * k / kSides), y, rr * std::sin(2 * kPi * k / kSides));
    mesh.vertices.emplace_back(0, -0.5 * l, 0);
    mesh.vertices.emplace_back(0, 0.5 * l, 0);
    const int bottom = 2 * kSides, top = 2 * kSides + 1;
    for (int k = 0; k < kSides; ++k) {
        const int k1 = (k + 1) % kSides;
        mesh.triangles.push_back({bottom, k, k1});
        mesh.triangles.push_back({top, kSides + k1, kSides + k});
        mesh.triangles.push_back({k, kSides + k, kSides + k1});
        mesh.triangles.push_back({k, kSides + k1, k1});
    }
    const MassProperties tessellated = meshMassProperties(mesh, density);
    EXPECT_NEAR(tessellated.mass, mass, 1e-9 * mass);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(closed.inertia(i, i), tessellated.inertia(i, i), 1e-5 * closed.inertia(i, i));
}

TEST(CylinderBounds, TightAroundTheRimsAndReachIsTheRimDistance) {
    const Shape coin = cylinderShape(0.5, 0.1);
    EXPECT_DOUBLE_EQ(shapeReach(coin), std::hypot(0.5, 0.05));
    const Quat tilt = turn(0.4, Vec3(1, 0, 2));
    const Aabb box = shapeBounds(coin, Vec3(1, 2, 3), tilt);
    // The rims sampled: the box holds them and touches them on every side.
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    const Pose pose{Vec3(1, 2, 3), tilt};
    for (const double side : {-1.0, 1.0})
        for (int k = 0; k < 100000; ++k) {
            const double a = 2 * kPi * k / 100000;
            const Vec3 p = pose.apply(Vec3(0.5 * std::cos(a), side * 0.05, 0.5 * std::sin(a)));
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
    EXPECT_TRUE((box.min - lo).cwiseAbs().maxCoeff() < 1e-8);
    EXPECT_TRUE((box.max - hi).cwiseAbs().maxCoeff() < 1e-8);
}

// --- Cylinder against plane ----------------------------------------------------------------

const Shape kCoin = cylinderShape(0.2, 0.04);
const Shape kGround = planeShape(Vec3::UnitY(), 0.0);

TEST(CylinderPlane, LyingFlatGivesSixRimPointsAtTheFaceDepth) {
    ContactManifold m;
    const Pose pose{Vec3(0.3, 0.02 - 0.001, -0.1), turn(0.7, Vec3::UnitY())};
    collide(kCoin, pose, kGround, {}, 0.002, m);
    ASSERT_EQ(m.count, kCylinderFlatRimPoints);
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < m.count; ++k) {
        const ContactPoint& c = m.points[k];
        EXPECT_NEAR(c.depth, 0.001, 1e-12);
        EXPECT_TRUE(c.normal.isApprox(Vec3::UnitY()));
        EXPECT_NEAR(c.point1.y(), 0.0, 1e-12);
        expectOnRim(kCoin, pose, c.point0);
        centre += c.point0 / m.count;
    }
    // Spread round the rim: their centre is the face's centre, under the coin's centre.
    EXPECT_NEAR(centre.x(), 0.3, 1e-12);
    EXPECT_NEAR(centre.z(), -0.1, 1e-12);
}

TEST(CylinderPlane, TiltedGivesTheExactDeepestRimPoint) {
    const Vec3 normals[] = {Vec3::UnitY(), Vec3(0.3, 1.0, -0.2).normalized()};
    for (const Vec3& n : normals) {
        for (const double tiltAngle : {0.05, 0.4, 1.2, 1.5}) {
            const Quat rotation = turn(tiltAngle, Vec3(1, 0, 0.5)) * turn(0.3, Vec3::UnitY());
            // Place the centre so that the lowest rim point is 1 mm under the plane n·x = 0.5.
            const Pose unplaced{Vec3(0.1, 0.0, 0.2), rotation};
            const Vec3 lowest = sampledLowestRimPoint(kCoin, unplaced, n);
            const Vec3 shift = n * (0.5 - 0.001 - n.dot(lowest));
            const Pose pose{unplaced.position + shift, rotation};
            ContactManifold m;
            collide(kCoin, pose, planeShape(n, 0.5), {}, 0.0005, m);
            ASSERT_EQ(m.count, 1) << tiltAngle;
            const ContactPoint& c = m.points[0];
            EXPECT_NEAR(c.depth, 0.001, 1e-9);
            EXPECT_TRUE(c.normal.isApprox(n));
            // The sampled rim agrees to its spacing (2π r / 200000 ≈ 6e-6 m, squared in height).
            EXPECT_LT((c.point0 - (lowest + shift)).norm(), 1e-5) << tiltAngle;
            expectOnRim(kCoin, pose, c.point0);
            EXPECT_NEAR(n.dot(c.point1), 0.5, 1e-12);
        }
    }
}

TEST(CylinderPlane, OnItsSideGivesOnePointPerFaceAlongTheLine) {
    const Shape wheel = cylinderShape(0.2, 0.5);
    // Axis along z (local y turned onto z), resting on its side 1 mm deep, rolled by 0.3 rad.
    const Pose pose{Vec3(0.0, 0.2 - 0.001, 0.0), turn(0.3, Vec3::UnitZ()) * turn(kPi / 2, Vec3::UnitX())};
    ContactManifold m;
    collide(wheel, pose, kGround, {}, 0.002, m);
    ASSERT_EQ(m.count, 2);
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].depth, 0.001, 1e-12);
        EXPECT_NEAR(m.points[k].point0.x(), 0.0, 1e-12);
        EXPECT_NEAR(m.points[k].point0.y(), -0.001, 1e-12);
    }
    EXPECT_NEAR(std::abs(m.points[0].point0.z() - m.points[1].point0.z()), 0.5, 1e-12);
}

TEST(CylinderPlane, ApartBeyondTheMarginGivesNothingAndOrderSwapsFlip) {
    ContactManifold m;
    collide(kCoin, {Vec3(0, 0.02 + 0.003, 0), Quat::Identity()}, kGround, {}, 0.002, m);
    EXPECT_EQ(m.count, 0);
    // Plane first: the same points with the roles exchanged.
    const Pose pose{Vec3(0, 0.15, 0), turn(1.0, Vec3::UnitX())};
    ContactManifold forward, reversed;
    collide(kCoin, pose, kGround, {}, 0.002, forward);
    collide(kGround, {}, kCoin, pose, 0.002, reversed);
    ASSERT_EQ(forward.count, 1);
    ASSERT_EQ(reversed.count, 1);
    EXPECT_TRUE(reversed.points[0].normal.isApprox(-forward.points[0].normal));
    EXPECT_TRUE(reversed.points[0].point1.isApprox(forward.points[0].point0));
    EXPECT_NEAR(reversed.points[0].depth, forward.points[0].depth, 1e-15);
}

// --- Cylinder against box (a table) and sphere ---------------------------------------------

TEST(CylinderBox, OnATableFaceMatchesThePlaneAndStaysOnTheFace) {
    const Shape table = boxShape(Vec3(2.0, 0.1, 2.0));
    const Pose tablePose{Vec3(0, -0.05, 0), Quat::Identity()};  // top face at y = 0
    for (const double tiltAngle : {0.0, 0.3, 1.1}) {
        const Pose pose{Vec3(0.2, 0.02 * std::cos(tiltAngle) + 0.2 * std::sin(tiltAngle) - 0.001, 0.1),
                        turn(tiltAngle, Vec3::UnitZ())};
        ContactManifold onBox, onPlane;
        collide(kCoin, pose, table, tablePose, 0.002, onBox);
        collide(kCoin, pose, kGround, {}, 0.002, onPlane);
        ASSERT_EQ(onBox.count, onPlane.count) << tiltAngle;
        for (int k = 0; k < onBox.count; ++k) {
            EXPECT_NEAR(onBox.points[k].depth, onPlane.points[k].depth, 1e-12);
            EXPECT_LT((onBox.points[k].point0 - onPlane.points[k].point0).norm(), 1e-12);
            EXPECT_TRUE(onBox.points[k].normal.isApprox(Vec3::UnitY()));
        }
    }
    // Near the table's edge a flat coin keeps only the rim points over the table.
    const Pose overhanging{Vec3(0.95, 0.019, 0.0), Quat::Identity()};
    ContactManifold m;
    collide(kCoin, overhanging, table, tablePose, 0.002, m);
    ASSERT_GT(m.count, 0);
    EXPECT_LT(m.count, kCylinderFlatRimPoints);
    for (int k = 0; k < m.count; ++k) EXPECT_LE(m.points[k].point1.x(), 1.0 + 1e-12);
}

TEST(CylinderBox, ACornerUnderTheCylindersFaceAndAnEdgeAcrossItsSide) {
    // A cube (0.2) turned onto its corner sits under the middle of a big disc's face.
    const Shape disc = cylinderShape(1.0, 0.2);
    const Shape cube = boxShape(Vec3::Constant(0.2));
    const Quat onCorner = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitY());
    const double cornerHeight = 0.1 * std::sqrt(3.0);
    const Pose discPose{Vec3(0, cornerHeight + 0.1 - 0.002, 0), Quat::Identity()};
    ContactManifold m;
    collide(disc, discPose, cube, {Vec3::Zero(), onCorner}, 0.001, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.002, 1e-9);
    EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitY(), 1e-9));
    EXPECT_NEAR(m.points[0].point1.y(), cornerHeight, 1e-9);

    // A box edge along x under a cylinder lying along z: the contact is on the side's bottom
    // line, the edge 1 mm into it.
    const Shape roller = cylinderShape(0.1, 1.0);
    const Quat edgeUp = turn(kPi / 4, Vec3::UnitX());
    const double edgeHeight = 0.1 * std::sqrt(2.0);
    const Pose rollerPose{Vec3(0.0, edgeHeight + 0.1 - 0.001, 0.0), turn(kPi / 2, Vec3::UnitX())};
    collide(roller, rollerPose, cube, {Vec3::Zero(), edgeUp}, 0.002, m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, 0.001, 1e-9);
    EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitY(), 1e-9));
}

TEST(CylinderSphere, ClosestPointsOnFaceSideAndRim) {
    const Shape can = cylinderShape(0.5, 1.0);
    const Pose pose{Vec3(1, 2, 3), turn(0.6, Vec3(1, 2, 0))};
    const Shape ball = sphereShape(0.1);
    struct Case {
        Vec3 local;     ///< sphere centre in the cylinder's frame
        double depth;   ///< expected
        Vec3 outward;   ///< expected direction from the cylinder to the sphere (local)
    };
    const double rimGap = 0.05;  // from the rim circle, diagonally outwards
    const Case cases[] = {
        {Vec3(0.2, 0.5 + 0.08, -0.1), 0.02, Vec3::UnitY()},              // over the top face
        {Vec3(0.0, -0.3, 0.5 + 0.09), 0.01, Vec3::UnitZ()},               // beside the side
        {Vec3((0.5 + rimGap / std::sqrt(2.0)), -0.5 - rimGap / std::sqrt(2.0), 0.0), 0.05,
         Vec3(1, -1, 0).normalized()},                                      // off the rim
        {Vec3(0.45, 0.1, 0.0), 0.15, Vec3::UnitX()},                        // centre inside, near the side
        {Vec3(0.0, -0.47, 0.1), 0.13, -Vec3::UnitY()},                      // centre inside, near a face
    };
    for (const Case& c : cases) {
        ContactManifold m;
        collide(can, pose, ball, {pose.apply(c.local), Quat::Identity()}, 0.001, m);
        ASSERT_EQ(m.count, 1) << c.local.transpose();
        EXPECT_NEAR(m.points[0].depth, c.depth, 1e-12) << c.local.transpose();
        EXPECT_TRUE(m.points[0].normal.isApprox(-(pose.rotation * c.outward), 1e-12)) << c.local.transpose();
    }
    ContactManifold m;
    collide(can, pose, ball, {pose.apply(Vec3(0, 0.5 + 0.102, 0)), Quat::Identity()}, 0.001, m);
    EXPECT_EQ(m.count, 0);
}

// --- In the world ----------------------------------------------------------------------------

TEST(CylinderWorld, RestingFlatStaysPut) {
    World world({.gravity = Vec3(0, -10, 0), .substeps = 20});
    world.createBody({.shape = kGround, .type = BodyType::Static});
    const BodyId coin = world.createBody({.shape = kCoin, .density = 8000.0, .position = Vec3(0.1, 0.02, -0.2),
                                          .orientation = turn(0.4, Vec3::UnitY())});
    for (int frame = 0; frame < 300; ++frame) world.step(1.0 / 60.0);
    const Body& b = world.body(coin);
    EXPECT_LT((b.userPosition() - Vec3(0.1, 0.02, -0.2)).norm(), 1e-5);
    EXPECT_LT(b.v.norm(), 1e-5);
    EXPECT_LT(b.omega.norm(), 1e-4);
    EXPECT_LT(b.userOrientation().angularDistance(turn(0.4, Vec3::UnitY())), 1e-5);
}

TEST(CylinderWorld, RollsDownAnInclineAtTwoThirdsGSinTheta) {
    // A solid cylinder rolling without slipping: a = g sin θ / (1 + I/(m r²)) = 2/3 g sin θ.
    const double theta = 15.0 * kPi / 180.0;
    const double g = 10.0;
    const double r = 0.1;
    const Vec3 n(-std::sin(theta), std::cos(theta), 0.0);
    const Vec3 downhill(-std::cos(theta), -std::sin(theta), 0.0);
    World world({.gravity = Vec3(0, -g, 0), .substeps = 20});
    world.createBody({.shape = planeShape(n, 0.0), .type = BodyType::Static, .staticFriction = 0.8, .dynamicFriction = 0.8});
    const BodyId wheel = world.createBody({.shape = cylinderShape(r, 0.3),
                                           .density = 1000.0,
                                           .position = r * n,
                                           .orientation = turn(kPi / 2, Vec3::UnitX()),
                                           .staticFriction = 0.8,
                                           .dynamicFriction = 0.8});
    const double seconds = 1.0;
    for (int frame = 0; frame < 60; ++frame) world.step(1.0 / 60.0);
    const Body& b = world.body(wheel);
    const double travelled = (b.x - r * n).dot(downhill);
    const double expected = 0.5 * (2.0 / 3.0) * g * std::sin(theta) * seconds * seconds;
    EXPECT_NEAR(travelled, expected, 0.005 * expected);  // sliding (a = g sin θ) would be 50 % more
    // Rolling: the speed is ω r, the axis still along z, and the wheel still on the incline.
    EXPECT_NEAR(b.v.norm(), b.omega.norm() * r, 0.01 * b.v.norm());
    EXPECT_NEAR(std::abs((b.userOrientation() * Vec3::UnitY()).z()), 1.0, 1e-6);
    EXPECT_NEAR((b.x).dot(n), r, 1e-4);
}

}  // namespace
}  // namespace substep

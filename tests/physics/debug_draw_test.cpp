// Tests engine/physics/debug_draw.{h,cpp}: the core's draw list puts limits, forces and torques
// where the joint's definition and statics say they are, and the bodies' layers (broadphase boxes,
// centres of mass, velocities, contact points) where geometry and kinematics say they are.

#include "physics/debug_draw.h"
#include "physics/collision/convex_mesh_shape.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace substep {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<DebugSegment> segmentsOf(const DebugDrawList& list, DebugLayer layer) {
    std::vector<DebugSegment> found;
    std::copy_if(list.segments.begin(), list.segments.end(), std::back_inserter(found),
                 [&](const DebugSegment& segment) { return segment.layer == layer; });
    return found;
}

/// A 2 kg bar of 0.5 m on a hinge about world z at the origin, level, with limits [-0.5, 1.0].
struct HingedBar {
    World world{WorldSettings{.gravity = Vec3(0.0, -10.0, 0.0)}};
    BodyId bar;
    JointId hinge;
    HingedBar() {
        bar = world.createBody({.shape = boxShape(Vec3(0.5, 0.05, 0.05)), .mass = 2.0, .position = Vec3(0.25, 0.0, 0.0)});
        hinge = world.createJoint({.type = JointType::Hinge,
                                   .body1 = bar,
                                   .anchor0 = Vec3::Zero(),
                                   .anchor1 = Vec3(-0.25, 0.0, 0.0),
                                   .axis0 = Vec3::UnitZ(),
                                   .axis1 = Vec3::UnitZ(),
                                   .limits = Range{-0.5, 1.0},
                                   .targetAngle = 0.0});
    }
};

TEST(DebugDraw, HingeLimitArcSpansTheLimitsAboutTheAxis) {
    HingedBar rig;
    DebugDrawList list;
    drawWorld(rig.world, {.layers = debugLayerBit(DebugLayer::JointLimit), .markerLength = 0.2}, list);
    const std::vector<DebugSegment> arc = segmentsOf(list, DebugLayer::JointLimit);
    ASSERT_FALSE(arc.empty());
    EXPECT_EQ(arc.size(), list.segments.size()) << "only the asked layer";
    // Every arc point lies in the plane z = 0 at radius 1.5 x marker; the two spokes end at
    // angles -0.5 and 1.0 from the joint's b axis.
    const Vec3 b = rig.world.body(rig.bar).q * rig.world.joint(rig.hinge).frame1 * Vec3::UnitY();
    std::vector<double> spokeAngles;
    for (const DebugSegment& segment : arc) {
        EXPECT_NEAR(segment.to.z(), 0.0, 1e-12);
        EXPECT_NEAR(segment.to.norm(), 0.3, 1e-12);
        if (segment.from.norm() < 1e-12) {
            const Vec3 spoke = segment.to.normalized();
            spokeAngles.push_back(std::atan2(b.cross(spoke).z(), b.dot(spoke)));
        }
    }
    ASSERT_EQ(spokeAngles.size(), 2u);
    std::sort(spokeAngles.begin(), spokeAngles.end());
    EXPECT_NEAR(spokeAngles[0], -0.5, 1e-9);
    EXPECT_NEAR(spokeAngles[1], 1.0, 1e-9);
}

TEST(DebugDraw, HeldBarShowsItsWeightAndTorqueOnTheBar) {
    HingedBar rig;
    for (int frame = 0; frame < 60; ++frame) rig.world.step(1.0 / 60.0);
    DebugDrawList list;
    drawWorld(rig.world,
              {.layers = debugLayerBit(DebugLayer::JointForce) | debugLayerBit(DebugLayer::JointTorque),
               .forceScale = 0.01, .torqueScale = 0.1, .longestArrow = 10.0},
              list);
    const std::vector<DebugSegment> force = segmentsOf(list, DebugLayer::JointForce);
    const std::vector<DebugSegment> torque = segmentsOf(list, DebugLayer::JointTorque);
    ASSERT_EQ(force.size(), 3u);  // shaft and two barbs
    ASSERT_EQ(torque.size(), 3u);
    // The hinge holds m g = 20 N up at the pivot and m g L/2 = 5 N m about +z (it lifts the
    // bar's free end, counter-clockwise seen from +z).
    const Vec3 forceArrow = force[0].to - force[0].from;
    EXPECT_NEAR(forceArrow.x(), 0.0, 1e-3);
    EXPECT_NEAR(forceArrow.y(), 0.01 * 20.0, 2e-3);
    EXPECT_NEAR(force[0].from.norm(), 0.0, 1e-3) << "drawn at the anchor";
    const Vec3 torqueArrow = torque[0].to - torque[0].from;
    EXPECT_NEAR(torqueArrow.z(), 0.1 * 5.0, 2e-3);
    EXPECT_NEAR(torqueArrow.head<2>().norm(), 0.0, 1e-3);
}

TEST(DebugDraw, ArrowsAreClippedAndLayersFiltered) {
    HingedBar rig;
    rig.world.step(1.0 / 60.0);
    DebugDrawList list;
    drawWorld(rig.world, {.layers = debugLayerBit(DebugLayer::JointForce), .forceScale = 10.0, .longestArrow = 0.5},
              list);
    ASSERT_FALSE(list.segments.empty());
    EXPECT_NEAR((list.segments[0].to - list.segments[0].from).norm(), 0.5, 1e-12);
    list.clear();
    drawWorld(rig.world, {.layers = 0}, list);
    EXPECT_TRUE(list.segments.empty());
}

TEST(DebugDraw, PrismaticRangeAndSwingConeFollowTheDefinitions) {
    World world;
    const BodyId slider = world.createBody({.shape = boxShape(Vec3::Constant(0.1)), .mass = 1.0});
    world.createJoint({.type = JointType::Prismatic, .body1 = slider, .axis0 = Vec3::UnitX(), .axis1 = Vec3::UnitX(),
                       .limits = Range{-0.2, 0.4}});
    const BodyId ball = world.createBody({.shape = sphereShape(0.1), .mass = 1.0, .position = Vec3(0.0, -1.0, 0.0)});
    world.createJoint({.type = JointType::Spherical, .body1 = ball, .anchor0 = Vec3(0.0, 0.0, 0.0),
                       .anchor1 = Vec3(0.0, 1.0, 0.0), .axis0 = -Vec3::UnitY(), .axis1 = -Vec3::UnitY(),
                       .swingLimit = kPi / 6.0});
    DebugDrawList list;
    drawWorld(world, {.layers = debugLayerBit(DebugLayer::JointLimit), .markerLength = 0.2}, list);
    // The slide's range: a segment from -0.2 to 0.4 along x through its anchor.
    bool rangeFound = false;
    for (const DebugSegment& segment : list.segments) {
        if ((segment.from - Vec3(-0.2, 0.0, 0.0)).norm() < 1e-12 && (segment.to - Vec3(0.4, 0.0, 0.0)).norm() < 1e-12)
            rangeFound = true;
    }
    EXPECT_TRUE(rangeFound);
    // The cone's rim: every rim point at 30° from the cone axis -y, 0.3 m from the apex.
    int rimPoints = 0;
    for (const DebugSegment& segment : list.segments) {
        if (segment.from.y() < -1e-9 && segment.to.y() < -1e-9 && std::abs(segment.from.norm() - 0.3) < 1e-12) {
            EXPECT_NEAR(std::acos(-segment.to.normalized().y()), kPi / 6.0, 1e-9);
            ++rimPoints;
        }
    }
    EXPECT_GE(rimPoints, 16);
}

/// The eight corners of a box of half extents `half` about `centre`, in corner-bit order.
std::vector<Vec3> cornersOf(const Vec3& centre, const Vec3& half) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.push_back(centre + Vec3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                        (i & 4) ? half.z() : -half.z()));
    return corners;
}

/// Whether every point of `expected` is an end of some segment and every end is one of them.
void expectEndsAre(const std::vector<DebugSegment>& segments, const std::vector<Vec3>& expected, double tolerance) {
    const auto isExpected = [&](const Vec3& p) {
        return std::any_of(expected.begin(), expected.end(), [&](const Vec3& e) { return (p - e).norm() < tolerance; });
    };
    for (const DebugSegment& segment : segments) {
        EXPECT_TRUE(isExpected(segment.from)) << segment.from.transpose();
        EXPECT_TRUE(isExpected(segment.to)) << segment.to.transpose();
    }
    for (const Vec3& corner : expected) {
        EXPECT_TRUE(std::any_of(segments.begin(), segments.end(), [&](const DebugSegment& s) {
            return (s.from - corner).norm() < tolerance || (s.to - corner).norm() < tolerance;
        })) << "corner " << corner.transpose() << " missing";
    }
}

TEST(DebugDraw, BoundsAreTheBroadphaseBoxesOfRotatedBoxesAtRest) {
    // Two boxes at rest far apart, no gravity: the broadphase's box is the shape's box grown by
    // the margin alone (no motion), and a box's world extent along an axis is the sum of its
    // rotated half sizes' projections.
    World world(WorldSettings{.gravity = Vec3::Zero()});
    const double c45 = std::sqrt(0.5);
    const Quat turnZ(Eigen::AngleAxisd(kPi / 4.0, Vec3::UnitZ()));
    const Quat turnX(Eigen::AngleAxisd(kPi / 6.0, Vec3::UnitX()));
    world.createBody({.shape = boxShape(Vec3::Ones()), .mass = 1.0, .position = Vec3(1.0, 2.0, 3.0), .orientation = turnZ});
    world.createBody({.shape = boxShape(Vec3(1.0, 2.0, 3.0)), .mass = 7.0, .position = Vec3(-5.0, 0.5, 0.0),
                      .orientation = turnX});
    world.step(1.0 / 60.0);
    DebugDrawList list;
    drawWorld(world, {.layers = debugLayerBit(DebugLayer::Bounds)}, list);
    ASSERT_EQ(list.segments.size(), 24u) << "twelve edges per box";
    const double margin = BroadphaseSettings{}.margin;
    const std::vector<DebugSegment> first(list.segments.begin(), list.segments.begin() + 12);
    const std::vector<DebugSegment> second(list.segments.begin() + 12, list.segments.end());
    // Unit cube turned 45 degrees about z: half extents cos45 + sin45 halves in x and y, 0.5 in z.
    expectEndsAre(first, cornersOf(Vec3(1.0, 2.0, 3.0), Vec3(c45, c45, 0.5) + Vec3::Constant(margin)), 1e-9);
    // 1 x 2 x 3 turned 30 degrees about x: y reaches 1 cos30 + 1.5 sin30, z 1 sin30 + 1.5 cos30.
    const double c30 = std::cos(kPi / 6.0), s30 = 0.5;
    expectEndsAre(second,
                  cornersOf(Vec3(-5.0, 0.5, 0.0), Vec3(0.5, c30 + 1.5 * s30, s30 + 1.5 * c30) + Vec3::Constant(margin)),
                  1e-9);
    for (const DebugSegment& edge : list.segments)
        EXPECT_EQ(((edge.to - edge.from).array().abs() > 1e-12).count(), 1) << "edges run along one axis";
}

TEST(DebugDraw, CentreOfMassMarkerSitsAtTheBodysCentreNotItsFrame) {
    // A tetrahedron with its corner at its frame's origin: its centre of mass is a quarter of the
    // way along each leg, (1/4, 1/4, 1/4) in its frame, wherever the body is put.
    auto tetrahedron = std::make_shared<TriangleMesh>();
    tetrahedron->vertices = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    tetrahedron->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    World world(WorldSettings{.gravity = Vec3::Zero()});
    const Vec3 position(0.5, 1.0, -2.0);
    const Quat orientation(Eigen::AngleAxisd(kPi / 2.0, Vec3::UnitY()));
    world.createBody({.shape = convexMeshShape(tetrahedron), .density = 300.0, .position = position,
                      .orientation = orientation});
    world.createBody({.shape = boxShape(Vec3::Ones()), .type = BodyType::Static});  // no marker
    DebugDrawList list;
    drawWorld(world, {.layers = debugLayerBit(DebugLayer::CentreOfMass), .markerLength = 0.2}, list);
    ASSERT_EQ(list.segments.size(), 3u);
    const Vec3 centre = position + orientation * Vec3::Constant(0.25);
    for (const DebugSegment& segment : list.segments) {
        EXPECT_LT((0.5 * (segment.from + segment.to) - centre).norm(), 1e-9);
        EXPECT_NEAR((segment.to - segment.from).norm(), 0.2, 1e-12);
    }
    const Vec3 a = list.segments[0].to - list.segments[0].from, b = list.segments[1].to - list.segments[1].from;
    EXPECT_NEAR(a.dot(b), 0.0, 1e-12) << "along the principal axes";
}

TEST(DebugDraw, VelocityArrowsAreVelocityTimesScaleAndTheArcTurnsWithOmega) {
    World world(WorldSettings{.gravity = Vec3::Zero()});
    const Vec3 start(0.0, 1.0, 0.0);
    world.createBody({.shape = sphereShape(0.3), .mass = 2.5, .position = start, .velocity = Vec3(3.0, -4.0, 0.0),
                      .angularVelocity = Vec3(0.0, 0.0, 2.0)});
    world.createBody({.shape = boxShape(Vec3(0.2, 0.4, 0.6)), .mass = 40.0, .position = Vec3(2.0, 0.0, 0.0),
                      .velocity = Vec3(0.0, 0.0, -30.0)});
    DebugDrawList list;
    const DebugDrawOptions options{.layers = debugLayerBit(DebugLayer::LinearVelocity) |
                                             debugLayerBit(DebugLayer::AngularVelocity),
                                   .markerLength = 0.2, .velocityScale = 0.1, .angularVelocityScale = 0.25,
                                   .longestArrow = 1.0};
    drawWorld(world, options, list);
    const std::vector<DebugSegment> linear = segmentsOf(list, DebugLayer::LinearVelocity);
    ASSERT_EQ(linear.size(), 6u) << "two arrows of a shaft and two barbs";
    // |v| = 5 m/s at 0.1 m per m/s: 0.5 m along (0.6, -0.8, 0) from the centre of mass.
    EXPECT_LT((linear[0].from - start).norm(), 1e-12);
    EXPECT_LT((linear[0].to - (start + Vec3(0.3, -0.4, 0.0))).norm(), 1e-12);
    // 30 m/s would be 3 m: clipped to the longest arrow, 1 m, still along -z.
    EXPECT_LT((linear[3].to - linear[3].from - Vec3(0.0, 0.0, -1.0)).norm(), 1e-12);

    const std::vector<DebugSegment> angular = segmentsOf(list, DebugLayer::AngularVelocity);
    std::vector<DebugSegment> shaft, arc;
    for (const DebugSegment& segment : angular) (segment.part == 0 ? shaft : arc).push_back(segment);
    ASSERT_EQ(shaft.size(), 3u) << "the box does not turn: one arrow";
    // |ω| = 2 rad/s at 0.25 m per rad/s: 0.5 m along +z (right-hand rule).
    EXPECT_LT((shaft[0].to - (start + Vec3(0.0, 0.0, 0.5))).norm(), 1e-12);
    // The arc circles the axis in the plane z = 0.25 at radius 0.1, counter-clockwise seen from +z
    // as a body turning about +z does.
    ASSERT_GE(arc.size(), 16u);
    for (std::size_t i = 0; i < 16; ++i) {
        const Vec3 from = arc[i].from - start - Vec3(0.0, 0.0, 0.25), to = arc[i].to - start - Vec3(0.0, 0.0, 0.25);
        EXPECT_NEAR(from.z(), 0.0, 1e-12);
        EXPECT_NEAR(to.head<2>().norm(), 0.1, 1e-12);
        EXPECT_GT(from.cross(to).z(), 0.0) << "segment " << i;
    }
}

TEST(DebugDraw, ContactPointsAreCrossesWhereTheSphereTouchesTheGround) {
    World world;
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    world.createBody({.shape = sphereShape(0.25), .mass = 1.0, .position = Vec3(0.7, 0.25, -0.3)});
    for (int frame = 0; frame < 30; ++frame) world.step(1.0 / 60.0);
    DebugDrawList list;
    drawWorld(world, {.layers = debugLayerBit(DebugLayer::Contact), .markerLength = 0.1}, list);
    std::vector<DebugSegment> crosses, normals;
    for (const DebugSegment& segment : segmentsOf(list, DebugLayer::Contact))
        (segment.part == 1 ? crosses : normals).push_back(segment);
    ASSERT_EQ(crosses.size(), 2u) << "one point, two strokes";
    ASSERT_EQ(normals.size(), 3u) << "one normal arrow";
    for (const DebugSegment& stroke : crosses) {
        EXPECT_LT((0.5 * (stroke.from + stroke.to) - Vec3(0.7, 0.0, -0.3)).norm(), 1e-3) << "under the sphere";
        EXPECT_NEAR((stroke.to - stroke.from).norm(), 0.05, 1e-12);
        EXPECT_NEAR((stroke.to - stroke.from).y(), 0.0, 1e-9) << "in the contact plane";
    }
    const Vec3 normal = normals[0].to - normals[0].from;
    EXPECT_NEAR(std::abs(normal.y()), 0.1, 1e-9) << "along the ground's normal";
}

}  // namespace
}  // namespace substep

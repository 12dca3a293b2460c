// Tests engine/physics/debug_draw.{h,cpp}: the core's draw list puts limits, forces and torques
// where the joint's definition and statics say they are.

#include "physics/debug_draw.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

}  // namespace
}  // namespace substep

// Tests sandbox/scenes/robot_arm.cpp (paper Fig. 17): the gripper meets a reachable target, the
// joint limits hold wherever the target goes, and a target out of reach leaves the gripper as
// close as the arm allows. Angles and the gripper point come from the bodies' poses alone, the
// reachable targets from this file's own forward kinematics.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>

namespace substep {
namespace {

// The arm as the scene describes it (m, rad).
const Vec3 kShoulder(0.0, 0.25, 0.0);  // on the yaw axis, above the turret
constexpr double kUpperArm = 0.5;
constexpr double kForearm = 0.45;
constexpr double kGripperReach = 0.16;  // wrist pivot to the gripper point
constexpr double kHand = 0.1;            // the hand box's length (its centre is kHand/2 from the wrist)
constexpr double kFullReach = kUpperArm + kForearm + kGripperReach;

struct Limit {
    const char* parent;
    const char* child;
    Vec3 axis;  // in both bodies' frames
    double lower, upper;
};
const std::array<Limit, 4> kLimits{{
    {"pedestal", "turret", Vec3::UnitY(), -2.6, 2.6},
    {"turret", "upper_arm", Vec3::UnitZ(), -1.3, 0.8},
    {"upper_arm", "forearm", Vec3::UnitZ(), -2.5, 0.2},
    {"forearm", "hand", Vec3::UnitZ(), -1.7, 1.7},
}};

double wrapped(double angle) {
    while (angle > M_PI) angle -= 2.0 * M_PI;
    while (angle <= -M_PI) angle += 2.0 * M_PI;
    return angle;
}

/// Gripper point of the arm with the given angles (yaw about y, then the pitch hinges about
/// the turret's z, each link along its own +y).
Vec3 gripperAt(double yaw, double shoulder, double elbow, double wrist) {
    const Quat turret(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
    const Quat upper = turret * Quat(Eigen::AngleAxisd(shoulder, Vec3::UnitZ()));
    const Quat fore = upper * Quat(Eigen::AngleAxisd(elbow, Vec3::UnitZ()));
    const Quat hand = fore * Quat(Eigen::AngleAxisd(wrist, Vec3::UnitZ()));
    return kShoulder + upper * Vec3(0, kUpperArm, 0) + fore * Vec3(0, kForearm, 0) + hand * Vec3(0, kGripperReach, 0);
}

class RobotArm : public testing::Test {
  protected:
    RobotArm() : scene_(findBuiltinScene("robot_arm")->build(), findBuiltinScene("robot_arm")) {}

    void set(std::string_view knob, double value) {
        ASSERT_TRUE(scene_.script()->setKnob(scene_.instance(), knob, value)) << knob;
    }
    /// Sets the sliders; the box glides there at 1 m/s, so this waits until it has arrived.
    void setTarget(const Vec3& target) {
        set("orbit", 0);
        set("target_x", target.x());
        set("target_y", target.y());
        set("target_z", target.z());
        for (int frame = 0; frame < 600 && (this->target() - target).norm() > 0.0; ++frame) run(1.0 / 60.0);
        ASSERT_NEAR((this->target() - target).norm(), 0.0, 1e-12);
    }
    void run(double seconds) {
        const int frames = static_cast<int>(std::lround(seconds / scene_.description().dt));
        for (int i = 0; i < frames; ++i) {
            scene_.step();
            checkLimits();
        }
        ASSERT_TRUE(scene_.world().isFinite());
    }
    const Body& body(std::string_view name) const {
        for (const auto& [bodyName, id] : scene_.instance().namedBodyIds())
            if (bodyName == name) return scene_.world().body(id);
        ADD_FAILURE() << "no body " << name;
        return scene_.world().body(BodyId{});
    }
    Vec3 gripper() const {
        const Body& hand = body("hand");
        return hand.userPosition() + hand.userOrientation() * Vec3(0, kGripperReach - 0.5 * kHand, 0);
    }
    Vec3 target() const { return body("target").userPosition(); }

    /// Hinge angle: the twist about the joint axis of the child's orientation relative to the
    /// parent's (both built so that equal orientations mean angle 0).
    double angle(const Limit& limit) const {
        const Quat relative = body(limit.parent).userOrientation().conjugate() * body(limit.child).userOrientation();
        return wrapped(2.0 * std::atan2(relative.vec().dot(limit.axis), relative.w()));
    }
    void checkLimits() {
        for (const Limit& limit : kLimits) {
            const double a = angle(limit);
            worstViolation_ = std::max({worstViolation_, limit.lower - a, a - limit.upper});
            closestApproach_ = std::min({closestApproach_, a - limit.lower, limit.upper - a});
        }
    }

    LiveScene scene_;
    double worstViolation_ = -1.0;  ///< largest angle beyond a limit seen (rad); negative: none
    double closestApproach_ = 1.0;  ///< smallest distance to a limit seen (rad)
};

/// Poses inside every limit with the gripper pointing down (wrist = −π − shoulder − elbow).
struct ArmPose {
    double yaw, shoulder, elbow;
};
class RobotArmReach : public RobotArm, public testing::WithParamInterface<ArmPose> {};

TEST_P(RobotArmReach, GripperMeetsAReachableTargetWithinAMillimetre) {
    // From the built pose, each target by a fresh scene: the arm's way to a target far round the
    // base is the solver's (it can stall in a fold, as any local method can).
    const ArmPose p = GetParam();
    const double wrist = -M_PI - p.shoulder - p.elbow;
    ASSERT_LE(std::abs(wrist), 1.7);
    const Vec3 goal = gripperAt(p.yaw, p.shoulder, p.elbow, wrist);
    setTarget(goal);
    run(3.0);
    EXPECT_LT((gripper() - goal).norm(), 1e-3) << "gripper " << gripper().transpose() << ", target " << goal.transpose();
    // And it points down, along the box's −y.
    EXPECT_GT((body("hand").userOrientation() * Vec3::UnitY()).dot(-Vec3::UnitY()), std::cos(0.01));
    EXPECT_LT(worstViolation_, 0.015);
}

INSTANTIATE_TEST_SUITE_P(Poses, RobotArmReach,
                         testing::Values(ArmPose{0.3, -0.4, -1.6}, ArmPose{-1.2, -0.9, -1.0}, ArmPose{1.4, 0.3, -2.2},
                                         ArmPose{-0.6, -1.1, -0.6}, ArmPose{0.9, -0.6, -1.0}),
                         [](const testing::TestParamInfo<ArmPose>& paramInfo) { return "pose" + std::to_string(paramInfo.index); });

TEST_F(RobotArm, JointLimitsHoldWhereverTheTargetGoes) {
    // The default path leaves the reach and the yaw range and comes back.
    run(40.0);
    // Targets out of reach: behind the base, under the ground, far above and far out.
    for (const Vec3& goal : {Vec3(-1.5, 0.3, 0.1), Vec3(0.2, -0.2, 0.1), Vec3(0.0, 1.8, 0.0), Vec3(1.6, 1.0, -1.6),
                             Vec3(0.05, 0.3, 0.05)}) {
        setTarget(goal);
        run(4.0);
    }
    EXPECT_LT(worstViolation_, 0.015);
    // The test reached the limits (else it proved nothing).
    EXPECT_LT(closestApproach_, 0.01);
}

TEST_F(RobotArm, OutOfReachTheGripperStopsOnTheLineAtFullReach) {
    // Without the orientation hold the arm can stretch straight along any direction its limits
    // allow: the closest point to a far target is at full reach on the line from the shoulder.
    set("hold_orientation", 0);
    // The kinematic claim alone: with the arm's weight on, the bounded pull (robot_arm.cpp) lets
    // a stretched arm sag below the line by its weight's torque over the pull.
    WorldSettings settings = scene_.world().settings();
    settings.gravity = Vec3::Zero();
    scene_.physics().setSettings(settings);
    for (const Vec3& direction : {Vec3(0, 1, 0), Vec3(0.8, 0.6, 0.0), Vec3(0.5, 0.5, -0.7)}) {
        const Vec3 d = direction.normalized();
        const Vec3 goal = kShoulder + 1.5 * d;
        setTarget(goal);
        run(8.0);
        // The stretched arm keeps a small zig-zag about the line (the overconstrained pull and
        // the hinges trade a little each substep, and the hinges' damping holds it down): the
        // worst over the next second counts.
        double worstOff = 0.0;
        double worstAlong = 0.0;
        for (int frame = 0; frame < 60; ++frame) {
            run(1.0 / 60.0);
            const Vec3 g = gripper() - kShoulder;
            const double along = g.dot(d);
            worstOff = std::max(worstOff, (g - along * d).norm());
            worstAlong = std::max(worstAlong, std::abs(along - kFullReach));
        }
        EXPECT_LT(worstAlong, 1e-3) << d.transpose();
        EXPECT_LT(worstOff, 5e-3) << d.transpose();
    }
    EXPECT_LT(worstViolation_, 0.015);
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

double knobValue(LiveScene& scene, std::string_view name) {
    for (const SceneKnob& knob : scene.script()->knobs())
        if (knob.name == name) return knob.value;
    ADD_FAILURE() << "no knob " << name;
    return 0.0;
}

// The target sliders follow the box wherever it goes, so the window's sliders never stand stale:
// along its orbit, and after the window's mouse moves it (a Transform patch, as body_dragger does).
TEST(RobotArmSliders, FollowTheTargetOnItsOrbitAndAfterADrag) {
    const SceneEntry* entry = findBuiltinScene("robot_arm");
    LiveScene scene(entry->build(), entry);
    const auto targetAt = [&] {
        for (const auto& [name, id] : scene.instance().namedBodyIds())
            if (name == "target") return scene.world().body(id).userPosition();
        ADD_FAILURE() << "no target";
        return Vec3(Vec3::Zero());
    };
    for (int frame = 0; frame < 90; ++frame) scene.step();  // orbiting, on by default
    Vec3 at = targetAt();
    EXPECT_NEAR(knobValue(scene, "target_x"), at.x(), 0.05);  // within the last frame's motion
    EXPECT_NEAR(knobValue(scene, "target_y"), at.y(), 0.05);
    EXPECT_NEAR(knobValue(scene, "target_z"), at.z(), 0.05);

    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "orbit", 0));
    for (int frame = 0; frame < 5; ++frame) scene.step();
    const Vec3 dropped(0.7, 0.4, -0.3);
    ecs::Entity target{};
    for (const ecs::Entity entity : scene.instance().bodyEntities)
        if (const ecs::Name* name = scene.instance().registry.tryGet<ecs::Name>(entity); name && name->value == "target")
            target = entity;
    scene.instance().registry.patch<ecs::Transform>(target, [&](ecs::Transform& box) { box.position = dropped; });
    scene.step();
    at = targetAt();
    EXPECT_NEAR((at - dropped).norm(), 0.0, 1e-12);  // it stays where it was put
    EXPECT_DOUBLE_EQ(knobValue(scene, "target_x"), dropped.x());
    EXPECT_DOUBLE_EQ(knobValue(scene, "target_y"), dropped.y());
    EXPECT_DOUBLE_EQ(knobValue(scene, "target_z"), dropped.z());
}

}  // namespace
}  // namespace substep

// Tests sandbox/scenes/joint_types.cpp (paper Fig. 7): every example rests where statics says it
// must, measured from the bodies' poses alone (never from the joints' own readouts), with the
// scene's knobs set by name as the panel sets them.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace substep {
namespace {

constexpr double kGravity = 10.0;
constexpr double kMass = 1.0;
constexpr double kBarLength = 0.4;
constexpr double kRailTop = 1.7;  // the prismatic anchors on the rails (world y)

class JointTypes : public testing::Test {
  protected:
    JointTypes() : scene_(findBuiltinScene("joint_types")->build(), findBuiltinScene("joint_types")) {
        // Joint damping (Eqs. 31-32) brings the soft examples to rest sooner; rest does not depend on it.
        scene_.script()->setKnob(scene_.instance(), "damping", 10.0);
    }

    void set(std::string_view knob, double value) {
        ASSERT_TRUE(scene_.script()->setKnob(scene_.instance(), knob, value)) << knob;
    }
    void run(double seconds) {
        const int frames = static_cast<int>(std::lround(seconds / scene_.description().dt));
        for (int i = 0; i < frames; ++i) scene_.step();
        ASSERT_TRUE(scene_.world().isFinite());
    }
    const Body& body(std::string_view name) const {
        for (const auto& [bodyName, id] : scene_.instance().namedBodyIds())
            if (bodyName == name) return scene_.world().body(id);
        ADD_FAILURE() << "no body " << name;
        return scene_.world().body(BodyId{});
    }

    /// Hinge angle about +z of a bar relative to its (unturned, static) mount: the twist part of
    /// the bar's orientation about z.
    double hingeAngle(std::string_view bar) const {
        const Quat q = body(bar).userOrientation();
        return 2.0 * std::atan2(q.z(), q.w());
    }
    /// Carriage height relative to its rail's top (the prismatic offset along +y).
    double offset(std::string_view carriage) const { return body(carriage).userPosition().y() - kRailTop; }
    /// Swing of a plate: the angle between its length axis and the mount's (+x).
    double swing(std::string_view plate) const {
        const Vec3 axis = body(plate).userOrientation() * Vec3::UnitX();
        return std::acos(std::clamp(axis.x(), -1.0, 1.0));
    }
    /// Twist of a plate as the paper measures it (Eqs. 22-24): about the mean axis
    /// n = (a0 + a1)/|a0 + a1|, the angle between the normals b0 (the mount's z) and b1 (the
    /// plate's z) with their n-components removed. (It is not the twist of a swing-twist
    /// decomposition: at a swing of 0.6 rad the two differ by about 4%.)
    double twist(std::string_view plate) const {
        const Quat q = body(plate).userOrientation();
        const Vec3 n = (Vec3::UnitX() + q * Vec3::UnitX()).normalized();
        const Vec3 b0 = Vec3::UnitZ() - n.z() * n;
        const Vec3 b1raw = q * Vec3::UnitZ();
        const Vec3 b1 = b1raw - n.dot(b1raw) * n;
        return std::atan2(b0.cross(b1).dot(n), b0.dot(b1));
    }

    LiveScene scene_;
};

/// Wraps to (−π, π].
double wrapped(double angle) {
    while (angle > M_PI) angle -= 2.0 * M_PI;
    while (angle <= -M_PI) angle += 2.0 * M_PI;
    return angle;
}

TEST_F(JointTypes, HardHingeLimitHoldsAndCarriesTheBar) {
    set("hinge_limit", 0.7);
    // The bar falls from level onto its lower limit; it never passes it.
    // It strikes the limit at about 4 rad/s: within the substep of impact the attachment,
    // solved after the limit, may carry it one substep's turn (4 rad/s x 1/1200 s) further.
    for (int frame = 0; frame < 240; ++frame) {
        run(1.0 / 60.0);
        const double angle = wrapped(hingeAngle("hinge_hard"));
        ASSERT_GE(angle, -0.7 - 5e-3) << "frame " << frame;
        ASSERT_LE(angle, 0.7 + 5e-3) << "frame " << frame;
    }
    EXPECT_NEAR(wrapped(hingeAngle("hinge_hard")), -0.7, 1e-3);
}

TEST_F(JointTypes, SoftHingeLimitIsExceededByComplianceTimesTorque) {
    for (const double compliance : {0.1, 0.25}) {
        set("soft_angular_compliance", compliance);
        run(8.0);
        // At rest on the limit, the limit carries the weight's torque about the pivot,
        // τ = m g (L/2) cos θ, and a compliant limit gives by excess = α τ (paper 3.3.1).
        const double angle = wrapped(hingeAngle("hinge_soft"));
        const double excess = -0.5 - angle;
        const double torque = kMass * kGravity * 0.5 * kBarLength * std::cos(angle);
        EXPECT_GT(excess, 0.05);
        EXPECT_NEAR(excess, compliance * torque, 0.01 * compliance * torque + 1e-4) << "α " << compliance;
    }
}

TEST_F(JointTypes, PrismaticLimitsHardAndSoft) {
    set("prismatic_lower", -0.4);
    set("soft_linear_compliance", 0.02);
    run(8.0);
    EXPECT_NEAR(offset("prismatic_hard"), -0.4, 1e-4);
    // The soft limit stretches by α m g.
    EXPECT_NEAR(offset("prismatic_soft"), -0.4 - 0.02 * kMass * kGravity, 1e-3);
}

TEST_F(JointTypes, PrismaticDriveSettlesAtTargetPlusComplianceTimesLoad) {
    set("animate", 0);
    set("prismatic_target", -0.25);
    set("drive_compliance", 0.005);
    run(8.0);
    // Eq. 25 with d_target: a spring of stiffness 1/α about the target, loaded by the weight.
    EXPECT_NEAR(offset("prismatic_drive"), -0.25 - 0.005 * kMass * kGravity, 5e-4);
    set("drive_compliance", 0.0);
    set("prismatic_target", -0.55);
    run(4.0);
    EXPECT_NEAR(offset("prismatic_drive"), -0.55, 1e-4);
}

TEST_F(JointTypes, HingeDriveReachesTheKnobsTarget) {
    set("animate", 0);
    for (const double target : {0.9, -1.2, 0.3}) {
        set("hinge_target", target);
        run(3.0);
        EXPECT_NEAR(wrapped(hingeAngle("hinge_drive")), target, 1e-3) << "target " << target;
    }
    // A compliant drive sags below its target by α τ, the weight's torque at the angle reached.
    set("drive_compliance", 0.05);
    run(8.0);
    const double angle = wrapped(hingeAngle("hinge_drive"));
    const double torque = kMass * kGravity * 0.5 * kBarLength * std::cos(angle);
    EXPECT_NEAR(0.3 - angle, 0.05 * torque, 1e-3);
    // Drives off: the bar hangs straight down (no limits on it).
    set("drives", 0);
    run(10.0);
    EXPECT_NEAR(wrapped(hingeAngle("hinge_drive")), -M_PI / 2, 2e-2);
}

TEST_F(JointTypes, SphericalSwingAndTwistLimitsHold) {
    set("swing_limit", 0.4);
    set("twist_limit", 0.25);
    double largestSwing = 0.0;
    double largestTwist = 0.0;
    for (int frame = 0; frame < 8 * 60; ++frame) {
        run(1.0 / 60.0);
        largestSwing = std::max(largestSwing, swing("ball_hard"));
        largestTwist = std::max(largestTwist, std::abs(twist("ball_hard")));
    }
    EXPECT_LE(largestSwing, 0.4 + 3e-3);
    EXPECT_LE(largestTwist, 0.25 + 3e-3);
    // The weight holds the hard plate on both limits...
    EXPECT_NEAR(swing("ball_hard"), 0.4, 3e-3);
    EXPECT_NEAR(std::abs(twist("ball_hard")), 0.25, 3e-3);
    // ... and pushes the soft one beyond them.
    EXPECT_GT(swing("ball_soft"), 0.4 + 0.03);
    EXPECT_GT(std::abs(twist("ball_soft")), 0.25 + 0.01);
}

}  // namespace
}  // namespace substep

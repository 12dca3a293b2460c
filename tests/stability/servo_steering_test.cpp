// Stability of a light driver moving a heavy load (docs/STABILITY.md): the RC car's steering of
// paper Fig. 16, a 3 cm servo arm turning a wheel of 760 times its mass through a tie rod.

#include "stability_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace substep::stability {
namespace {

// Paper, the remote controlled car (Fig. 16): "The mass ration [sic] between the servo arm and
// the wheels is 1:760. The servo arm is 3cm long while the wheels have a diameter of 15cm."
constexpr double kArmMass = 0.001;  // 1 g servo arm
constexpr double kWheelMass = 760 * kArmMass;
constexpr double kArmLength = 0.03;
constexpr double kWheelDiameter = 0.15;
constexpr double kServoSpeed = 10.0;  // rad/s: a hobby servo's 0.1 s per 60°

const Vec3 kServoPivot(0.0, 0.3, 0.0);
const Vec3 kKingpin(0.0, 0.3, 0.2);    // steering axis of the knuckle, parallel to the servo's
constexpr double kWheelOffset = 0.06;  // wheel centre outboard of the kingpin (z)

/// The steering linkage, a parallelogram seen from above (y up): the servo arm turns about y at
/// kServoPivot, driven by the hinge motor; a 0.2 m tie rod (2 g) joins the arm's tip to the
/// tip of the knuckle's 3 cm steering arm by spherical joints; the knuckle (30 g) turns about y
/// at kKingpin; the wheel (760 g, 15 cm, axle along z) turns on the knuckle about its axle, and
/// may spin. The parallelogram makes the knuckle's angle equal the arm's.
struct Steering {
    World world;
    BodyId arm, rod, knuckle, wheel;
    JointId servo;

    Steering(int substeps, double wheelSpin)
        : world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps}) {
        const Vec3 halfArm(kArmLength / 2, 0, 0);
        arm = world.createBody({.shape = boxShape(Vec3(kArmLength, 0.006, 0.004)),
                                .mass = kArmMass,
                                .position = kServoPivot + halfArm});
        const double rodLength = (kKingpin - kServoPivot).norm();
        rod = world.createBody({.shape = boxShape(Vec3(0.004, 0.004, rodLength)),
                                .mass = 2 * kArmMass,
                                .position = (kServoPivot + kKingpin) / 2 + 2 * halfArm});
        knuckle = world.createBody({.shape = boxShape(Vec3(kArmLength, 0.02, 0.02)),
                                    .mass = 30 * kArmMass,
                                    .position = kKingpin + halfArm});
        const Vec3 wheelCentre = kKingpin + Vec3(0, 0, kWheelOffset);
        wheel = world.createBody({.shape = boxShape(Vec3(kWheelDiameter, kWheelDiameter, 0.05)),
                                  .mass = kWheelMass,
                                  .position = wheelCentre,
                                  .angularVelocity = Vec3(0, 0, wheelSpin)});
        // The motor advances the drive's target by h v every substep: the servo's target
        // moves smoothly within a frame.
        servo = world.createJoint({.type = JointType::Hinge,
                                   .body1 = arm,
                                   .anchor0 = kServoPivot,
                                   .anchor1 = -halfArm,
                                   .axis0 = Vec3::UnitY(),
                                   .axis1 = Vec3::UnitY(),
                                   .targetVelocity = 0.0});
        world.createJoint({.type = JointType::Spherical,
                           .body0 = arm,
                           .body1 = rod,
                           .anchor0 = halfArm,
                           .anchor1 = Vec3(0, 0, -rodLength / 2)});
        world.createJoint({.type = JointType::Spherical,
                           .body0 = rod,
                           .body1 = knuckle,
                           .anchor0 = Vec3(0, 0, rodLength / 2),
                           .anchor1 = halfArm});
        world.createJoint({.type = JointType::Hinge,
                           .body1 = knuckle,
                           .anchor0 = kKingpin,
                           .anchor1 = -halfArm,
                           .axis0 = Vec3::UnitY(),
                           .axis1 = Vec3::UnitY()});
        world.createJoint({.type = JointType::Hinge,
                           .body0 = knuckle,
                           .body1 = wheel,
                           .anchor0 = Vec3(-kArmLength / 2, 0, kWheelOffset),
                           .axis0 = Vec3::UnitZ(),
                           .axis1 = Vec3::UnitZ()});
    }

    double steeringAngle() const { return yawAngle(world.body(knuckle)); }
    /// The wheel's spin rate about its axle (rad/s).
    double spin() const {
        const Body& w = world.body(wheel);
        return w.omega.dot(test::userAxis(w, Vec3::UnitZ()));
    }
    /// The servo's target angle (rad), advanced by the motor.
    double target() const { return world.joint(servo).hinge().target; }
    /// Sets the motor speed that brings the target to `angle` within one frame, at most
    /// kServoSpeed.
    void command(double angle) {
        HingeJoint& j = world.joint(servo).hinge();
        j.targetVelocity = std::clamp((angle - j.target) / kDt, -kServoSpeed, kServoSpeed);
    }
};

/// The steering command (rad): full left, full right, then a 2 Hz weave.
double steeringCommand(double t) {
    if (t < 1.0) return 0.5;
    if (t < 2.0) return -0.5;
    return 0.4 * std::sin(2 * kPi * 2.0 * (t - 2.0));
}

struct SteeringRun {
    Outcome outcome;         ///< measure: holdError
    double holdError = 0.0;  ///< largest |steering − target| in the last 0.3 s of each hold (rad)
    double trackError = 0.0;    ///< largest |steering − target| over the run (rad)
    double steeringRate = 0.0;  ///< largest steering rate of the knuckle (rad/s)
    double spinChange = 0.0;    ///< largest relative change of the wheel's spin rate
};

/// Steers for 3 s, the motor's speed set once per frame (a 60 Hz controller).
SteeringRun steer(int substeps, double wheelSpin) {
    Steering rig(substeps, wheelSpin);
    SteeringRun run;
    rig.command(steeringCommand(kDt));
    run.outcome = watch(rig.world, 3.0, kDt, [&](double t) {
        const double error = std::abs(rig.steeringAngle() - rig.target());
        run.trackError = std::max(run.trackError, error);
        if ((t > 0.7 && t < 1.0) || (t > 1.7 && t < 2.0))
            run.holdError = std::max(run.holdError, error);
        run.steeringRate =
            std::max(run.steeringRate, std::abs(rig.world.body(rig.knuckle).omega.y()));
        if (wheelSpin > 0.0)
            run.spinChange = std::max(run.spinChange, std::abs(rig.spin() - wheelSpin) / wheelSpin);
        rig.command(steeringCommand(t + kDt));
        return run.holdError;
    });
    return run;
}

// The servo arm steers the wheel left, right and through a 2 Hz weave at a hobby servo's speed,
// with the wheel still and spinning at 130 rad/s (10 m/s on 15 cm wheels: steering then also
// fights the wheel's gyroscopic torque). Something drives the system, so energy is not bounded.
// Holds: finite, every joint within 1 mm, the steering angle within 0.02 rad of the servo's
// target in the last 0.3 s of each hold.
// Measured: the paper's 20 substeps do not hold. The hard drive on the 1 g arm acts on the 760 g
// wheel like an undamped spring whose stiffness grows as 1/h² (each substep the wheel takes up
// only the arm's share of the correction, as in ERRATA item 7), so the wheel overshoots the
// target and rings about it: at 20 substeps it swings past the linkage's dead point and turns
// round (steering error up to 3.6 rad), and only from about 2560 substeps does it settle within
// 0.02 rad. The still wheel never blows up (every count finite, joints within about 1 cm).
// ENGINE WEAK SPOT, still present with the implicit gyroscopic term (docs/STABILITY.md): with the
// wheel spinning at 130 rad/s, 40 and 44 substeps blow up (1.8e14 J and 2.5e22 J, joints 84 km
// apart at 40), while 20-36 and 50-70 do not; at 60 rad/s 20 and 24 substeps blow up (4e43 J).
// The wheel swings through the linkage's dead point while spinning, on a knuckle of 1/25 its
// mass; which counts blow up is a matter of where the substeps land. On the list 80 to 5120 it
// never blows up, so for the spinning wheel the blow-up check applies from 80 substeps (its
// present limit); the still wheel is checked from the default 20.
class ServoSteeringTest : public ::testing::TestWithParam<double> {};

TEST_P(ServoSteeringTest, WheelFollowsTheServo) {
    const double wheelSpin = GetParam();
    const std::string name = wheelSpin > 0.0 ? "servo_steering_spinning" : "servo_steering";
    const Bounds bounds{.jointError = 1e-3, .measure = 0.02};
    const std::vector<int> counts{10, 20, 40, 80, 160, 320, 640, 1280, 2560, 5120};
    std::vector<SteeringRun> runs;
    const Sweep sweep = sweepSubsteps(name, counts, bounds, [&](int substeps) {
        runs.push_back(steer(substeps, wheelSpin));
        return runs.back().outcome;
    });
    for (size_t i = 0; i < counts.size(); ++i) {
        const SteeringRun& run = runs[i];
        std::printf(
            "[ measured ] %s @ %d substeps: hold error %.3g rad, track error %.3g rad, "
            "steering rate %.3g rad/s, spin change %.3g\n",
            name.c_str(), counts[i], run.holdError, run.trackError, run.steeringRate,
            run.spinChange);
        // Driven, so no energy check; a blow-up shows as joints opening beyond 5 cm or the
        // wheel steering faster than 1000 rad/s (the servo turns at 10). The spinning wheel is
        // checked from 80 substeps (its present limit, above), the still one from 20.
        const int blowUpFrom = wheelSpin > 0.0 ? 80 : 20;
        if (kDt / counts[i] <= kDefaultSubstep * (1.0 + 1e-9) && counts[i] >= blowUpFrom) {
            EXPECT_LT(run.outcome.jointError, 0.05) << name << " @ " << counts[i] << " blows up";
            EXPECT_LT(run.steeringRate, 1000.0) << name << " @ " << counts[i] << " blows up";
        }
    }
    report(name + "_hold_error_rad_at_20", sweep.at(20).measure);
    expectStable(name, sweep, 0.0, 2560);
}

INSTANTIATE_TEST_SUITE_P(Wheel, ServoSteeringTest, ::testing::Values(0.0, 130.0),
                         [](const ::testing::TestParamInfo<double>& param) {
                             return std::string(param.param > 0.0 ? "Spinning" : "Still");
                         });

}  // namespace
}  // namespace substep::stability

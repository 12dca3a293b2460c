// Tests sandbox/scenes/rc_car_autopilot.cpp on a kinematic car (a bicycle model: the heading
// turns at v tan(δ) / wheelbase, the speed follows the throttle with a lag), so that the lap's
// logic is checked over speeds, slips and starts it was not tuned on, in milliseconds; the real
// car's laps run in rc_car_soak_test (label `stability`).

#include "scenes/rc_car.h"
#include "scenes/rc_car_autopilot.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep::scenes::rc_car {
namespace {

constexpr double kDegree = M_PI / 180.0;

struct KinematicCar {
    Vec3 position = Vec3(-3.0, 0.0, 0.0);
    double heading = 0.0;
    double speed = 0.0;
    /// Ground speed at full throttle over the wheels' free speed: what the tyres' slip leaves.
    double grip = 0.9;

    void step(const DriveCommand& command, double dt) {
        const double target = command.throttle * kMaxWheelSpeed * kTyreRadius * grip;
        speed += (target - speed) * std::min(1.0, dt / 0.3);  // a motor and a mass: 0.3 s to follow
        heading += speed * std::tan(command.steer * kDegree) / kWheelbase * dt;
        position += speed * dt * Vec3(std::cos(heading), 0.0, -std::sin(heading));
    }
};

struct LapRecord {
    int laps = 0;                   ///< out legs begun after the first
    double farthest = 0.0;          ///< m: largest |x| or |z| reached
    double worstPlankOffset = 0.0;  ///< m: largest |z| when crossing x = 1.5 going out
    double worstPlankHeading = 0.0; ///< rad: largest |heading| there
};

LapRecord drive(KinematicCar car, double seconds) {
    Autopilot pilot;
    LapRecord record;
    const double dt = 1.0 / 60.0;
    Autopilot::Leg leg = pilot.leg();
    for (double t = 0.0; t < seconds; t += dt) {
        const double xBefore = car.position.x();
        car.step(pilot.drive(t, car.position, car.heading), dt);
        if (pilot.leg() == Autopilot::Leg::Out && leg == Autopilot::Leg::TurnHome) ++record.laps;
        leg = pilot.leg();
        record.farthest = std::max({record.farthest, std::abs(car.position.x()), std::abs(car.position.z())});
        if (leg == Autopilot::Leg::Out && xBefore < 1.5 && car.position.x() >= 1.5) {
            record.worstPlankOffset = std::max(record.worstPlankOffset, std::abs(car.position.z()));
            record.worstPlankHeading =
                std::max(record.worstPlankHeading, std::abs(std::remainder(car.heading, 2.0 * M_PI)));
        }
    }
    return record;
}

TEST(RcCarAutopilot, LapsStayOnTheTerrainAndCrossThePlanksOnTheLine) {
    // Grips from a slipping to a gripping car, and starts off the line and askew: every lap
    // comes back, far inside the 48 m field, and each straight crosses the planks (0.4 m wide,
    // at z = −0.1 and 0.12) within a few centimetres of the line, nearly straight.
    for (const double grip : {0.6, 0.8, 1.0}) {
        for (const double startZ : {0.0, 0.4, -0.4}) {
            for (const double startHeading : {0.0, 8.0 * kDegree}) {
                SCOPED_TRACE(::testing::Message() << "grip " << grip << ", start z " << startZ << ", heading "
                                                  << startHeading / kDegree << " deg");
                KinematicCar car;
                car.grip = grip;
                car.position.z() = startZ;
                car.heading = startHeading;
                const LapRecord record = drive(car, 300.0);
                EXPECT_GE(record.laps, 8);
                EXPECT_LT(record.farthest, 16.0);
                EXPECT_LT(record.worstPlankOffset, 0.08);
                EXPECT_LT(record.worstPlankHeading, 5.0 * kDegree);
            }
        }
    }
}

TEST(RcCarAutopilot, StandsStillWhileSettlingThenDrivesOut) {
    Autopilot pilot;
    const DriveCommand settling = pilot.drive(0.2, Vec3(-3.0, 0.0, 0.0), 0.0);
    EXPECT_EQ(settling.throttle, 0.0);
    EXPECT_EQ(settling.steer, 0.0);
    const DriveCommand out = pilot.drive(0.6, Vec3(-3.0, 0.0, 0.0), 0.0);
    EXPECT_GT(out.throttle, 0.0);
    EXPECT_EQ(out.steer, 0.0);  // on the line, along it
    // Left of the line (−z) it steers right, towards it, and the other way round.
    EXPECT_LT(pilot.drive(0.7, Vec3(-2.0, 0.0, -0.5), 0.0).steer, 0.0);
    EXPECT_GT(pilot.drive(0.8, Vec3(-2.0, 0.0, 0.5), 0.0).steer, 0.0);
}

TEST(RcCarAutopilot, HeadingIsMeasuredFromPlusXTurningLeft) {
    EXPECT_NEAR(headingOf(Vec3(1.0, 0.0, 0.0)), 0.0, 1e-15);
    EXPECT_NEAR(headingOf(Vec3(0.0, 0.0, -1.0)), 0.5 * M_PI, 1e-15);  // left of +x is −z
    EXPECT_NEAR(std::abs(headingOf(Vec3(-1.0, 0.0, 0.0))), M_PI, 1e-15);
    EXPECT_NEAR(headingOf(Vec3(1.0, 0.5, 1.0)), -0.25 * M_PI, 1e-15);  // the chassis' pitch aside
}

}  // namespace
}  // namespace substep::scenes::rc_car

#include "scenes/rc_car_autopilot.h"

#include <algorithm>
#include <cmath>

namespace substep::scenes::rc_car {

namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr double kSettleTime = 0.5;      ///< s standing before the first straight
constexpr double kOutEnd = 10.0;         ///< m: x where the first straight ends, past the ramp
constexpr double kReturnLine = -3.0;     ///< m: z of the way back, clear of the obstacles
constexpr double kBackEnd = -5.0;        ///< m: x where the way back ends, behind the start
constexpr double kLookAhead = 2.0;       ///< m: how far ahead on its line a straight steers to
constexpr double kTurnSteer = 14.0;      ///< degrees, the turns' steering
constexpr double kMaxLineSteer = 10.0;   ///< degrees: a straight corrects at most this much

/// `angle` wrapped into (−π, π].
double wrapped(double angle) { return std::remainder(angle, 2.0 * M_PI); }

/// Steering (degrees) that brings a car heading `heading` at `position` onto the line through
/// z = `lineZ` along `lineHeading` (0 or π): towards the point kLookAhead ahead on the line.
double holdLine(const Vec3& position, double heading, double lineZ, double lineHeading) {
    // Left of a heading h is (−sin h, −cos h) in (x, z); the car's offset to the line's left:
    const double left = -std::cos(lineHeading) * (position.z() - lineZ);
    const double wanted = lineHeading - std::atan2(left, kLookAhead);
    return std::clamp(wrapped(wanted - heading) / kDegree, -kMaxLineSteer, kMaxLineSteer);
}

}  // namespace

double headingOf(const Vec3& forward) { return std::atan2(-forward.z(), forward.x()); }

DriveCommand Autopilot::drive(double time, const Vec3& position, double heading) {
    // Each leg hands over to the next when the car reaches its end, so one call may pass
    // through several legs.
    if (leg_ == Leg::Settle && time >= kSettleTime) leg_ = Leg::Out;
    if (leg_ == Leg::Out && position.x() >= kOutEnd) leg_ = Leg::TurnForward;
    if (leg_ == Leg::TurnForward && wrapped(heading) >= 90.0 * kDegree) leg_ = Leg::TurnReverse;
    if (leg_ == Leg::TurnReverse && std::abs(wrapped(heading - M_PI)) <= 10.0 * kDegree) leg_ = Leg::Back;
    if (leg_ == Leg::Back && position.x() <= kBackEnd) leg_ = Leg::TurnHome;
    if (leg_ == Leg::TurnHome && std::abs(wrapped(heading)) <= 10.0 * kDegree && position.z() > kReturnLine)
        leg_ = Leg::Out;
    switch (leg_) {
        case Leg::Settle:
            return {};
        case Leg::Out:
            return {0.7, holdLine(position, heading, 0.0, 0.0)};
        case Leg::TurnForward:
            return {0.4, kTurnSteer};
        case Leg::TurnReverse:
            return {-0.5, -kTurnSteer};
        case Leg::Back:
            return {0.7, holdLine(position, heading, kReturnLine, M_PI)};
        case Leg::TurnHome:
            return {0.4, kTurnSteer};
    }
    return {};
}

}  // namespace substep::scenes::rc_car

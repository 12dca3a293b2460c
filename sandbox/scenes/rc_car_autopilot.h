#pragma once

// The RC car's autopilot: a closed lap over the obstacles and back, steered by where the car
// is, so that lap after lap it stays on the terrain whatever its tyres slip.

#include "physics/math.h"

namespace substep::scenes::rc_car {

/// A command to the car: throttle in [−1, 1], steering in degrees (+ left).
struct DriveCommand {
    double throttle = 0.0;
    double steer = 0.0;
};

/// The lap: settle; out along z = 0 over the bumps, planks, curb and ramp; a three-point turn
/// (forward to the left, then in reverse steering right); back along z = kReturnLine past the
/// start; a U-turn to the left onto the first straight; and again. Each leg ends where the car
/// is, not at a time, and the straights hold their line by steering towards a point ahead on it.
class Autopilot {
  public:
    /// The command for the chassis at `position` heading `heading` (rad about +y, 0 along +x,
    /// + left) at scene time `time`.
    DriveCommand drive(double time, const Vec3& position, double heading);

    enum class Leg { Settle, Out, TurnForward, TurnReverse, Back, TurnHome };
    Leg leg() const { return leg_; }

  private:
    Leg leg_ = Leg::Settle;
};

/// The heading of a chassis whose forward axis is `forward` (rad about +y, 0 along +x, + left).
double headingOf(const Vec3& forward);

}  // namespace substep::scenes::rc_car

#pragma once
/// Dispatch over joint types (a switch, no virtual calls in the solver loop).

#include "physics/correction.h"
#include "physics/joints/joint.h"

namespace substep {

/// Before a substep's solve: zeroes the parts' multipliers (paper 3.3.1) and advances a hinge
/// motor's target by h·v (paper after Eq. 21). Inline: it runs for every joint every substep.
inline void beginJointSubstep(Joint& joint, double h) {
    joint.resetMultipliers();
    if (HingeJoint* hinge = std::get_if<HingeJoint>(&joint.model); hinge && hinge->drive == JointDrive::Velocity)
        hinge->target = wrapAngle(hinge->target + h * hinge->targetVelocity);
}
/// One position-level projection of the joint (all its parts).
void solveJointPositions(Joint& joint, SolverContext& ctx);
/// Velocity pass: joint damping, Eq. 31 (linear) and Eq. 32 (angular), applied by Eq. 33.
void solveJointVelocities(const Joint& joint, Body* bodies, double h);
/// Force, torque (from the last substep's impulses, Eqs. 10 and 17), error, elastic energy and
/// coordinate.
JointReadout readJoint(const Joint& joint, const Body* bodies, double h);
/// The joint's coordinate (JointReadout::coordinate) on the current state.
double jointCoordinate(const Joint& joint, const Body* bodies);

}  // namespace substep

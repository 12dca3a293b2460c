#pragma once
/// Dispatch over joint types (a switch, no virtual calls in the solver loop).

#include "physics/correction.h"
#include "physics/joints/joint.h"

namespace substep {

/// One position-level projection of the joint (all its parts).
void solveJointPositions(Joint& joint, SolverContext& ctx);
/// Velocity pass: joint damping, Eqs. 31-32.
void solveJointVelocities(const Joint& joint, Body* bodies, double h);
/// Force, torque (from the last substep's impulses, Eqs. 10 and 17), error, elastic energy and
/// coordinate.
JointReadout readJoint(const Joint& joint, const Body* bodies, double h);
/// The joint's coordinate (JointReadout::coordinate) on the current state.
double jointCoordinate(const Joint& joint, const Body* bodies);

}  // namespace substep

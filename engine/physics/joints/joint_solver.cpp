#include "physics/joints/joint_solver.h"

#include "physics/joints/joint_parts.h"

#include <algorithm>

namespace substep {

void solveJointPositions(Joint& joint, SolverContext& ctx) {
    switch (joint.type) {
        case JointType::Distance: solveDistanceJoint(joint, ctx); break;
        case JointType::Fixed: solveFixedJoint(joint, ctx); break;
        case JointType::Hinge: solveHingeJoint(joint, ctx); break;
        case JointType::Spherical: solveSphericalJoint(joint, ctx); break;
        case JointType::Prismatic: solvePrismaticJoint(joint, ctx); break;
    }
}

void solveJointVelocities(const Joint& joint, Body* bodies, double h) {
    Body& b0 = bodies[joint.body0];
    Body& b1 = bodies[joint.body1];
    if (joint.linearDamping > 0.0) {
        // Eq. 31 on the anchor points: body 0's anchor velocity moves toward body 1's.
        const Vec3 r0 = b0.toWorld(joint.anchor0);
        const Vec3 r1 = b1.toWorld(joint.anchor1);
        const Vec3 relative = (b1.v + b1.omega.cross(r1)) - (b0.v + b0.omega.cross(r0));
        applyVelocityCorrection(b0, b1, relative * std::min(joint.linearDamping * h, 1.0), r0, r1);
    }
    if (joint.angularDamping > 0.0) {
        const Vec3 relative = b1.omega - b0.omega;  // Eq. 32
        applyAngularVelocityCorrection(b0, b1, relative * std::min(joint.angularDamping * h, 1.0));
    }
}

JointReadout readJoint(const Joint& joint, const Body* bodies, double h) {
    JointEvaluation evaluation;
    switch (joint.type) {
        case JointType::Distance: evaluation = evaluateDistanceJoint(joint, bodies); break;
        case JointType::Fixed: evaluation = evaluateFixedJoint(joint, bodies); break;
        case JointType::Hinge: evaluation = evaluateHingeJoint(joint, bodies); break;
        case JointType::Spherical: evaluation = evaluateSphericalJoint(joint, bodies); break;
        case JointType::Prismatic: evaluation = evaluatePrismaticJoint(joint, bodies); break;
    }
    const double invH2 = h > 0.0 ? 1.0 / (h * h) : 0.0;
    return {.force = joint.linearImpulse.norm() * invH2,
            .torque = joint.angularImpulse.norm() * invH2,
            .error = evaluation.error,
            .elasticEnergy = evaluation.elasticEnergy};
}

}  // namespace substep

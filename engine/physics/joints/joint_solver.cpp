#include "physics/joints/joint_solver.h"

#include "physics/correction_kernels.h"
#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_rows.h"

#include <algorithm>
#include <cmath>

namespace substep {

void solveJointPositions(Joint& joint, SolverContext& ctx) {
    switch (joint.model.index()) {
        case 0: solveDistanceJoint(joint, *std::get_if<DistanceJoint>(&joint.model), ctx); break;
        case 1: solveFixedJoint(joint, *std::get_if<FixedJoint>(&joint.model), ctx); break;
        case 2: solveHingeJoint(joint, *std::get_if<HingeJoint>(&joint.model), ctx); break;
        case 3: solveSphericalJoint(joint, *std::get_if<SphericalJoint>(&joint.model), ctx); break;
        case 4: solvePrismaticJoint(joint, *std::get_if<PrismaticJoint>(&joint.model), ctx); break;
    }
}

void appendJointRows(Joint& joint, const SolverContext& ctx, JointRows& rows) {
    switch (joint.model.index()) {
        case 0: appendDistanceRows(joint, *std::get_if<DistanceJoint>(&joint.model), ctx, rows); break;
        case 1: appendFixedRows(joint, *std::get_if<FixedJoint>(&joint.model), ctx, rows); break;
        case 2: appendHingeRows(joint, *std::get_if<HingeJoint>(&joint.model), ctx, rows); break;
        case 3: appendSphericalRows(joint, *std::get_if<SphericalJoint>(&joint.model), ctx, rows); break;
        case 4: appendPrismaticRows(joint, *std::get_if<PrismaticJoint>(&joint.model), ctx, rows); break;
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
        correction_kernels::angularVelocityCorrection(b0, b1, relative * std::min(joint.angularDamping * h, 1.0));
    }
}

JointReadout readJoint(const Joint& joint, const Body* bodies, double h) {
    JointEvaluation evaluation;
    switch (joint.model.index()) {
        case 0: evaluation = evaluateDistanceJoint(joint, *std::get_if<DistanceJoint>(&joint.model), bodies); break;
        case 1: evaluation = evaluateFixedJoint(joint, *std::get_if<FixedJoint>(&joint.model), bodies); break;
        case 2: evaluation = evaluateHingeJoint(joint, *std::get_if<HingeJoint>(&joint.model), bodies); break;
        case 3: evaluation = evaluateSphericalJoint(joint, *std::get_if<SphericalJoint>(&joint.model), bodies); break;
        case 4: evaluation = evaluatePrismaticJoint(joint, *std::get_if<PrismaticJoint>(&joint.model), bodies); break;
    }
    // Eq. 10: f = λn/h², and Eq. 17: τ = λn/h², summed over the joint's parts.
    const double invH2 = h > 0.0 ? 1.0 / (h * h) : 0.0;
    return {.force = joint.linearImpulse().norm() * invH2,
            .torque = joint.angularImpulse().norm() * invH2,
            .error = evaluation.error,
            .elasticEnergy = evaluation.elasticEnergy,
            .coordinate = jointCoordinate(joint, bodies)};
}

double jointCoordinate(const Joint& joint, const Body* bodies) {
    switch (joint.type()) {
        case JointType::Hinge: return hingeAngle(joint, bodies);
        case JointType::Spherical: {
            const Vec3 a0 = worldFrame0(joint, bodies) * Vec3::UnitX();
            const Vec3 a1 = worldFrame1(joint, bodies) * Vec3::UnitX();
            return std::atan2(a0.cross(a1).norm(), a0.dot(a1));
        }
        case JointType::Prismatic: {
            const JointAnchors anchors = jointAnchors(joint, bodies);
            return (anchors.p1 - anchors.p0).dot(worldFrame0(joint, bodies) * Vec3::UnitX());
        }
        case JointType::Distance:
        case JointType::Fixed: return 0.0;
    }
    return 0.0;
}

}  // namespace substep

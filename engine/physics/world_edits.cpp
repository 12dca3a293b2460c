/// Changes to live world objects: a joint's parameters, a body's pose, velocity and surface.
/// The engine layer's physics system is their one caller in the product (it applies the
/// components the sandbox patched); each change keeps the rest of the running state, so
/// a parameter set to the value it already has changes nothing, bit for bit.

#include "physics/world.h"

#include "physics/joints/joint_frame.h"
#include "physics/joints/joint_parts.h"

#include <stdexcept>

namespace substep {

void World::setJointParameters(Joint& joint, const JointDef& def) {
    // Anchors and frames go from each body's user frame into its principal frame; the world's
    // are already in world coordinates.
    const Body& b0 = bodies_[joint.body0];
    const Body& b1 = bodies_[joint.body1];
    joint.anchor0 = b0.userRotation * def.anchor0 + b0.userOrigin;
    joint.anchor1 = b1.userRotation * def.anchor1 + b1.userOrigin;
    joint.frame0 = (b0.userRotation * jointFrame(def.axis0, def.normal0)).normalized();
    joint.frame1 = (b1.userRotation * jointFrame(def.axis1, def.normal1)).normalized();
    joint.compliance = def.compliance;
    joint.maxDistance = def.maxDistance;
    joint.hasLimits = def.limits.has_value();
    if (def.limits) joint.limits = *def.limits;
    joint.limitCompliance = def.limitCompliance;
    joint.driveCompliance = def.driveCompliance;
    if (def.targetVelocity) {
        // A motor keeps the angle it has reached when only its speed changes.
        if (joint.drive != Joint::Drive::Velocity)
            joint.target = def.type == JointType::Hinge ? hingeAngle(joint, bodies_.data()) : 0.0;
        joint.drive = Joint::Drive::Velocity;
        joint.targetVelocity = *def.targetVelocity;
    } else if (def.targetAngle || def.targetOffset) {
        joint.drive = Joint::Drive::Position;
        joint.target = def.targetAngle ? *def.targetAngle : *def.targetOffset;
    } else {
        joint.drive = Joint::Drive::None;
    }
    joint.hasSwingLimit = def.swingLimit.has_value();
    joint.swingLimit = def.swingLimit.value_or(0.0);
    joint.hasTwistLimits = def.twistLimits.has_value();
    if (def.twistLimits) joint.twistLimits = *def.twistLimits;
    joint.twistCompliance = def.twistCompliance.value_or(def.limitCompliance);
    joint.linearDamping = def.linearDamping;
    joint.angularDamping = def.angularDamping;
    joint.collide = def.collide;
}

void World::updateJoint(JointId id, const JointDef& def) {
    Joint& joint = this->joint(id);
    if (def.type != joint.type) throw std::invalid_argument("World::updateJoint: a joint keeps its type");
    const bool collided = joint.collide;
    setJointParameters(joint, def);
    if (joint.collide != collided) jointsChanged_ = true;
}

void World::setBodyPose(BodyId id, const Vec3& position, const Quat& orientation) {
    Body& body = this->body(id);
    // An orientation within rounding of the current one leaves q alone, so moving a body does
    // not perturb its rotation (the user frame's quaternion is q times a fixed rotation,
    // normalised, so it does not give q back bit for bit).
    if (orientation.angularDistance(body.userOrientation()) > 1e-12)
        body.q = (orientation * body.userRotation.conjugate()).normalized();
    body.x = position - body.q * body.userOrigin;
    // Moved, not pushed: the previous pose goes along, so the body carries no velocity from the
    // move and only the joints and contacts on it feel it.
    body.xPrev = body.x;
    body.qPrev = body.q;
}

void World::setBodyVelocity(BodyId id, const Vec3& velocity, const Vec3& angularVelocity) {
    Body& body = this->body(id);
    if (!body.isDynamic()) return;  // a static body has no velocity to set
    body.v = velocity;
    if (body.rotates()) body.omega = angularVelocity;
}

void World::setBodySurface(BodyId id, double staticFriction, double dynamicFriction,
                           double restitution, bool collide) {
    Body& body = this->body(id);
    body.staticFriction = staticFriction;
    body.dynamicFriction = dynamicFriction;
    body.restitution = restitution;
    const bool collided = body.alive && body.collide && body.shape.type != ShapeType::None;
    body.collide = collide;
    const bool collides = body.alive && body.collide && body.shape.type != ShapeType::None;
    collidingBodies_ += static_cast<int>(collides) - static_cast<int>(collided);
}

}  // namespace substep

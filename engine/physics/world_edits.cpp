/// Changes to live world objects: a joint's parameters, a body's pose, velocity and surface.
/// The engine layer's physics system is their one caller in the product (it applies the
/// components the sandbox patched); each change keeps the rest of the running state, so
/// a parameter set to the value it already has changes nothing, bit for bit.

#include "physics/world.h"


#include <stdexcept>

namespace substep {

void World::updateJoint(JointId id, const JointDef& def) {
    Joint& joint = this->joint(id);
    if (def.type != joint.type()) throw std::invalid_argument("World::updateJoint: a joint keeps its type");
    const bool collided = joint.collide;
    // A motor keeps the angle it has reached when only its speed changes; everything else is the
    // definition's (the parts' multipliers start from zero every substep anyway).
    const HingeJoint* hinge = joint.type() == JointType::Hinge ? &joint.hinge() : nullptr;
    const bool wasMotor = hinge != nullptr && hinge->drive == JointDrive::Velocity;
    const double reached = wasMotor ? hinge->target : 0.0;
    setJointParameters(joint, def);
    if (wasMotor && joint.hinge().drive == JointDrive::Velocity) joint.hinge().target = reached;
    if (joint.collide != collided) jointsChanged_ = true;
    sleep_.wake(joint.body0, bodies_[joint.body0]);
    sleep_.wake(joint.body1, bodies_[joint.body1]);
}

void World::setBodyPose(BodyId id, const Vec3& position, const Quat& orientation) {
    Body& body = bodies_[checked(id)];
    wakeBody(id);
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
    Body& body = bodies_[checked(id)];
    if (!body.isDynamic()) return;  // a static body has no velocity to set
    wakeBody(id);
    body.v = velocity;
    if (body.rotates()) body.omega = angularVelocity;
}

void World::setBodySurface(BodyId id, double staticFriction, double dynamicFriction,
                           double restitution, bool collide) {
    Body& body = bodies_[checked(id)];
    wakeBody(id);
    body.staticFriction = staticFriction;
    body.dynamicFriction = dynamicFriction;
    body.restitution = restitution;
    const bool collided = body.alive && body.collide && body.shape.type != ShapeType::None;
    body.collide = collide;
    const bool collides = body.alive && body.collide && body.shape.type != ShapeType::None;
    collidingBodies_ += static_cast<int>(collides) - static_cast<int>(collided);
}

}  // namespace substep

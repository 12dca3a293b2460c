#include "physics/body.h"

#include "physics/mass_properties.h"

#include <algorithm>

namespace substep {
namespace {

/// A dynamic body without a shape that has mass (a bare point mass) gets the inertia of a
/// 10 cm sphere of that mass, so that joints acting off its centre stay well conditioned.
constexpr double kShapelessRadius = 0.1;

/// Smallest principal moment relative to the largest: thinner bodies are clamped so that
/// I⁻¹ stays finite (a zero moment would let any torque spin the body infinitely fast).
constexpr double kMinMomentRatio = 1e-9;

}  // namespace

Body makeBody(const BodyDef& def) {
    Body body;
    body.type = def.type;
    body.shape = def.shape;
    body.staticFriction = def.staticFriction;
    body.dynamicFriction = def.dynamicFriction;
    body.restitution = def.restitution;
    body.collide = def.collide;
    body.collisionGroup = def.collisionGroup;
    body.collisionMask = def.collisionMask;
    body.alive = true;

    if (def.type == BodyType::Static) {
        body.x = def.position;
        body.q = def.orientation.normalized();
    } else {
        MassProperties props = shapeMassProperties(def.shape, def.density);
        if (def.mass > 0.0) {
            props = props.mass > 0.0 ? withMass(props, def.mass)
                                     : MassProperties{def.mass, Vec3::Zero(),
                                                      Mat3::Identity() * (0.4 * def.mass * kShapelessRadius *
                                                                          kShapelessRadius)};
        }
        body.mass = props.mass;
        body.invMass = props.mass > 0.0 ? 1.0 / props.mass : 0.0;
        PrincipalFrame principal = principalFrame(props.inertia);
        if (def.type == BodyType::Particle) principal = PrincipalFrame{};
        const double largest = std::max(principal.moments.maxCoeff(), 0.0);
        for (int i = 0; i < 3; ++i) {
            const double moment = std::max(principal.moments[i], largest * kMinMomentRatio);
            body.inertia[i] = def.type == BodyType::Particle ? 0.0 : moment;
            body.invInertia[i] = body.inertia[i] > 0.0 ? 1.0 / body.inertia[i] : 0.0;
        }
        body.isotropic = body.inertia.x() == body.inertia.y() && body.inertia.y() == body.inertia.z();
        // User frame -> principal frame: p_principal = Rᵀ (p_user − com).
        body.userRotation = principal.rotation.conjugate();
        body.userOrigin = -(body.userRotation * props.centerOfMass);
        const Quat userOrientation = def.orientation.normalized();
        body.q = (userOrientation * principal.rotation).normalized();
        body.x = def.position + userOrientation * props.centerOfMass;
        body.v = def.velocity;
        body.omega = def.type == BodyType::Particle ? Vec3::Zero() : def.angularVelocity;
    }
    body.xPrev = body.x;
    body.qPrev = body.q;
    body.vPrev = body.v;
    body.omegaPrev = body.omega;
    return body;
}

}  // namespace substep

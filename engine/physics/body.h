#pragma once
/// Rigid bodies and particles: their creation settings and the simulation state the solver
/// works on.

#include "physics/collision/shape.h"
#include "physics/math.h"

#include <cstdint>

namespace substep {

enum class BodyType : uint8_t {
    Static,    ///< never moves; infinite mass
    Dynamic,   ///< a rigid body: position, orientation and their velocities
    Particle,  ///< position only (soft bodies): the same loop with the rotation left out
};

/// Creation settings. Pose and anchors refer to the body's user frame (the shape's frame);
/// the world keeps the body in its principal frame and converts.
struct BodyDef {
    Shape shape;
    BodyType type = BodyType::Dynamic;
    double mass = 0.0;       ///< > 0 overrides density
    double density = 1000.0; ///< kg/m³, used when mass is 0
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 velocity = Vec3::Zero();         ///< of the centre of mass
    Vec3 angularVelocity = Vec3::Zero();
    double staticFriction = 0.5;
    double dynamicFriction = 0.3;
    double restitution = 0.0;
    bool collide = true;
    /// Collision filter (as Box2D's category and mask bits): two bodies meet only when each one's
    /// group is in the other's mask. The defaults let everything meet.
    uint32_t collisionGroup = 1;
    uint32_t collisionMask = ~0u;
};

/// Simulation state of one body, in its principal frame: `x` is the centre of mass, `q` turns
/// principal-frame vectors into world vectors, and the inertia is diagonal (paper 3.3.2).
struct Body {
    Vec3 x = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 v = Vec3::Zero();
    Vec3 omega = Vec3::Zero();  ///< world angular velocity ω = ω n_rot (Eq. 1)
    Vec3 xPrev = Vec3::Zero();
    Quat qPrev = Quat::Identity();
    Vec3 vPrev = Vec3::Zero();      ///< velocity before the substep's velocity derivation
    Vec3 omegaPrev = Vec3::Zero();
    double invMass = 0.0;
    Vec3 invInertia = Vec3::Zero();  ///< principal moments, inverted (0 where locked/static)
    double mass = 0.0;
    Vec3 inertia = Vec3::Zero();
    BodyType type = BodyType::Static;
    bool isotropic = false;  ///< equal principal moments: no gyroscopic term
    bool alive = false;
    uint32_t generation = 0;

    // Cold data: the user frame relative to the principal frame, and surface properties.
    Vec3 userOrigin = Vec3::Zero();          ///< user-frame origin in principal coordinates
    Quat userRotation = Quat::Identity();    ///< user-frame vectors -> principal-frame vectors
    Shape shape;
    double staticFriction = 0.5;
    double dynamicFriction = 0.3;
    double restitution = 0.0;
    bool collide = true;
    uint32_t collisionGroup = 1;   ///< BodyDef::collisionGroup
    uint32_t collisionMask = ~0u;  ///< BodyDef::collisionMask

    /// Whether the collision filters of two bodies let them meet.
    static bool filtersMeet(const Body& a, const Body& b) {
        return (a.collisionGroup & b.collisionMask) != 0 && (b.collisionGroup & a.collisionMask) != 0;
    }

    bool isDynamic() const { return invMass > 0.0; }
    bool rotates() const { return type == BodyType::Dynamic; }

    /// World vector of a principal-frame vector.
    Vec3 toWorld(const Vec3& local) const { return q * local; }
    /// World point of a principal-frame point.
    Vec3 pointToWorld(const Vec3& local) const { return x + q * local; }

    /// I⁻¹ v for a world vector v, evaluated in the rest frame (paper 3.3.2).
    /// With equal moments (spheres, cubes) I⁻¹ is a scalar and needs no rotation.
    Vec3 applyInverseInertia(const Vec3& worldVector) const {
        if (isotropic) return invInertia.x() * worldVector;
        return q * invInertia.cwiseProduct(q.conjugate() * worldVector);
    }
    /// The generalised inverse mass of Eq. 2 (Eq. 3) for a correction along unit n at offset r.
    double positionalInverseMass(const Vec3& r, const Vec3& n) const {
        const Vec3 rn = r.cross(n);
        if (isotropic) return invMass + invInertia.x() * rn.squaredNorm();
        const Vec3 rnBody = q.conjugate() * rn;
        return invMass + rnBody.dot(invInertia.cwiseProduct(rnBody));
    }
    /// The generalised inverse mass of Eq. 11 (Eq. 12) for a rotation about unit n.
    double angularInverseMass(const Vec3& n) const {
        if (isotropic) return invInertia.x() * n.squaredNorm();
        const Vec3 nb = q.conjugate() * n;
        return nb.dot(invInertia.cwiseProduct(nb));
    }

    /// Pose of the user frame (for output and rendering).
    Vec3 userPosition() const { return pointToWorld(userOrigin); }
    Quat userOrientation() const { return (q * userRotation).normalized(); }
};

/// A body's simulation state from its definition: mass properties from the shape (or the
/// given mass), diagonalised into the principal frame, and the user pose converted to it.
Body makeBody(const BodyDef& def);

}  // namespace substep

#pragma once
/// A soft particle's contact with a rigid body in one substep (SoftSystem's contacts_, found by
/// soft_contacts.cpp, solved by soft_coupling.cpp and, against still bodies, still_contacts.h).

#include "physics/math.h"

#include <cstdint>

namespace substep {

/// A contact point of this substep: the particle's surface point is x − radius n; the body's
/// is kept in its principal frame (r1); n points from the body to the particle.
struct ParticleContact {
    uint32_t particle = 0;
    uint32_t body = 0;
    Vec3 local1 = Vec3::Zero();
    Vec3 normal = Vec3::UnitY();
    double radius = 0.0;
    double staticFriction = 0.0, dynamicFriction = 0.0, restitution = 0.0;
    double lambdaNormal = 0.0;
    double lambdaTangent = 0.0;
    Vec3 frictionImpulse = Vec3::Zero();  ///< Σ of the static friction's impulses on the particle
    /// The body is still (static: no inverse mass, no velocity now or at the substep's start):
    /// its point is `anchor` (world, b.x + b.q r1 as the solve computes it) all substep, and
    /// its terms of Eqs. 26-30 and 34 are zero, so the solve leaves them out (the same bits).
    bool still = false;
    Vec3 anchor = Vec3::Zero();
};

}  // namespace substep

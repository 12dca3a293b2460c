#pragma once
/// What both contact solves (the one-point path in contact.cpp, the patches in contact_patch.cpp)
/// share: a point's previous position and velocity, the push-out cap, and the thresholds (the
/// soft particles' contacts, still_contacts.h and soft_coupling.cpp, take the thresholds too).
/// Internal to the contact solve.

#include "physics/contact.h"

#include <algorithm>
#include <cmath>

namespace substep::contact_detail {

/// |(a, b)| without std::hypot's care for overflow, which costs more than the solve here.
inline double planarLength(double a, double b) { return std::sqrt(a * a + b * b); }

/// The speed (m/s) at which an overlap that the bodies' motion does not explain is pushed out.
constexpr double kPushOutSpeed = 1.0;

/// Velocity changes below this (m/s) are not worth a patch solve in the velocity pass.
constexpr double kRestingSpeed = 1e-9;

/// Eq. 27: where a body's point was before this substep's integration.
inline Vec3 previousPoint(const Body& b, const Vec3& local) { return b.xPrev + b.qPrev * local; }

/// Velocity of a body's point at world offset r.
inline Vec3 pointVelocity(const Vec3& v, const Vec3& omega, const Vec3& r) { return v + omega.cross(r); }

/// How much of a depth one substep pushes out: all of what the bodies' approach this substep
/// explains (an impact, or gravity's g h² at rest), but an overlap they were created with, or
/// were pressed into by a crowd, only at kPushOutSpeed. Pushed out in one substep, such an
/// overlap becomes a speed of depth / h for every body it shoves into another: four boxes and
/// four spheres created inside one another flew off at 89 m/s at 20 substeps (and twice that at
/// 40). The paper's Fig. 13 case (spheres 40 % into the ground) rises the same either way.
inline double pushOut(double depth, const Body& b0, const Body& b1, const Vec3& r0, const Vec3& r1,
                      const Vec3& n, const SolverContext& ctx) {
    const double h = ctx.h;
    // The cap is never below h kPushOutSpeed: a depth within it (every resting contact, whose
    // depth is about g h²) needs no approach speed.
    if (!(depth > h * kPushOutSpeed) || !ctx.capPushOut) return depth;
    const double approach = -(pointVelocity(b0.v, b0.omega, r0) - pointVelocity(b1.v, b1.omega, r1)).dot(n);
    return std::min(depth, h * std::max(approach, kPushOutSpeed));
}

}  // namespace substep::contact_detail

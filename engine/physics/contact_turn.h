#pragma once
/// The turn of a body by a contact correction (Eq. 8, Eq. 9), as integrateRotation (math.h)
/// makes it, on a shorter chain of dependent operations: a pile's one-point contacts each turn
/// two bodies twice, and the next correction of a body waits for its turn.

#include "physics/math.h"

#include <cmath>

namespace substep {

/// Below this (|θ|/2)² a correction's turn takes turnBy's short path: the series there are
/// exact to rounding (their first terms left out are under 1e-17 of the result).
constexpr double kSmallTurn = 1e-4;
/// turnBy's short path needs |q| = 1 to within this; anything else takes the general path.
constexpr double kUnitDrift = 1e-10;

/// integrateRotation (math.h) for the small turns of contact corrections, with the same result
/// to rounding but a shorter chain of dependent operations, which is what a pile's solve waits
/// on: the exact turn is the unit quaternion (cos h, sin h θ/|θ|), h = |θ|/2, times q, which is
/// integrateRotation's q + ½ (tan h / h) θ q scaled by cos h. Normalising that sum after forming
/// it (a square root and a division after the product) put both on the path from one
/// correction to the next; cos h, a series in h² like the tangent's, is ready when the
/// product is. The factor 1 − δ/2 (δ = |q|² − 1, a few roundings) keeps |q| = 1 as the
/// renormalisation did.
[[gnu::always_inline]] inline void turnBy(Quat& q, const Vec3& rotation) {
    const double half2 = 0.25 * rotation.squaredNorm();  // h²
    const double drift = q.coeffs().squaredNorm() - 1.0;
    if (!(half2 < kSmallTurn) || !(std::abs(drift) < kUnitDrift)) return integrateRotation(q, rotation);
    const double tanScale = 1.0 + half2 * (1.0 / 3.0 + half2 * (2.0 / 15.0 + half2 * (17.0 / 315.0)));
    const double cosine = 1.0 + half2 * (-1.0 / 2.0 + half2 * (1.0 / 24.0 + half2 * (-1.0 / 720.0)));
    const Vec3 turn = rotation * tanScale;
    const Quat dq(0.0, turn.x(), turn.y(), turn.z());
    const Quat product = dq * q;
    q.coeffs() = (q.coeffs() + 0.5 * product.coeffs()) * (cosine * (1.0 - 0.5 * drift));
}

}  // namespace substep

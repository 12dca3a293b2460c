#pragma once
/// Restitution that passes through touching bodies whatever order they are listed in.
///
/// The paper's velocity pass (Eq. 34) gives each contact that pushed the normal velocity −e v̄_n,
/// v̄_n its approach before the substep. When a striker hits a row of touching spheres, one
/// Gauss-Seidel pass of the position solve can carry the push down the whole row within the
/// substep (when the row is listed from the striker on): every contact pushes, but only the
/// first had an approach before the substep, so the others get e = 0 and the row moves off
/// together (1 m/s into three touching spheres left −0.125, 0.27, 0.43, 0.43 m/s instead of
/// 0, 0, 0, 1). Listed the other way the push reaches one sphere per substep and the result
/// was right: the outcome depended on the order.
///
/// Here the collisions themselves are resolved before the velocity pass, on the velocities the
/// bodies had before the substep's derivation (Body::vPrev, omegaPrev): sweeps over the
/// contacts that pushed, each approaching contact taking the two-body impulse (1 + e) a / w
/// (a its approach, w = w0 + w1, Eq. 2 and Eq. 3; e = 0 for a resting approach of at most
/// 2 |g| h, the paper's jitter guard), until none approaches. That is the sequential model of
/// colliding bodies, a chain of two-body collisions, the same for any order of the list. The
/// velocity pass then replaces the impulse a one-point contact's push gave (λ_n / h) by this
/// collision impulse: for a contact alone that is exactly Eq. 34's −e v̄_n; a resting contact's
/// push-out speed is removed as Eq. 34 removes it. Patches of several points keep Eq. 34.
///
/// Collisions closer in time than a substep are taken in the order the sweeps meet them, not in
/// time order (a striker into spheres 1 mm apart at 1 m/s and 20 substeps: the closed form
/// holds for equal masses, within 0.3 m/s for unequal ones; 10 mm gaps: within 5e-3).

#include "physics/body.h"
#include "physics/contact.h"
#include "physics/math.h"

#include <span>
#include <vector>

namespace substep {

/// A body's velocities in the restitution sweeps.
struct BodyVelocity {
    Vec3 v = Vec3::Zero();
    Vec3 omega = Vec3::Zero();
};

/// Sets Contact::restitutionImpulse of every contact that pushed this substep (λ_n > 0) in a
/// pair with restitution: the sum of the impulses it took in the sweeps (0 if it took none).
/// Does nothing (and touches no memory) when no such contact pushed. `scratch` is reused.
void findRestitutionImpulses(std::span<const ContactPair> pairs, std::span<Contact> contacts,
                             const Body* bodies, size_t bodyCount, double h, double gravity,
                             std::vector<BodyVelocity>& scratch);

}  // namespace substep

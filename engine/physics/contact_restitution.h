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
/// one-point contacts with restitution that pushed, each contact approaching faster than
/// resting (2 |g| h, the paper's jitter guard) taking the two-body impulse (1 + e) a / w (a its
/// approach, w = w0 + w1, Eq. 2 and Eq. 3), until none approaches. That is the sequential model
/// of colliding bodies, a chain of two-body collisions, the same for any order of the list.
///
/// In the velocity pass (contact.h) a contact that collided, or that pushed between two bodies
/// a collision reached within the last kCollisionWindow substeps (a push carried through from
/// the collision, or the overlaps one Gauss-Seidel pass leaves in a struck row), has its push's
/// impulse λ_n / h replaced by its collision impulse (none for the latter); these changes add
/// up in any order, so all are made before Eq. 34 sets any other contact's velocity. An
/// approach such a contact is left with (a support under gravity, whose push held it up) is
/// then removed, Eq. 34 with e = 0 (marbles had sunk 1.5 mm into rolling_balls' wires), and
/// one that did not collide separates no faster than its v̄_n (contact.cpp). A contact between a reached body and
/// one no collision reached (a floor, a wall, a neighbour in a pile: a support) keeps Eq. 34,
/// so a settling pile sleeps as under Eq. 34 alone. For a contact alone the collision
/// impulse gives Eq. 34's −e v̄_n. All other contacts, patches of several points, and every
/// substep with no collision in the window keep Eq. 34 exactly, at the cost of one look at the
/// pushing contacts with restitution.
///
/// Collisions closer in time than a substep are taken in the order the sweeps meet them, not in
/// time order (a striker into spheres 1 mm apart at 1 m/s and 20 substeps: the closed form
/// holds for equal masses, within 0.3 m/s for unequal ones; 10 mm gaps: within 5e-3).

#include "physics/body.h"
#include "physics/contact.h"
#include "physics/math.h"

#include <cstdint>
#include <span>
#include <vector>

namespace substep {

class WorkerPool;

/// A body's velocities in the restitution sweeps.
struct BodyVelocity {
    Vec3 v = Vec3::Zero();
    Vec3 omega = Vec3::Zero();
};

/// A pair the sweeps visit, with what their every pass over it reads first: a compact, ordered
/// list rather than the pairs' records (each its own cache line), read up to kMaxSweeps times
/// a substep on one thread.
struct SweepPair {
    uint32_t pair;          ///< index into the pairs
    uint32_t body0;
    uint32_t body1;
    uint32_t pushedBefore;  ///< ContactPair::pushedBefore
};

/// Storage the sweeps reuse from substep to substep (grown, never shrunk: no allocation once a
/// world has settled). A body's entry in `velocities` is valid only while its `stamp` equals
/// the current call's, so a call touches only the bodies a collision reaches.
struct RestitutionScratch {
    std::vector<BodyVelocity> velocities;  ///< per body: its velocities in the sweeps
    std::vector<uint32_t> stamp;           ///< per body: the call that last set its entry
    std::vector<int> changedIn;            ///< per body: the sweep its velocities last changed in
    std::vector<SweepPair> pairs;          ///< the pairs the sweeps visit, in pair order
    std::vector<uint32_t> collidedIn;      ///< per body: the last call a collision reached it in
    /// Per block of a parallel look over the touching pairs: the sweeps' pairs it found, and
    /// whether one of them starts a collision (or, later, takes the collision pass).
    std::vector<std::vector<SweepPair>> blockPairs;
    std::vector<uint8_t> blockFlags;
    uint32_t call = 0;                     ///< this call's stamp
    uint32_t lastCollision = 0;            ///< the last call with a collision (0: none yet)
};

/// Sets Contact::restitutionImpulse of every contact of a one-point pair with restitution that
/// pushed this substep (λ_n > 0) and collided: the sum of its collision impulses; and
/// Contact::collisionPass of those the velocity pass gives their collision impulse (see
/// above). Returns whether any contact takes that pass; when none does (no collision in the
/// window) every contact is left as it was and the velocity pass is exactly the paper's.
/// With a `pool` the looks over every touching pair and every sweeps' pair (which pairs sweep,
/// whether one starts a collision, which take the collision pass) run in blocks on its threads;
/// the sweeps themselves, a chain of collisions in pair order, stay on the calling thread. The
/// results are the same bytes with or without.
bool findRestitutionImpulses(std::span<const uint32_t> touching, std::span<const ContactPair> pairs,
                             std::span<Contact> contacts, const Body* bodies, size_t bodyCount, double h,
                             double gravity, RestitutionScratch& scratch, WorkerPool* pool = nullptr);

}  // namespace substep

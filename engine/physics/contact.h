#pragma once
/// Contacts (paper 3.5-3.6): the narrowphase finds them every substep on the current poses; the
/// position solve keeps them from penetrating and, while static friction holds, from sliding;
/// the velocity pass applies dynamic friction and restitution.
///
/// Convention (the joints'): body 0 is the paper's body 1. The normal points from body 1 towards
/// body 0; the depth d = (p1 − p0)·n is positive while they overlap, and the correction d n is
/// the motion of body 0 relative to body 1, so λ_n ≥ 0 and the normal force is λ_n / h².
///
/// Static friction holds the whole contact patch, not each point on its own. Applied corner by
/// corner (as printed), a correction at one corner turns the box and moves the others, whose
/// ratios λ_t / λ_n then swing between about 0.35 and 1.3: a box with μ_s = 0.6 slid down a 25°
/// incline (ERRATA item 6). Here a pair's points form a patch, solved as one small system: a
/// push along the normal at every point, and at the patch's centre two tangential rows that
/// undo its slip during the substep and one that undoes its turn about the normal. Friction
/// holds while the tangential λ stays within μ_s times the patch's summed normal λ, so the box
/// holds below atan μ_s and slides above it with a = g (sin θ − μ_d cos θ).
///
/// A patch of three or more points is held at anchors kept from first touch rather than at
/// its motion during the substep (Eq. 27): measured per substep, the friction rows of a stack
/// of ten boxes fed one another's corrections back and the stack's sway grew 10⁴-fold a second
/// until it fell; anchored, they act like a joint and the stack stands. Anchors let go when
/// friction gives way. One or two points (a marble, a coin on its rim, a rolling capsule) keep
/// the paper's per-substep form, which lets them roll.

#include "physics/body.h"
#include "physics/collision/contact_manifold.h"
#include "physics/correction.h"
#include "physics/math.h"

#include <cmath>
#include <cstdint>
#include <span>

namespace substep {

/// Most points one pair's patch holds (the narrowphase's limit).
inline constexpr int kMaxPatchPoints = kMaxContactPoints;

/// One contact point of the current substep, in the bodies' principal frames (the paper's r1,
/// r2), with the normal fixed for the substep.
struct Contact {
    Vec3 local0 = Vec3::Zero();  ///< contact point on body 0, principal frame
    Vec3 local1 = Vec3::Zero();  ///< contact point on body 1, principal frame
    Vec3 normal = Vec3::UnitY(); ///< world, from body 1 towards body 0
    double lambdaNormal = 0.0;   ///< this substep's normal multiplier
    uint32_t feature = 0;        ///< the narrowphase's feature id
    /// Whether this substep's velocity pass gives this point (of a one-point pair) its
    /// collision impulse in place of its push's λ_n / h: it collided in the restitution sweeps
    /// or touches a body a collision reached (contact_restitution.h).
    bool collisionPass = false;
    /// The collision impulse (N s, along the normal, on body 0) this point took in the
    /// substep's restitution sweeps (contact_restitution.h); 0 if none.
    double restitutionImpulse = 0.0;
};

/// A pair of bodies that may touch this frame (from the broadphase), with its averaged surface
/// coefficients and this substep's contact points `contacts[first, first + count)`.
struct ContactPair {
    uint32_t body0 = 0;
    uint32_t body1 = 0;
    double staticFriction = 0.0;   ///< μ_s, the average of the two bodies' (paper 3.5)
    double dynamicFriction = 0.0;  ///< μ_d, likewise
    double restitution = 0.0;      ///< e, likewise
    uint32_t first = 0;
    uint32_t count = 0;
    double lambdaTangent1 = 0.0;   ///< the patch's static friction multipliers this substep,
    double lambdaTangent2 = 0.0;   ///< along two tangents of its normal
    double lambdaTwist = 0.0;      ///< the patch's torsional friction multiplier
    double lambdaNormal = 0.0;     ///< Σ λ_n of its points this substep
    /// Whether the pair pushed (Σ λ_n > 0) in the substep before this one: it was touching, so
    /// it starts no collision in the restitution sweeps (contact_restitution.h).
    bool pushedBefore = false;
    /// Whether the anchors below hold the patch. Kept with the fields above, which the
    /// narrowphase and the one-point solve write every substep: together they fill the
    /// pair's first 80 bytes, two cache lines, where `anchored` after the anchors made a third
    /// (a pile streams through thousands of pairs per substep).
    bool anchored = false;

    // Static friction anchors of a patch that spans an area, kept from first touch while it
    // sticks (across substeps and frames): the patch centre on body 0 and the point of body 1
    // it touched, and the bodies' relative orientation then (q0⁻¹ q1).
    Vec3 anchor0 = Vec3::Zero();
    Vec3 anchor1 = Vec3::Zero();
    Quat turnAnchor = Quat::Identity();

    /// Magnitude of the static friction multiplier (the friction force is this / h²).
    double lambdaTangent() const { return std::hypot(lambdaTangent1, lambdaTangent2); }
};

/// Current depth of a contact: (p1 − p0)·n on the bodies' current poses.
double contactDepth(const Contact& contact, const Body& b0, const Body& b1);

/// Position solve of one pair (paper 3.5, Eqs. 26-28): pushes apart every point that
/// penetrates (α = 0) and, solved with the pushes, holds the patch by static friction while
/// λ_t ≤ μ_s Σλ_n.
void solveContactPositions(ContactPair& pair, std::span<Contact> contacts, SolverContext& ctx);

/// Velocity pass of one pair (paper 3.6, Eqs. 29-34): restitution e v̄_n (e = 0 below
/// 2|g|h, the jitter guard) replaces the normal velocity PBD derived, and dynamic friction
/// removes slip with an impulse of at most h μ_d |f_n| (Eq. 30 with ERRATA item 2's units).
/// Only points that pushed this substep (λ_n > 0) take part. A one-point pair's point that
/// took solveCollisionVelocities (Contact::collisionPass) only has an approach left removed
/// (Eq. 34 with e = 0) and, if it did not collide, a separation faster than its v̄_n.
void solveContactVelocities(const ContactPair& pair, std::span<const Contact> contacts,
                            Body* bodies, double h, double gravity);

/// The collision pass of a one-point pair's point (Contact::collisionPass,
/// contact_restitution.h): the push's impulse λ_n / h, which the derivation put into the
/// velocities, is replaced by the collision impulse (0 if it did not collide), then dynamic
/// friction as in solveContactVelocities. These changes add up in any order, so every such
/// point takes this before solveContactVelocities, where Eq. 34 sets velocities.
void solveCollisionVelocities(const ContactPair& pair, const Contact& contact, Body* bodies, double h);

}  // namespace substep

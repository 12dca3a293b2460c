#include "physics/contact_restitution.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace substep {
namespace {

/// Sweeps at most: a row of n touching bodies needs about n (one per collision down the row,
/// fewer when listed in the row's order); a heavy striker's follow-up collisions a few more.
/// Only colliding contacts take part: a pile at rest costs one look at its contacts.
constexpr int kMaxSweeps = 8;
/// Approach speeds at or below this count as resting when there is no gravity (m/s).
constexpr double kRestingApproach = 1e-9;

/// The velocities a body brought into the substep: v̄ for a dynamic body (before the
/// derivation), the current ones for a static or kinematic body (it has no v̄).
BodyVelocity velocityBefore(const Body& body) {
    if (body.invMass == 0.0) return {body.v, body.omega};
    return {body.vPrev, body.rotates() ? body.omegaPrev : Vec3::Zero()};
}

/// Approach speed −(v0(r0) − v1(r1))·n of a contact on the sweep velocities: positive while the
/// bodies move into each other.
double approach(const BodyVelocity& u0, const BodyVelocity& u1, const Vec3& r0, const Vec3& r1,
                const Vec3& n) {
    return -((u0.v + u0.omega.cross(r0)) - (u1.v + u1.omega.cross(r1))).dot(n);
}

/// Whether any contact pushed in a pair with restitution this substep.
bool anyPush(std::span<const ContactPair> pairs, std::span<const Contact> contacts) {
    for (const ContactPair& pair : pairs) {
        if (pair.count == 0 || !(pair.restitution > 0.0)) continue;
        for (uint32_t i = pair.first; i < pair.first + pair.count; ++i)
            if (contacts[i].lambdaNormal > 0.0) return true;
    }
    return false;
}

}  // namespace

void findRestitutionImpulses(std::span<const ContactPair> pairs, std::span<Contact> contacts,
                             const Body* bodies, size_t bodyCount, double h, double gravity,
                             std::vector<BodyVelocity>& scratch) {
    // The paper's jitter guard (Eq. 34's e = 0 below 2 |g| h), and a floor without gravity.
    const double resting = std::max(2.0 * gravity * h, kRestingApproach);
    if (!anyPush(pairs, contacts)) return;
    scratch.resize(bodyCount);
    // The sweep in which each body's velocity last changed: after the first sweep, a pair whose
    // bodies both kept their velocities through the last sweep has nothing new to resolve, so a
    // collision's later sweeps visit only the bodies it reached. Kept across calls (no
    // allocation once grown), per thread so that worlds on different threads do not share it.
    static thread_local std::vector<int> changedIn;
    changedIn.assign(bodyCount, -2);
    for (const ContactPair& pair : pairs) {
        if (pair.count == 0) continue;
        scratch[pair.body0] = velocityBefore(bodies[pair.body0]);
        scratch[pair.body1] = velocityBefore(bodies[pair.body1]);
    }
    // The pairs the sweeps visit: those with restitution whose contacts pushed.
    static thread_local std::vector<uint32_t> pushing;
    pushing.clear();
    for (uint32_t k = 0; k < pairs.size(); ++k) {
        const ContactPair& pair = pairs[k];
        if (pair.count == 0 || !(pair.restitution > 0.0)) continue;
        for (uint32_t i = pair.first; i < pair.first + pair.count; ++i)
            if (contacts[i].lambdaNormal > 0.0) {
                pushing.push_back(k);
                break;
            }
    }
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
        bool collided = false;
        for (const uint32_t k : pushing) {
            const ContactPair& pair = pairs[k];
            if (sweep > 0 && changedIn[pair.body0] < sweep - 1 && changedIn[pair.body1] < sweep - 1)
                continue;
            const Body& b0 = bodies[pair.body0];
            const Body& b1 = bodies[pair.body1];
            BodyVelocity& u0 = scratch[pair.body0];
            BodyVelocity& u1 = scratch[pair.body1];
            for (uint32_t i = pair.first; i < pair.first + pair.count; ++i) {
                Contact& c = contacts[i];
                if (!(c.lambdaNormal > 0.0)) continue;
                const Vec3 r0 = b0.q * c.local0;
                const Vec3 r1 = b1.q * c.local1;
                const double speed = approach(u0, u1, r0, r1, c.normal);
                // Resting contacts (at most 2 |g| h, the paper's jitter guard) keep Eq. 34.
                if (!(speed > resting)) continue;
                const double e = pair.restitution;
                // Eq. 2 and Eq. 3: w = w0 + w1 along the normal; the two-body collision
                // impulse (1 + e) a / w, applied as Eq. 33 applies a velocity change.
                const double w =
                    b0.positionalInverseMass(r0, c.normal) + b1.positionalInverseMass(r1, c.normal);
                if (!(w > 0.0)) continue;
                const double impulse = (1.0 + e) * speed / w;
                const Vec3 p = impulse * c.normal;
                if (b0.invMass > 0.0) {
                    u0.v += p * b0.invMass;
                    if (b0.rotates()) u0.omega += b0.applyInverseInertia(r0.cross(p));
                }
                if (b1.invMass > 0.0) {
                    u1.v -= p * b1.invMass;
                    if (b1.rotates()) u1.omega -= b1.applyInverseInertia(r1.cross(p));
                }
                c.restitutionImpulse += impulse;
                changedIn[pair.body0] = changedIn[pair.body1] = sweep;
                collided = true;
            }
        }
        if (!collided) break;
    }
}

}  // namespace substep

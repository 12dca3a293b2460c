#pragma once
/// Soft particles' contacts with still bodies (ParticleContact::still: the ground and static
/// obstacles): Eqs. 26-28 in the position solve and Eqs. 30 and 34 in the velocity pass with the
/// body's terms left out, so that a contact changes its own particle and nothing else. Consecutive
/// still contacts on distinct particles then change disjoint state, and groups of them are
/// solved side by side, one per lane of a vector (still_contact_lanes.cpp for AVX2's four,
/// still_contact_lanes_wide.cpp for x86-64-v4's eight) with the one-by-one path's operations in
/// its order: the same bits as one after the other (rc_car's tyres hold about 450 contacts
/// with the ground).

#include "physics/math.h"
#include "physics/soft/particle_contact.h"

#include <cstddef>
#include <cstdint>
#include <span>

namespace substep {

/// The speed (m/s) at which an overlap the motion does not explain is pushed out: the rigid
/// contacts' value (contact_kinematics.h), so a particle created sunk into the ground rises gently.
inline constexpr double kParticlePushOutSpeed = 1.0;
/// Below this speed a particle contact's velocity is left alone (contact_kinematics.h's kRestingSpeed).
inline constexpr double kParticleRestingSpeed = 1e-9;

/// The particles' arrays the contacts read and write (SoftSystem's, indexed by particle).
struct ContactParticles {
    Vec3* x = nullptr;
    const Vec3* xPrev = nullptr;
    Vec3* v = nullptr;
    const Vec3* vPrev = nullptr;  ///< the velocity pass's v̄ (Eq. 34)
    const double* invMass = nullptr;
    double* heldImpulse = nullptr;  ///< the elements' push a held particle did not take
};

/// What a substep's contact solve reads besides the contacts and particles.
struct ContactStep {
    double h = 0.0;           ///< the substep (s)
    bool capPushOut = false;  ///< SolverContext::capPushOut
    Vec3 gravityStep = Vec3::Zero();  ///< g h: the position solve's particle velocity is v + g h
    double restingSpeed = 0.0;        ///< 2 |g| h: no bounce below it (Eq. 34)
};

/// How the still contacts are solved (the same bits whichever): one by one; four to an AVX2
/// register where the CPU has AVX2; or as widest pays (eight to an AVX-512 register where
/// wideElementLanes(), element_batch.h, else one by one: four lanes cost more than that).
enum class StillContactLanes { OneByOne, Avx2, Widest };

/// The group size `lanes` selects on this CPU: 8, 4, or 0 for one by one.
int stillContactGroup(StillContactLanes lanes);

/// Whether contacts[0, group) are all still, on distinct particles: a group the lanes take.
/// Contacts come particle by particle (the candidates' order), so rising particles answer
/// without comparing every pair.
inline bool isStillGroup(const ParticleContact* contacts, int group) {
    bool still = true, rising = true;
    for (int i = 0; i < group; ++i) {
        still &= contacts[i].still;
        rising &= i == 0 || contacts[i - 1].particle < contacts[i].particle;
    }
    if (!still) return false;
    if (rising) return true;
    for (int i = 1; i < group; ++i)
        for (int j = 0; j < i; ++j)
            if (contacts[j].particle == contacts[i].particle) return false;
    return true;
}

/// The position solve of one still contact: the particle's held impulse taken into λ_n, then
/// Eq. 26's push-out and Eqs. 27-28's static friction (SoftSystem::solveContactsPerParticle).
void solveStillContactPosition(ParticleContact& c, const ContactParticles& particles, const ContactStep& step);
/// The velocity pass of one still contact: Eq. 34's restitution and, unless `slid` (its patch
/// slid, static friction per patch), Eq. 30's dynamic friction.
void solveStillContactVelocity(const ParticleContact& c, const ContactParticles& particles, const ContactStep& step,
                               bool slid);

/// solveStillContactPosition / solveStillContactVelocity (not slid) of contacts[0, groups
/// group): `groups` consecutive groups (isStillGroup) of `group` = stillContactGroup(...)
/// contacts, each group's side by side.
void solveStillPositionGroups(ParticleContact* contacts, int group, size_t groups, const ContactParticles& particles,
                              const ContactStep& step);
void solveStillVelocityGroups(const ParticleContact* contacts, int group, size_t groups,
                              const ContactParticles& particles, const ContactStep& step);

/// The kernels, compiled for AVX2 (four lanes) and x86-64-v4 (eight); only on a CPU with them.
void solveStillPositionsInLanes(ParticleContact* contacts, size_t groups, const ContactParticles& particles,
                                const ContactStep& step);
void solveStillVelocitiesInLanes(const ParticleContact* contacts, size_t groups, const ContactParticles& particles,
                                 const ContactStep& step);
void solveStillPositionsInWideLanes(ParticleContact* contacts, size_t groups, const ContactParticles& particles,
                                    const ContactStep& step);
void solveStillVelocitiesInWideLanes(const ParticleContact* contacts, size_t groups,
                                     const ContactParticles& particles, const ContactStep& step);

/// The contacts in order, each run of consecutive groups of `group` still contacts on distinct
/// particles (isStillGroup) solved in lanes by `inGroups(first, groups)`, every other contact
/// by `one(index)`: the bits of `one` for every contact, where `inGroups` gives `one`'s bits.
/// (A run goes to the lanes whole: consecutive groups overlap in the processor.)
template <class InGroups, class One>
void forContactGroups(std::span<const ParticleContact> contacts, int group, InGroups&& inGroups, One&& one) {
    const size_t n = contacts.size(), size = static_cast<size_t>(group);
    size_t k = 0;
    while (k < n) {
        size_t groups = 0;
        while (group > 0 && n - k - groups * size >= size && isStillGroup(contacts.data() + k + groups * size, group))
            ++groups;
        if (groups > 0) {
            inGroups(k, groups);
            k += groups * size;
            continue;
        }
        one(k);
        ++k;
    }
}

}  // namespace substep

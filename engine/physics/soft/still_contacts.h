#pragma once
/// Soft particles' contacts with still bodies (ParticleContact::still: the ground and static
/// obstacles): Eqs. 26-28 in the position solve and Eqs. 30 and 34 in the velocity pass with the
/// body's terms left out, so that a contact changes its own particle and nothing else. Consecutive
/// still contacts on distinct particles then change disjoint state, and groups of them are
/// solved side by side, one per lane of a vector (still_contact_lanes.cpp for AVX2's four,
/// still_contact_lanes_wide.cpp for x86-64-v4's eight) with the one-by-one path's operations in
/// its order: the same bits as one after the other (rc_car's tyres hold about 450 contacts
/// with the ground).

#include "physics/contact_kinematics.h"
#include "physics/math.h"
#include "physics/soft/particle_contact.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

namespace substep {

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
    double h = 0.0;                   ///< the substep (s)
    bool capPushOut = false;          ///< SolverContext::capPushOut
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
void solveStillContactPosition(ParticleContact& c, const ContactParticles& particles,
                               const ContactStep& step);
/// The velocity pass of one still contact: Eq. 34's restitution and, unless `slid` (its patch
/// slid, static friction per patch), Eq. 30's dynamic friction.
void solveStillContactVelocity(const ParticleContact& c, const ContactParticles& particles,
                               const ContactStep& step, bool slid);

/// The number of contacts from `contacts` on (at most `most`) that are still, on distinct
/// particles: a run's end that one more group takes.
inline size_t stillPrefix(const ParticleContact* contacts, size_t most) {
    size_t p = 0;
    for (; p < most && contacts[p].still; ++p)
        for (size_t j = 0; j < p; ++j)
            if (contacts[j].particle == contacts[p].particle) return p;
    return p;
}

/// A run's end this short goes one by one (a group costs about as much as three contacts one
/// by one).
inline constexpr size_t kShortestGroup = 3;

/// solveStillContactPosition / solveStillContactVelocity (not slid) of contacts[0, count), in
/// groups of `group` = stillContactGroup(...) side by side, the last one maybe shorter: each
/// group (its first `group` contacts and the rest) still on distinct particles (isStillGroup).
void solveStillPositionGroups(ParticleContact* contacts, int group, size_t count,
                              const ContactParticles& particles, const ContactStep& step);
void solveStillVelocityGroups(const ParticleContact* contacts, int group, size_t count,
                              const ContactParticles& particles, const ContactStep& step);

/// The kernels, compiled for AVX2 (four lanes) and x86-64-v4 (eight); only on a CPU with them.
void solveStillPositionsInLanes(ParticleContact* contacts, size_t count,
                                const ContactParticles& particles, const ContactStep& step);
void solveStillVelocitiesInLanes(const ParticleContact* contacts, size_t count,
                                 const ContactParticles& particles, const ContactStep& step);
void solveStillPositionsInWideLanes(ParticleContact* contacts, size_t count,
                                    const ContactParticles& particles, const ContactStep& step);
void solveStillVelocitiesInWideLanes(const ParticleContact* contacts, size_t count,
                                     const ContactParticles& particles, const ContactStep& step);

/// The contacts in order, each run of consecutive groups of `group` still contacts on distinct
/// particles (isStillGroup), and its end where kShortestGroup or more of them, solved in lanes
/// by `inLanes(first, count)`, every other contact by `one(index)`: the bits of `one` for every
/// contact, where `inLanes` gives `one`'s bits. (A run goes to the lanes whole: consecutive
/// groups overlap in the processor.)
template <class InLanes, class One>
void forContactGroups(std::span<const ParticleContact> contacts, int group, InLanes&& inLanes,
                      One&& one) {
    const size_t n = contacts.size(), size = static_cast<size_t>(group);
    size_t k = 0;
    while (k < n) {
        size_t run = 0;
        if (group > 0) {
            while (n - k - run >= size && isStillGroup(contacts.data() + k + run, group))
                run += size;
            const size_t end =
                stillPrefix(contacts.data() + k + run, std::min(size - 1, n - k - run));
            if (end >= kShortestGroup) run += end;
        }
        if (run > 0) {
            inLanes(k, run);
            k += run;
            continue;
        }
        one(k);
        ++k;
    }
}

}  // namespace substep

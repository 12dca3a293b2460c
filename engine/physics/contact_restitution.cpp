#include "physics/contact_restitution.h"

// Only a pair that did not push in the substep before (ContactPair::pushedBefore: it was
// apart) starts a collision; one that was touching collides only once a collision of this
// substep's sweeps has reached one of its bodies. A touching pair's own approach is a pile
// settling, which Eq. 34 damps: when every such approach faster than 2 |g| h collided, and
// the bodies it reached lost their pushes for the window, spheres1000 never came to rest
// (kinetic energy 0.65-1.3 J from 4 s to 10 s, where Eq. 34 alone leaves 0.04-0.38 J; 100-170
// touching contacts approaching faster than 2 |g| h a substep against 0.1-0.5). A substep in
// which no pair starts a collision and the window is closed costs one test of two flags per
// touching pair.

#include "physics/worker_pool.h"

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
/// Substeps after a collision during which the pushes between the bodies it reached are still
/// replaced: one Gauss-Seidel pass leaves a struck row overlapping (a quarter of the push
/// between the first two of three), and the next substeps' pushes out of those overlaps,
/// carried down the row, would hand momentum on as Eq. 34 sets each pair's velocity (a row of
/// three struck at 1 m/s ended at −0.02, 0.01, 0.01, 1). The overlaps shrink substep by
/// substep; eight substeps still left 7.5e-3 m/s in a row of six, sixteen leave < 1e-3.
constexpr uint32_t kCollisionWindow = 16;
/// Below this many pairs a look over them runs on the calling thread alone; a parallel look's
/// blocks hold at least kMinLookBlock pairs (a pair's look costs a few nanoseconds).
constexpr size_t kMinParallelLook = 512;
constexpr size_t kMinLookBlock = 128;

/// Runs look(block, first, last) over [0, count) in blocks on the pool, each block's results in
/// scratch.blockPairs[block] and scratch.blockFlags[block]; returns the number of blocks.
template <class Look>
size_t lookInBlocks(WorkerPool& pool, size_t count, RestitutionScratch& scratch, const Look& look) {
    const auto blocks = static_cast<size_t>(pool.blocksFor(count, kMinLookBlock));
    if (scratch.blockPairs.size() < blocks) scratch.blockPairs.resize(blocks);
    scratch.blockFlags.assign(blocks, 0);
    pool.parallelFor(static_cast<int>(blocks), [&](int block) {
        const auto b = static_cast<size_t>(block);
        look(b, count * b / blocks, count * (b + 1) / blocks);
    });
    return blocks;
}

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

/// A one-point pair with restitution whose point pushed this substep: the sweeps' pairs.
/// Patches keep Eq. 34 (contact.h), so their pushes take no part.
inline bool sweeps(const ContactPair& pair, std::span<const Contact> contacts) {
    return pair.count == 1 && pair.restitution > 0.0 && contacts[pair.first].lambdaNormal > 0.0;
}

/// A pair of the sweeps that did not push in the substep before: only such a pair's approach
/// starts a collision.
inline bool starts(const ContactPair& pair, std::span<const Contact> contacts) {
    return !pair.pushedBefore && sweeps(pair, contacts);
}

inline SweepPair sweepPair(uint32_t index, const ContactPair& pair) {
    return {index, pair.body0, pair.body1, pair.pushedBefore ? 1u : 0u};
}

}  // namespace

bool findRestitutionImpulses(std::span<const uint32_t> touching, std::span<const ContactPair> pairs,
                             std::span<Contact> contacts, const Body* bodies, size_t bodyCount, double h,
                             double gravity, RestitutionScratch& scratch, WorkerPool* pool) {
    // The paper's jitter guard (Eq. 34's e = 0 below 2 |g| h), and a floor without gravity.
    const double resting = std::max(2.0 * gravity * h, kRestingApproach);
    if (scratch.stamp.size() < bodyCount) {
        scratch.velocities.resize(bodyCount);
        scratch.stamp.resize(bodyCount, 0);
        scratch.changedIn.resize(bodyCount, 0);
        scratch.collidedIn.resize(bodyCount, 0);
    }
    // A new stamp invalidates every body's entry at once; on wrapping round, clear them.
    if (++scratch.call == 0) {
        std::fill(scratch.stamp.begin(), scratch.stamp.end(), 0);
        std::fill(scratch.collidedIn.begin(), scratch.collidedIn.end(), 0);
        scratch.lastCollision = 0;
        scratch.call = 1;
    }
    const uint32_t call = scratch.call;
    const bool windowOpen = scratch.lastCollision != 0 && call - scratch.lastCollision < kCollisionWindow;
    // The look every substep takes: does a collision start? Only a pair that did not push in
    // the substep before can start one (starts()), so a pile at rest, every pair of which
    // pushed, costs a test of two flags per touching pair.
    const auto startsNow = [&](const ContactPair& pair) {
        if (!starts(pair, contacts)) return false;
        const Body& b0 = bodies[pair.body0];
        const Body& b1 = bodies[pair.body1];
        const Contact& c = contacts[pair.first];
        return approach(velocityBefore(b0), velocityBefore(b1), b0.q * c.local0, b1.q * c.local1, c.normal) > resting;
    };
    std::vector<SweepPair>& visited = scratch.pairs;
    visited.clear();
    bool starting = false;
    const bool parallel = pool != nullptr && pool->threads() > 1 && touching.size() >= kMinParallelLook;
    if (parallel) {
        // The same look as below over every touching pair, in blocks: each block lists its
        // sweeps' pairs in order and notes whether one starts a collision (it reads pairs,
        // contacts and bodies and writes its own list and flag alone); the lists are joined in
        // block order, the serial `visited`. The serial look stops at the first pair that starts
        // one when the window is closed; that changes how much is looked at, not what is found.
        const size_t blocks = lookInBlocks(*pool, touching.size(), scratch, [&](size_t block, size_t first, size_t last) {
            std::vector<SweepPair>& list = scratch.blockPairs[block];
            list.clear();
            bool starts = false;
            for (size_t i = first; i < last; ++i) {
                const ContactPair& pair = pairs[touching[i]];
                if (!sweeps(pair, contacts)) continue;
                list.push_back(sweepPair(touching[i], pair));
                starts = starts || startsNow(pair);
            }
            scratch.blockFlags[block] = starts ? 1 : 0;
        });
        for (size_t block = 0; block < blocks; ++block) starting = starting || scratch.blockFlags[block] != 0;
        if (!starting && !windowOpen) return false;
        for (size_t block = 0; block < blocks; ++block)
            visited.insert(visited.end(), scratch.blockPairs[block].begin(), scratch.blockPairs[block].end());
    } else if (windowOpen) {
        // The sweeps' pairs are needed whatever happens: one pass lists them and looks.
        for (const uint32_t k : touching) {
            const ContactPair& pair = pairs[k];
            if (!sweeps(pair, contacts)) continue;
            visited.push_back(sweepPair(k, pair));
            starting = starting || startsNow(pair);
        }
    } else {
        for (const uint32_t k : touching)
            if (startsNow(pairs[k])) {
                starting = true;
                break;
            }
        if (!starting) return false;
        for (const uint32_t k : touching)
            if (sweeps(pairs[k], contacts)) visited.push_back(sweepPair(k, pairs[k]));
    }

    BodyVelocity* velocities = scratch.velocities.data();
    uint32_t* stamp = scratch.stamp.data();
    int* changedIn = scratch.changedIn.data();
    // A body's sweep velocities: its entry once a collision changed them, else what it
    // brought into the substep.
    const auto velocity = [&](uint32_t body) {
        return stamp[body] == call ? velocities[body] : velocityBefore(bodies[body]);
    };
    const auto reachedNow = [&](uint32_t body) { return stamp[body] == call; };
    bool collidedAny = false;
    for (int sweep = 0; starting && sweep < kMaxSweeps; ++sweep) {
        bool collided = false;
        for (const SweepPair& k : visited) {
            // The first sweep looks at every pair that pushed; the later ones only at the pairs
            // a body of which changed in the sweep before.
            if (sweep > 0 && !(reachedNow(k.body0) && changedIn[k.body0] >= sweep - 1) &&
                !(reachedNow(k.body1) && changedIn[k.body1] >= sweep - 1))
                continue;
            // A pair that was already touching collides only once a collision has reached one
            // of its bodies: its own approach is a pile's settling, left to Eq. 34.
            if (k.pushedBefore && !reachedNow(k.body0) && !reachedNow(k.body1)) continue;
            const ContactPair& pair = pairs[k.pair];
            const Body& b0 = bodies[pair.body0];
            const Body& b1 = bodies[pair.body1];
            Contact& c = contacts[pair.first];
            const BodyVelocity u0 = velocity(pair.body0);
            const BodyVelocity u1 = velocity(pair.body1);
            const Vec3 r0 = b0.q * c.local0;
            const Vec3 r1 = b1.q * c.local1;
            const double speed = approach(u0, u1, r0, r1, c.normal);
            // Resting contacts (at most 2 |g| h, the paper's jitter guard) keep Eq. 34.
            if (!(speed > resting)) continue;
            // Eq. 2 and Eq. 3: w = w0 + w1 along the normal; the two-body collision impulse
            // (1 + e) a / w, applied as Eq. 33 applies a velocity change.
            const double w = b0.positionalInverseMass(r0, c.normal) + b1.positionalInverseMass(r1, c.normal);
            if (!(w > 0.0)) continue;
            const double impulse = (1.0 + pair.restitution) * speed / w;
            const Vec3 p = impulse * c.normal;
            if (b0.invMass > 0.0) {
                BodyVelocity& v0 = velocities[pair.body0];
                v0 = u0;
                v0.v += p * b0.invMass;
                if (b0.rotates()) v0.omega += b0.applyInverseInertia(r0.cross(p));
                stamp[pair.body0] = call;
                changedIn[pair.body0] = sweep;
            }
            if (b1.invMass > 0.0) {
                BodyVelocity& v1 = velocities[pair.body1];
                v1 = u1;
                v1.v -= p * b1.invMass;
                if (b1.rotates()) v1.omega -= b1.applyInverseInertia(r1.cross(p));
                stamp[pair.body1] = call;
                changedIn[pair.body1] = sweep;
            }
            c.restitutionImpulse += impulse;
            collided = true;
        }
        collidedAny = collidedAny || collided;
        if (!collided) break;
        if (sweep == kMaxSweeps - 1) {
            // Still colliding after the last sweep: a crowd (a pile, where every body touches
            // several others), not a chain. Two-body collisions taken one after another do not
            // settle there, and their impulses left it shaking (spheres1000: 1650 collisions a
            // substep, five times the paper's rule's, and 70 % more time). It keeps Eq. 34.
            for (const SweepPair& k : visited) contacts[pairs[k.pair].first].restitutionImpulse = 0.0;
            return false;
        }
    }
    // With no collision now nor in the window, the velocity pass is the paper's (Eq. 34).
    if (collidedAny) scratch.lastCollision = call;
    if (scratch.lastCollision == 0 || call - scratch.lastCollision >= kCollisionWindow) return false;
    uint32_t* collidedIn = scratch.collidedIn.data();
    if (collidedAny)
        for (const SweepPair& k : visited) {
            for (const uint32_t body : {k.body0, k.body1})
                if (stamp[body] == call) collidedIn[body] = call;
        }
    // The points whose push the velocity pass replaces: those that collided, and those between
    // two bodies a collision reached within the window (a push carried through from a
    // collision, or the overlap a collision left in a row: that velocity is not the bodies'
    // own). A point between a reached body and one no collision reached (a static floor or
    // wall, or a neighbour in a pile) keeps Eq. 34: its push is a support, and replacing it
    // with nothing, the approach then removed in one Gauss-Seidel pass, let a reached ball in
    // a pile sag off its supports by up to 0.14 m/s over eight substeps, hit the floor below,
    // reach it again, and keep spheres1000 awake (the window open in 40-100 % of the substeps).
    const auto reached = [&](uint32_t body) {
        return collidedIn[body] != 0 && call - collidedIn[body] < kCollisionWindow;
    };
    // Each pair sets its own contact's flag from collidedIn, which no pair writes here: in
    // blocks with a pool, any order gives the same flags.
    const auto markPasses = [&](size_t first, size_t last) {
        bool any = false;
        for (size_t i = first; i < last; ++i) {
            const SweepPair& k = visited[i];
            Contact& c = contacts[pairs[k.pair].first];
            c.collisionPass = c.restitutionImpulse > 0.0 || (reached(k.body0) && reached(k.body1));
            any = any || c.collisionPass;
        }
        return any;
    };
    if (!parallel || visited.size() < kMinParallelLook) return markPasses(0, visited.size());
    const size_t blocks = lookInBlocks(*pool, visited.size(), scratch, [&](size_t block, size_t first, size_t last) {
        scratch.blockFlags[block] = markPasses(first, last) ? 1 : 0;
    });
    bool any = false;
    for (size_t block = 0; block < blocks; ++block) any = any || scratch.blockFlags[block] != 0;
    return any;
}

}  // namespace substep

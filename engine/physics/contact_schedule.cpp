#include "physics/contact_schedule.h"

#include "physics/contact_lanes.h"

#include <algorithm>

namespace substep {

using contact_detail::kContactLanes;

void ContactSchedule::plan(std::span<const uint32_t> touching, std::span<const ContactPair> pairs,
                           std::span<const Body> bodies) {
    // A pair's partners come from the next kWindow − 1 pairs: wider finds fuller steps but looks
    // at more pairs per step. spheres1000's steps hold 3.95 pairs at 32 (96 % of them full)
    // against 2.89 at 8, and its solve and velocity pass take a fifth less time; 48 gained
    // nothing more (docs/PERFORMANCE_LOG.md).
    constexpr size_t kWindow = 32;
    static_assert(kWindow <= 32, "`early` holds a bit per pair of the window");
    // Each pair's moving bodies, read once: the window below looks at every pair up to
    // kWindow − 1 times, and a body's record is a scattered 608 bytes. (Read per pair, not once
    // per body into an array: a settled pile whose bodies nearly all sleep has few touching
    // pairs, and a pass over every body each substep cost it a fifth of its frame.)
    constexpr uint32_t kStill = ~0u;  // a static or kinematic body, which the step may share
    const bool sameList = std::ranges::equal(touching, touching_);
    next_.resize(touching.size());
    for (size_t k = 0; k < touching.size(); ++k) {
        const ContactPair& pair = pairs[touching[k]];
        const auto moving = [&](uint32_t body) { return bodies[body].invMass != 0.0 ? body : kStill; };
        next_[k] = {moving(pair.body0), moving(pair.body1), pair.count == 1 ? 1u : 0u};
    }
    // The steps are a function of the listed pairs and their candidates alone. A pile's touching
    // pairs mostly stay from one substep to the next, and the look below is most of the plan.
    if (sameList && next_ == candidates_) return;
    candidates_.swap(next_);
    touching_.assign(touching.begin(), touching.end());
    // At most a count and an index per pair. Grown only: shrunk to the steps' length, the vector
    // would zero its tail again at every substep.
    if (steps_.size() < 2 * touching.size()) steps_.resize(2 * touching.size());
    // A body is blocked for the step being filled when its mark is the step's: one look per
    // body, where a list of the step's blocked bodies took up to 2 kWindow compares. The marks
    // carry over from plan to plan (mark_ only grows), so they are cleared only when it wraps.
    if (blockedMark_.size() < bodies.size()) blockedMark_.resize(bodies.size(), 0);
    // Locals, not members, in the loop: its stores to the marks and steps could otherwise alias
    // them, and they would be read again at every look.
    uint32_t* const marks = blockedMark_.data();
    uint32_t* const steps = steps_.data();
    const Candidate* const candidates = candidates_.data();
    uint32_t mark = mark_;
    const auto block = [&](const Candidate& c) {
        if (c.moving0 != kStill) marks[c.moving0] = mark;
        if (c.moving1 != kStill) marks[c.moving1] = mark;
    };
    const auto isBlocked = [&](uint32_t body) { return body != kStill && marks[body] == mark; };
    size_t written = 0;
    uint32_t early = 0;  // bit i: touching[k + i] already has its step
    for (size_t k = 0; k < touching.size(); ++k, early >>= 1) {
        if (early & 1u) continue;
        const size_t step = written;
        steps[written++] = 1;
        steps[written++] = touching[k];
        if (!candidates[k].onePoint) continue;
        // The moving bodies a partner must not touch: the step's and those of the pairs it passes.
        if (++mark == 0) {  // the marks wrapped: none may look current
            std::fill(blockedMark_.begin(), blockedMark_.end(), 0u);
            mark = 1;
        }
        block(candidates[k]);
        const size_t window = std::min(kWindow, touching.size() - k);
        uint32_t taken = 1;
        for (size_t i = 1; i < window && taken < kContactLanes; ++i) {
            if (early >> i & 1u) continue;
            const Candidate& candidate = candidates[k + i];
            if (candidate.onePoint && !isBlocked(candidate.moving0) && !isBlocked(candidate.moving1)) {
                steps[written++] = touching[k + i];
                ++taken;
                early |= 1u << i;
            }
            block(candidate);
        }
        steps[step] = taken;
    }
    mark_ = mark;
    stepsLength_ = written;
}

namespace {

/// Calls take(members, count) for every step of `steps`.
template <class Take>
void forEachStep(std::span<const uint32_t> steps, const Take& take) {
    for (size_t s = 0; s < steps.size(); s += 1 + steps[s]) take(&steps[s + 1], steps[s]);
}

void solvePositionsAlone(ContactPair& pair, std::span<Contact> contacts, SolverContext& ctx) {
    solveContactPositions(pair, contacts.subspan(pair.first, pair.count), ctx);
}

void solveVelocitiesAlone(const ContactPair& pair, std::span<const Contact> contacts, Body* bodies, double h,
                          double gravity) {
    solveContactVelocities(pair, contacts.subspan(pair.first, pair.count), bodies, h, gravity);
}

/// One step of the velocity pass: its pairs in lanes, but a point in the collision pass (its
/// removeApproach is not in the lanes) and a pair left alone are solved alone. They share no
/// moving body with the rest of the step, so any order within it gives the same bytes.
void solveVelocityStep(const ContactPair* const* step, int count, std::span<const Contact> contacts, Body* bodies,
                       double h, double gravity) {
    const ContactPair* lanes[kContactLanes];
    int inLanes = 0;
    for (int i = 0; i < count; ++i) {
        if (count > 1 && !contacts[step[i]->first].collisionPass)
            lanes[inLanes++] = step[i];
        else
            solveVelocitiesAlone(*step[i], contacts, bodies, h, gravity);
    }
    if (inLanes == 1) solveVelocitiesAlone(*lanes[0], contacts, bodies, h, gravity);
    if (inLanes > 1) contact_detail::solveOnePointVelocitiesInLanes(lanes, inLanes, contacts, bodies, h, gravity);
}

}  // namespace

void solveTouchingPositions(const ContactSchedule& schedule, std::span<ContactPair> pairs,
                            std::span<Contact> contacts, SolverContext& ctx) {
    if (ctx.solver != SolverType::GaussSeidel) {
        for (const uint32_t p : schedule.touching()) solvePositionsAlone(pairs[p], contacts, ctx);
        return;
    }
    forEachStep(schedule.steps(), [&](const uint32_t* members, uint32_t count) {
        if (count == 1) return solvePositionsAlone(pairs[members[0]], contacts, ctx);
        ContactPair* step[kContactLanes];
        for (uint32_t i = 0; i < count; ++i) step[i] = &pairs[members[i]];
        contact_detail::solveOnePointPositionsInLanes(step, static_cast<int>(count), contacts, ctx);
    });
}

void solveTouchingVelocities(const ContactSchedule& schedule, std::span<const ContactPair> pairs,
                             std::span<const Contact> contacts, Body* bodies, double h, double gravity) {
    forEachStep(schedule.steps(), [&](const uint32_t* members, uint32_t count) {
        const ContactPair* step[kContactLanes];
        for (uint32_t i = 0; i < count; ++i) step[i] = &pairs[members[i]];
        solveVelocityStep(step, static_cast<int>(count), contacts, bodies, h, gravity);
    });
}

void solveIndependentPositions(std::span<const uint32_t> independent, std::span<ContactPair> pairs,
                               std::span<Contact> contacts, SolverContext& ctx) {
    if (ctx.solver != SolverType::GaussSeidel) {
        for (const uint32_t p : independent) solvePositionsAlone(pairs[p], contacts, ctx);
        return;
    }
    ContactPair* step[kContactLanes];
    int count = 0;
    const auto solveStep = [&] {
        if (count == 1) solvePositionsAlone(*step[0], contacts, ctx);
        if (count > 1) contact_detail::solveOnePointPositionsInLanes(step, count, contacts, ctx);
        count = 0;
    };
    for (const uint32_t p : independent) {
        ContactPair& pair = pairs[p];
        if (pair.count != 1) {
            solvePositionsAlone(pair, contacts, ctx);
            continue;
        }
        step[count++] = &pair;
        if (count == kContactLanes) solveStep();
    }
    solveStep();
}

void solveIndependentVelocities(std::span<const uint32_t> independent, std::span<const ContactPair> pairs,
                                std::span<const Contact> contacts, Body* bodies, double h, double gravity) {
    const ContactPair* step[kContactLanes];
    int count = 0;
    for (const uint32_t p : independent) {
        const ContactPair& pair = pairs[p];
        if (pair.count != 1) {
            solveVelocitiesAlone(pair, contacts, bodies, h, gravity);
            continue;
        }
        step[count++] = &pair;
        if (count == kContactLanes) {
            solveVelocityStep(step, count, contacts, bodies, h, gravity);
            count = 0;
        }
    }
    solveVelocityStep(step, count, contacts, bodies, h, gravity);
}

}  // namespace substep

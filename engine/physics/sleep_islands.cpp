#include "physics/sleep_islands.h"

#include "physics/collision/shape_bounds.h"

#include <algorithm>
#include <limits>

namespace substep {
namespace {

constexpr uint32_t kNoBody = std::numeric_limits<uint32_t>::max();

/// Whether a joint keeps its bodies moving by itself: a hinge motor turning at a set rate
/// advances its target every substep, so bodies held still by it are loaded, not at rest.
bool drivesMotion(const Joint& joint) {
    if (joint.type() != JointType::Hinge) return false;
    const HingeJoint& hinge = joint.hinge();
    return hinge.drive == JointDrive::Velocity && hinge.targetVelocity != 0.0;
}

/// Bodies a ball must touch to count as held in place (heldBall).
constexpr uint32_t kHeldContacts = 3;

/// Whether a body is a ball held by `touches` bodies (contacts this frame): then it cannot turn
/// without slipping at one of them while they stand still. A ball turning in place about its
/// centre keeps every contact point where it is only if the turning axis passes through them,
/// and the axis meets the ball at two points; with three contacts at least one slips, and
/// dynamic friction (Eq. 30) opposes the slip. What turning remains is the solve's own
/// residue (spheres1000: 500 of 1000 balls turning in their pockets at 0.05-1 rad/s, 15 to 90 s
/// after the drop, their centres still), not a motion: such a ball rests on the speed of its
/// surface, which turning in place leaves still. Rolling (one contact, or two: a groove, a pair of
/// rails) keeps the turning rate test.
bool heldBall(const Body& body, uint32_t touches) {
    return body.shape.type == ShapeType::Sphere && touches >= kHeldContacts;
}

}  // namespace

void SleepIslands::resize(size_t bodies) {
    if (bodies <= asleep_.size()) return;
    restTime_.resize(bodies, 0.0);
    asleep_.resize(bodies, 0);
    moved_.resize(bodies, 0);
    const size_t old = nextInIsland_.size();
    nextInIsland_.resize(bodies);
    for (size_t i = old; i < bodies; ++i) nextInIsland_[i] = static_cast<uint32_t>(i);
}

void SleepIslands::wake(uint32_t index, const Body& body) {
    resize(index + 1);
    if (body.isDynamic()) {
        if (asleep_[index]) wakeIsland(index);
        restTime_[index] = 0.0;
    } else {
        moved_[index] = 1;
        anyMoved_ = true;
    }
}

void SleepIslands::wakeAll() {
    for (uint32_t i = 0; i < asleep_.size(); ++i) {
        if (asleep_[i]) wakeIsland(i);
        restTime_[i] = 0.0;
    }
}

void SleepIslands::wakeIsland(uint32_t index) {
    // Walks the island's circular list, dissolving it: every body awake, its rest restarted.
    ++changes_;
    uint32_t body = index;
    do {
        const uint32_t next = nextInIsland_[body];
        asleep_[body] = 0;
        restTime_[body] = 0.0;
        nextInIsland_[body] = body;
        --sleeping_;
        body = next;
    } while (body != index);
}

void SleepIslands::wakeLinked(std::span<const Body> bodies, std::span<const ContactPair> pairs,
                              std::span<const Joint> joints) {
    resize(bodies.size());
    const auto awake = [&](uint32_t i) {
        const Body& b = bodies[i];
        if (b.isDynamic()) return asleep_[i] == 0;
        return moved_[i] != 0 || !b.v.isZero(0.0) || !b.omega.isZero(0.0);
    };
    // A woken island's bodies are awake in their turn, so the passes repeat until none wakes
    // (a chain of islands a falling body will push through wakes link by link).
    bool changed = sleeping_ > 0;
    while (changed && sleeping_ > 0) {
        changed = false;
        const auto link = [&](uint32_t a, uint32_t b) {
            if (asleep_[a] && awake(b)) wakeIsland(a), changed = true;
            if (asleep_[b] && awake(a)) wakeIsland(b), changed = true;
        };
        for (const ContactPair& pair : pairs) link(pair.body0, pair.body1);
        for (const Joint& joint : joints)
            if (joint.alive) link(joint.body0, joint.body1);
    }
    if (anyMoved_) {
        std::fill(moved_.begin(), moved_.end(), uint8_t{0});
        anyMoved_ = false;
    }
}

uint32_t SleepIslands::find(uint32_t index) {
    // Path halving: every other node on the way points to its grandparent.
    while (parent_[index] != index) {
        parent_[index] = parent_[parent_[index]];
        index = parent_[index];
    }
    return index;
}

void SleepIslands::update(std::span<Body> bodies, std::span<const BodyPair> touching,
                          std::span<const Joint> joints, double dt, const SleepSettings& settings) {
    const size_t n = bodies.size();
    resize(n);
    parent_.resize(n);
    const auto simulated = [&](uint32_t i) { return bodies[i].isDynamic() && asleep_[i] == 0; };

    // Bodies each body touched this frame (static ones too). islandLast_ holds the counts until
    // the islands are linked below, which refills it.
    std::vector<uint32_t>& touches = islandLast_;
    touches.assign(n, 0);
    for (const BodyPair& pair : touching) {
        ++touches[pair.body0];
        ++touches[pair.body1];
    }

    // Rest time: the fastest point of the shape, and the turning rate, both below threshold.
    for (uint32_t i = 0; i < n; ++i) {
        parent_[i] = i;
        if (!simulated(i)) continue;
        const Body& b = bodies[i];
        const double turning = b.rotates() ? b.omega.norm() : 0.0;
        bool resting;
        if (heldBall(b, touches[i])) {
            // Turning about the centre of mass moves the ball's surface only as far as its
            // centre is off that point (|userOrigin|): its rest is its surface's speed alone.
            resting = b.v.norm() + turning * b.userOrigin.norm() < settings.speed;
        } else {
            const double reach = b.userOrigin.norm() + shapeReach(b.shape);
            resting = b.v.norm() + turning * reach < settings.speed && turning < settings.angularSpeed;
        }
        restTime_[i] = resting ? restTime_[i] + dt : 0.0;
    }

    // Islands: joints and touching pairs between simulated bodies; static bodies link nothing.
    const auto unite = [&](uint32_t a, uint32_t b) {
        if (!simulated(a) || !simulated(b)) return;
        const uint32_t ra = find(a);
        const uint32_t rb = find(b);
        if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
    };
    for (const Joint& joint : joints) {
        if (!joint.alive) continue;
        if (drivesMotion(joint)) {
            if (simulated(joint.body0)) restTime_[joint.body0] = 0.0;
            if (simulated(joint.body1)) restTime_[joint.body1] = 0.0;
        }
        unite(joint.body0, joint.body1);
    }
    for (const BodyPair& pair : touching) unite(pair.body0, pair.body1);

    // An island sleeps when its least rested body has rested long enough.
    islandRest_.assign(n, std::numeric_limits<double>::infinity());
    for (uint32_t i = 0; i < n; ++i)
        if (simulated(i)) {
            const uint32_t root = find(i);
            islandRest_[root] = std::min(islandRest_[root], restTime_[i]);
        }
    islandLast_.assign(n, kNoBody);
    for (uint32_t i = 0; i < n; ++i) {
        if (!simulated(i) || !(islandRest_[find(i)] >= settings.time)) continue;
        const uint32_t root = find(i);
        // Linked into the island's circular list after the body linked last.
        if (islandLast_[root] != kNoBody) {
            nextInIsland_[i] = nextInIsland_[islandLast_[root]];
            nextInIsland_[islandLast_[root]] = i;
        } else {
            nextInIsland_[i] = i;
        }
        islandLast_[root] = i;
        Body& b = bodies[i];
        b.v.setZero();
        b.omega.setZero();
        b.vPrev.setZero();
        b.omegaPrev.setZero();
        b.xPrev = b.x;
        b.qPrev = b.q;
        asleep_[i] = 1;
        ++sleeping_;
        ++changes_;
    }
}

}  // namespace substep

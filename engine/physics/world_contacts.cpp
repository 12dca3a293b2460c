/// The world's contact finding, once per frame and once per substep: the broadphase's candidate
/// pairs filtered into contact pairs that keep last frame's friction anchors, the lists of awake
/// bodies and pairs while some sleep, and the narrowphase's points (serial or in chunks of
/// pairs on the worker pool, joined in the serial order).

#include "physics/world.h"

#include "physics/step_cancellation.h"

#include "physics/constraint_colouring.h"
#include "physics/collision/narrowphase.h"
#include "physics/collision/shape_bounds.h"
#include "physics/contact_spheres.h"
#include "physics/worker_pool.h"

#include <algorithm>
#include <cmath>

namespace substep {
namespace {

/// Below twice this many pairs the narrowphase runs on the calling thread alone; the cancellation
/// flag is asked every this many pairs.
constexpr size_t kPairsPerChunk = 64;

/// The points of a pair other than two spheres, appended to `out` in the bodies' frames;
/// returns their count: a sphere on a plane or a box by the fast path, any other pair by the
/// dispatch table. Out of line, so that the loop over a pile's pairs (spheres on spheres, most
/// of them apart) keeps its own values in registers (a function with clones is not inlined).
[[gnu::target_clones("avx2", "default")]] int appendOtherPairContacts(
    const Body& b0, const Pose& pose0, const Body& b1, const Pose& pose1, double margin,
    ContactManifold& manifold, std::vector<Contact>& out) {
    const int spherePoints = appendSpherePairContacts(b0, pose0, b1, pose1, margin, out);
    if (spherePoints >= 0) return spherePoints;
    // The general path's poses, a sphere's with the orientation the pose loop left out.
    const auto fullPose = [](const Body& body, const Pose& pose) {
        return body.shape.type == ShapeType::Sphere ? Pose{pose.position, body.userOrientation()}
                                                    : pose;
    };
    collide(b0.shape, fullPose(b0, pose0), b1.shape, fullPose(b1, pose1), margin, manifold);
    // Paper 3.5: the points are kept in the bodies' frames (r1, r2), so the position solve
    // measures the depth on the poses as other corrections leave them.
    for (int i = 0; i < manifold.count; ++i) {
        const ContactPoint& point = manifold.points[i];
        appendContactInBodyFrames(b0, b1, point.point0, point.point1, point.normal, out,
                                  point.feature);
    }
    return manifold.count;
}

/// Whether two spheres can come within `margin` of each other during the frame, from their
/// pairing boxes (Broadphase): each box is its sphere grown by the same distance on every side,
/// which bounds the frame's motion, so the ball inscribed in it holds every place the sphere may
/// reach. Boxes that overlap only at their corners, as a pile's diagonal neighbours' do, hold
/// balls that do not meet: those pairs never touch within the frame.
bool grownSpheresMeet(const Aabb& box0, const Aabb& box1, double margin) {
    const double reach = 0.5 * (box0.extents().x() + box1.extents().x()) + margin;
    return !((box0.center() - box1.center()).squaredNorm() > reach * reach);
}

}  // namespace

void World::listAwake(bool newPairs) {
    const uint64_t changes = sleep_.changes();
    if (changes != awakeBodiesListedAt_ || bodies_.size() != awakeBodiesListedFor_) {
        awakeBodies_.clear();
        for (uint32_t i = 0; i < bodies_.size(); ++i)
            if (sleepFlags_[i] == 0) awakeBodies_.push_back(i);
        awakeBodiesListedAt_ = changes;
        awakeBodiesListedFor_ = bodies_.size();
    }
    if (newPairs || changes != awakePairsListedAt_) {
        // A sleeping island's pairs (the other body sleeps or is static) are left out: they
        // report no contact points and keep their static friction anchors for when it wakes.
        awakePairs_.clear();
        for (uint32_t p = 0; p < contactPairs_.size(); ++p) {
            const ContactPair& pair = contactPairs_[p];
            if ((sleepFlags_[pair.body0] | sleepFlags_[pair.body1]) == 0) awakePairs_.push_back(p);
        }
        awakePairsListedAt_ = changes;
    }
}

void World::collectContactPairs(double dt) {
    // Last frame's pairs keep their static friction anchors (contact.h) when they are found
    // again; both lists are sorted by (body0, body1).
    previousPairs_.swap(contactPairs_);
    contactPairs_.clear();
    contacts_.clear();
    touchingPairs_.clear();
    if (collidingBodies_ < 2) return;  // nothing can touch: no broadphase at all
    if (jointsChanged_) {
        jointsChanged_ = false;
        jointExclusions_.clear();
        for (const Joint& joint : joints_) {
            if (!joint.alive || joint.collide || joint.body0 == joint.body1) continue;
            jointExclusions_.push_back({std::min(joint.body0, joint.body1), std::max(joint.body0, joint.body1)});
        }
        std::sort(jointExclusions_.begin(), jointExclusions_.end(),
                  [](const BodyPair& a, const BodyPair& b) {
                      return a.body0 != b.body0 ? a.body0 < b.body0 : a.body1 < b.body1;
                  });
    }
    // Sleeping bodies keep their boxes and their pairs with one another (broadphase.h).
    const bool anyAsleep = sleepingActive() && sleep_.sleepingCount() > 0;
    broadphase_.update(bodies_, dt, 2.0, anyAsleep ? sleep_.flags() : nullptr, workerPool());
    reaches_.assign(bodies_.size(), 0.0);
    poses_.resize(bodies_.size());
    size_t previous = 0;
    droppedContactPairs_ = 0;
    // A sphere's box is a cube about its centre unless it is swept along the velocity.
    const bool spheresInCubes = !broadphase_.settings().sweptGrowth;
    const size_t cap = contactPairCap();
    for (const BodyPair& candidate : broadphase_.pairs()) {
        // Bounded work per frame: beyond the cap, pairs are dropped (deterministically, the
        // last in sorted order) and counted for a warning.
        if (contactPairs_.size() >= cap) {
            ++droppedContactPairs_;
            continue;
        }
        const bool joined = std::binary_search(
            jointExclusions_.begin(), jointExclusions_.end(), candidate,
            [](const BodyPair& a, const BodyPair& b) {
                return a.body0 != b.body0 ? a.body0 < b.body0 : a.body1 < b.body1;
            });
        if (joined) continue;
        const Body& b0 = bodies_[candidate.body0];
        const Body& b1 = bodies_[candidate.body1];
        if (!canCollide(b0.shape.type, b1.shape.type) || !Body::filtersMeet(b0, b1)) continue;
        // Two spheres' boxes overlap where their balls do not: spheres1000 keeps 3412 of 4709
        // pairs, the 2813 touching ones among them, and the narrowphase's look at the others
        // every substep was 5 % of its frame.
        if (spheresInCubes && b0.shape.type == ShapeType::Sphere && b1.shape.type == ShapeType::Sphere &&
            !grownSpheresMeet(broadphase_.bounds(candidate.body0), broadphase_.bounds(candidate.body1),
                              settings_.contactMargin))
            continue;
        reaches_[candidate.body0] = shapeReach(b0.shape);
        reaches_[candidate.body1] = shapeReach(b1.shape);
        // Paper 3.5: a pair's coefficients are the averages of its bodies'.
        ContactPair pair{.body0 = candidate.body0,
                         .body1 = candidate.body1,
                         .staticFriction = 0.5 * (b0.staticFriction + b1.staticFriction),
                         .dynamicFriction = 0.5 * (b0.dynamicFriction + b1.dynamicFriction),
                         .restitution = 0.5 * (b0.restitution + b1.restitution)};
        while (previous < previousPairs_.size() &&
               (previousPairs_[previous].body0 < pair.body0 ||
                (previousPairs_[previous].body0 == pair.body0 && previousPairs_[previous].body1 < pair.body1)))
            ++previous;
        if (previous < previousPairs_.size() && previousPairs_[previous].body0 == pair.body0 &&
            previousPairs_[previous].body1 == pair.body1) {
            const ContactPair& old = previousPairs_[previous];
            pair.anchor0 = old.anchor0;
            pair.anchor1 = old.anchor1;
            pair.turnAnchor = old.turnAnchor;
            pair.anchored = old.anchored;
            pair.lambdaNormal = old.lambdaNormal;  // its last substep's push, for pushedBefore
        }
        contactPairs_.push_back(pair);
    }
}

// Compiled for the base ISA and AVX2 (without FMA, so every operation rounds as in the base
// build), chosen at load time: the three-operand forms take instructions off. Defined before
// its first call, as clang asks of a function with clones.
[[gnu::target_clones("avx2", "default")]] void World::findPairContacts(
    const uint32_t* order, size_t first, size_t last, bool sleeping, std::vector<Contact>& out,
    std::vector<uint32_t>& touching) {
    // Most of a frame's pairs have no point in a given substep (a pile's: three in four): the
    // solve and the velocity pass visit only those that have, in pair order. Listed here, as
    // each pair's point is found, rather than in a second pass over every pair.
    ContactManifold manifold;  // the general path's, made once
    // Read once, not per pair: the loop writes pairs and contacts, which the compiler cannot
    // tell apart from these arrays.
    ContactPair* const pairs = contactPairs_.data();
    const Body* const bodies = bodies_.data();
    const Pose* const poses = poses_.data();
    const double* const reaches = reaches_.data();
    uint8_t* const touched = pairTouched_.data();
    const double margin = settings_.contactMargin;
    auto written = static_cast<uint32_t>(out.size());
    // Pairs [from, to) by their index in contactPairs_ (the loop is made once for the awake
    // list and once for every pair, so that neither asks which per pair).
    const auto findPoints = [&](size_t from, size_t to, const auto& pairIndex)
        __attribute__((always_inline)) {
        for (size_t k = from; k < to; ++k) {
            const size_t p = pairIndex(k);
            ContactPair& pair = pairs[p];
            const Pose& pose0 = poses[pair.body0];
            const Pose& pose1 = poses[pair.body1];
            // Bounding spheres first: most of a frame's candidate pairs are not touching in a
            // given substep, and this test costs a fraction of the narrowphase.
            const double reach = reaches[pair.body0] + reaches[pair.body1] + margin;
            const bool apart = std::isfinite(reach) &&
                               (pose0.position - pose1.position).squaredNorm() > reach * reach;
            pair.first = written;
            pair.pushedBefore = pair.lambdaNormal > 0.0;
            pair.lambdaNormal = pair.lambdaTangent1 = pair.lambdaTangent2 = pair.lambdaTwist = 0.0;
            if (apart) {
                pair.count = 0;
                pair.anchored = false;  // apart: the next touch anchors anew
                continue;
            }
            const Body& b0 = bodies[pair.body0];
            const Body& b1 = bodies[pair.body1];
            // Spheres on spheres (a pile's pairs) write their point straight into `out`.
            const int count =
                b0.shape.type == ShapeType::Sphere && b1.shape.type == ShapeType::Sphere
                    ? appendSphereSphereContact(b0, pose0, b1, pose1, margin, out)
                    : appendOtherPairContacts(b0, pose0, b1, pose1, margin, manifold, out);
            pair.count = static_cast<uint32_t>(count);
            if (count == 0) {
                pair.anchored = false;  // apart: the next touch anchors anew
                continue;
            }
            written += static_cast<uint32_t>(count);
            touching.push_back(static_cast<uint32_t>(p));
            if (sleeping) touched[p] = 1;
        }
    };
    for (size_t from = first; from < last; from += kPairsPerChunk) {
        // The step ends at the substep loop's check. Asked every kPairsPerChunk pairs: the
        // flag is an atomic load, and a frame's pairs are thousands.
        if (stepCancellationRequested()) break;
        const size_t to = std::min(from + kPairsPerChunk, last);
        if (order)
            findPoints(from, to, [order](size_t k) { return size_t{order[k]}; });
        else
            findPoints(from, to, [](size_t k) { return k; });
    }
}

void World::findContacts(bool sleeping) {
    // Each colliding body's shape pose, once per substep rather than once per pair; while some
    // sleep, the awake bodies' and pairs' lists alone are visited (in chunks with more threads).
    // A sphere's orientation is left out: the fast path (contact_spheres.h) reads its position
    // alone, and findPairContacts gives the general path its orientation when a pair needs it.
    const auto pose = [&](Body& body) __attribute__((always_inline)) {
        const auto i = static_cast<size_t>(&body - bodies_.data());
        if (!(reaches_[i] > 0.0)) return;
        poses_[i].position = body.userPosition();
        if (body.shape.type != ShapeType::Sphere) poses_[i].rotation = body.userOrientation();
    };
    forEachMovingBody(pose);
    const uint32_t* order = sleepFlags_ ? awakePairs_.data() : nullptr;
    const size_t pairs = sleepFlags_ ? awakePairs_.size() : contactPairs_.size();
    WorkerPool* const pool = workerPool();
    if (pool == nullptr || pairs < 2 * kPairsPerChunk) {
        contacts_.clear();
        touchingPairs_.clear();
        findPairContacts(order, 0, pairs, sleeping, contacts_, touchingPairs_);
        return;
    }
    // In parallel: each block of pairs finds its contacts and its touching pairs into its own
    // lists, and the lists are joined in block order (each block copying its own at offsets
    // summed in order), so the contacts and touching pairs are the serial ones, in the serial
    // order whichever thread ran a block. The blocks are dealt out as in the other stages
    // (world_parallel.cpp, forChunks), so each thread mostly visits the same bodies.
    const auto chunks = static_cast<size_t>(pool->blocksFor(pairs, kPairsPerChunk));
    const auto chunkStart = [&](size_t chunk) { return pairs * chunk / chunks; };
    if (chunkContacts_.size() < chunks) chunkContacts_.resize(chunks);
    if (chunkTouching_.size() < chunks) chunkTouching_.resize(chunks);
    const auto pairIndex = [&](size_t k) { return static_cast<uint32_t>(order ? order[k] : k); };
    // The coloured solve's grouping of the touching pairs by colour (groupTouchingPairs) is
    // done here too, block by block: counted in the first loop, placed in the second.
    const bool grouping = frame_.coloured && coloured_ != nullptr;
    if (grouping && coloured_->blockCounts.size() < chunks) coloured_->blockCounts.resize(chunks);
    pool->parallelFor(static_cast<int>(chunks), [&](int chunk) {
        const size_t first = chunkStart(static_cast<size_t>(chunk));
        const size_t last = chunkStart(static_cast<size_t>(chunk) + 1);
        chunkContacts_[chunk].clear();
        std::vector<uint32_t>& touching = chunkTouching_[chunk];
        touching.clear();
        findPairContacts(order, first, last, sleeping, chunkContacts_[chunk], touching);
        if (grouping) ColourGroups::count(touching, coloured_->pairColours.data(), coloured_->blockCounts[chunk]);
    });
    chunkContactOffsets_.resize(chunks + 1);
    chunkTouchingOffsets_.resize(chunks + 1);
    chunkContactOffsets_[0] = chunkTouchingOffsets_[0] = 0;
    for (size_t chunk = 0; chunk < chunks; ++chunk) {
        chunkContactOffsets_[chunk + 1] =
            chunkContactOffsets_[chunk] + static_cast<uint32_t>(chunkContacts_[chunk].size());
        chunkTouchingOffsets_[chunk + 1] =
            chunkTouchingOffsets_[chunk] + static_cast<uint32_t>(chunkTouching_[chunk].size());
    }
    // Resized, not cleared: only slots beyond the last substep's count are constructed.
    contacts_.resize(chunkContactOffsets_[chunks]);
    touchingPairs_.resize(chunkTouchingOffsets_[chunks]);
    if (grouping) {
        coloured_->touching.beginBlocks(std::span(coloured_->blockCounts).first(chunks));
        coloured_->touchingGrouped = true;
    }
    pool->parallelFor(static_cast<int>(chunks), [&](int chunk) {
        const uint32_t offset = chunkContactOffsets_[chunk];
        for (size_t k = chunkStart(static_cast<size_t>(chunk)); k < chunkStart(static_cast<size_t>(chunk) + 1); ++k)
            contactPairs_[pairIndex(k)].first += offset;
        std::copy(chunkContacts_[chunk].begin(), chunkContacts_[chunk].end(), contacts_.begin() + offset);
        std::copy(chunkTouching_[chunk].begin(), chunkTouching_[chunk].end(),
                  touchingPairs_.begin() + chunkTouchingOffsets_[chunk]);
        if (grouping)
            coloured_->touching.placeBlock(chunkTouching_[chunk], coloured_->pairColours.data(),
                                           coloured_->blockCounts[chunk]);
    });
}

}  // namespace substep

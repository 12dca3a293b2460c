#include "physics/collision/broadphase.h"

#include "physics/collision/shape_bounds.h"
#include "physics/worker_pool.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace substep {

namespace {

/// Below this many boxes in the sweep its overlap tests run on the calling thread alone, and a
/// parallel sweep's blocks hold at least kMinSweepBlock boxes: a box's tests cost some tens of
/// nanoseconds, a loop's hand-out about a microsecond.
constexpr size_t kMinParallelSweep = 256;
constexpr size_t kMinSweepBlock = 32;

Aabb infiniteBox() {
    const double inf = std::numeric_limits<double>::infinity();
    return {Vec3::Constant(-inf), Vec3::Constant(inf)};
}

bool isFinite(const Aabb& box) {
    return box.min.allFinite() && box.max.allFinite();
}

/// Same geometry as far as the bounds are concerned (a static body is re-boxed only when this
/// or its pose changes).
bool sameGeometry(const Shape& a, const Shape& b) {
    return a.type == b.type && a.radius == b.radius && a.size == b.size && a.length == b.length &&
           a.mesh == b.mesh && a.localBounds.min == b.localBounds.min &&
           a.localBounds.max == b.localBounds.max;
}

BodyPair orderedPair(uint32_t a, uint32_t b) {
    return a < b ? BodyPair{a, b} : BodyPair{b, a};
}

bool pairLess(const BodyPair& a, const BodyPair& b) {
    return a.body0 != b.body0 ? a.body0 < b.body0 : a.body1 < b.body1;
}

/// Whether a box reaches a plane n·x = offset: its lowest point along n at or below it (the box
/// already carries the margin).
bool reachesPlane(const Aabb& box, const Vec3& n, const Vec3& nAbs, double offset) {
    const double lowest = n.dot(box.center()) - 0.5 * nAbs.dot(box.extents());
    return lowest <= offset;
}

}  // namespace

Broadphase::Broadphase(const BroadphaseSettings& settings)
    : settings_(settings), staticTree_(0.0), dynamicTree_(settings.fatMargin), frozenTree_(0.0) {}

void Broadphase::setSettings(const BroadphaseSettings& settings) {
    settings_ = settings;
    dynamicTree_ = AabbTree(settings.fatMargin);
    clear();
}

void Broadphase::clear() {
    slots_.clear();
    boxes_.clear();
    staticTree_.clear();
    dynamicTree_.clear();
    frozenTree_.clear();
    dynamic_.clear();
    planes_.clear();
    frozen_.clear();
    newlyFrozen_.clear();
    changedFixed_.clear();
    kept_.clear();
    sweep_.clear();
    found_.clear();
    pairs_.clear();
}

const Aabb& Broadphase::bounds(uint32_t index) const {
    static const Aabb kEmpty;
    return index < boxes_.size() ? boxes_[index] : kEmpty;
}

void Broadphase::update(std::span<const Body> bodies, double dt, double k, const uint8_t* asleep, WorkerPool* pool) {
    // Slots beyond the span belong to bodies that no longer exist.
    for (size_t i = bodies.size(); i < slots_.size(); ++i)
        leave(static_cast<uint32_t>(i));
    slots_.resize(bodies.size());
    boxes_.resize(bodies.size());

    dynamic_.clear();
    planes_.clear();
    frozen_.clear();
    newlyFrozen_.clear();
    changedFixed_.clear();
    for (size_t i = 0; i < bodies.size(); ++i)
        syncSlot(static_cast<uint32_t>(i), bodies[i], dt, k, asleep != nullptr && asleep[i] != 0);

    found_.clear();
    if (settings_.method == BroadphaseMethod::SweepAndPrune) collectSweepPairs(pool);
    collectStaticAndTreePairs();
    collectPlanePairs(bodies);
    collectSleepingPairs(bodies);
    sortPairs(bodies.size());
}

void Broadphase::leave(uint32_t index) {
    Slot& slot = slots_[index];
    if (slot.proxy != AabbTree::kNull) {
        AabbTree& tree = slot.kind == Kind::Static ? staticTree_ : slot.frozen ? frozenTree_ : dynamicTree_;
        tree.destroyProxy(slot.proxy);
    }
    slot.proxy = AabbTree::kNull;
    slot.frozen = false;
    slot.kept = false;
    slot.kind = Kind::None;
    boxes_[index] = Aabb{};
    slot.shape = Shape{};  // drops references to mesh data
    slot.inSweep = false;  // its sweep entry is dropped at the next sweep
}

void Broadphase::syncSlot(uint32_t index, const Body& body, double dt, double k, bool asleep) {
    Kind wanted = Kind::None;
    if (body.alive && body.collide && body.shape.type != ShapeType::None) {
        if (body.shape.type == ShapeType::Plane) {
            wanted = Kind::Plane;
        } else {
            wanted = body.isDynamic() ? Kind::Dynamic : Kind::Static;
        }
    }
    Slot& slot = slots_[index];
    // A slot reused by a new body, or a body that changed its kind, starts over.
    if (slot.kind != Kind::None && (slot.kind != wanted || slot.generation != body.generation)) {
        leave(index);
    }
    slot.generation = body.generation;
    slot.kept = false;
    if (wanted == Kind::None) return;

    if (wanted == Kind::Plane) {
        const bool same = slot.kind == Kind::Plane && body.shape.normal == slot.shape.normal &&
                          body.shape.offset == slot.shape.offset;
        if (!same) slot.shape = body.shape;
        slot.kind = Kind::Plane;
        boxes_[index] = infiniteBox();
        if (body.shape.normal.allFinite() && std::isfinite(body.shape.offset)) {
            planes_.push_back(index);
            if (same) slot.kept = true;
            else changedFixed_.push_back(index);
        }
        return;
    }

    // A body asleep since the last update has not moved: its box, leaf and pairs stay.
    if (wanted == Kind::Dynamic && asleep && slot.frozen) {
        slot.kept = true;
        frozen_.push_back(index);
        return;
    }
    if (slot.frozen) {
        // Woken: back from the sleeping bodies' tree into the sweep (or the dynamic tree).
        frozenTree_.destroyProxy(slot.proxy);
        slot.proxy = AabbTree::kNull;
        slot.frozen = false;
    }

    // A static body that has not moved or changed keeps its box and its leaf untouched.
    const bool still = body.v.isZero(0.0) && body.omega.isZero(0.0);
    if (wanted == Kind::Static && slot.kind == Kind::Static && still && body.x == slot.position &&
        body.q.coeffs() == slot.orientation.coeffs() && sameGeometry(body.shape, slot.shape)) {
        slot.kept = true;
        return;
    }

    const Aabb tight = shapeBounds(body.shape, body.userPosition(), body.userOrientation());
    if (tight.isEmpty() || !isFinite(tight)) {
        if (slot.kind != Kind::None) leave(index);
        return;
    }
    double growth = 0.0;
    Vec3 sweep = Vec3::Zero();
    if (!still) {
        double speed = body.rotates()
                           ? body.omega.norm() * (body.userOrigin.norm() + shapeReach(body.shape))
                           : 0.0;
        if (settings_.sweptGrowth) {
            sweep = (k * dt) * body.v;
            // A sweep that is not finite or too long becomes the clamped growth on every side.
            if (!(sweep.norm() <= settings_.maxGrowth)) {
                sweep.setZero();
                speed = std::numeric_limits<double>::infinity();
            }
        } else {
            speed += body.v.norm();
        }
        growth = std::abs(k * dt) * speed;
        // Clamped, NaN included: a runaway body gets a large finite box, never a broken tree.
        if (!(growth <= settings_.maxGrowth)) growth = settings_.maxGrowth;
    }
    Aabb box = tight.inflated(growth + settings_.margin);
    box.min += sweep.cwiseMin(0.0);
    box.max += sweep.cwiseMax(0.0);
    if (!isFinite(box)) {
        if (slot.kind != Kind::None) leave(index);
        return;
    }
    boxes_[index] = box;

    if (wanted == Kind::Static) {
        slot.position = body.x;
        slot.orientation = body.q;
        slot.shape = body.shape;
        if (slot.proxy == AabbTree::kNull) {
            slot.proxy = staticTree_.createProxy(box, index);
        } else {
            staticTree_.moveProxy(slot.proxy, box);
        }
        changedFixed_.push_back(index);
    } else if (asleep) {
        // Falling asleep: the box made now (a sleeping body is still) serves until it wakes.
        if (slot.proxy != AabbTree::kNull) dynamicTree_.destroyProxy(slot.proxy);
        slot.proxy = frozenTree_.createProxy(box, index);
        slot.frozen = true;
        slot.inSweep = false;  // its sweep entry is dropped at the next sweep
        frozen_.push_back(index);
        newlyFrozen_.push_back(index);
    } else {
        dynamic_.push_back(index);
        if (settings_.method == BroadphaseMethod::AabbTree) {
            if (slot.proxy == AabbTree::kNull) {
                slot.proxy = dynamicTree_.createProxy(box, index);
            } else {
                dynamicTree_.moveProxy(slot.proxy, box);
            }
        }
    }
    slot.kind = wanted;
}

void Broadphase::collectStaticAndTreePairs() {
    const bool useTree = settings_.method == BroadphaseMethod::AabbTree;
    const bool anyFrozen = !frozen_.empty();
    for (const uint32_t i : dynamic_) {
        const Aabb& box = boxes_[i];
        // Leaves hold fattened boxes: keep only partners whose pairing boxes overlap.
        staticTree_.query(box, [&](int32_t proxy) {
            const uint32_t j = staticTree_.userData(proxy);
            if (boxes_[j].overlaps(box)) found_.push_back(orderedPair(i, j));
        });
        // Sleeping bodies do not search: the awake ones find them.
        if (anyFrozen)
            frozenTree_.query(box, [&](int32_t proxy) {
                const uint32_t j = frozenTree_.userData(proxy);
                if (boxes_[j].overlaps(box)) found_.push_back(orderedPair(i, j));
            });
        if (!useTree) continue;
        // Each dynamic pair is reported by its lower body only.
        dynamicTree_.query(box, [&](int32_t proxy) {
            const uint32_t j = dynamicTree_.userData(proxy);
            if (j > i && boxes_[j].overlaps(box)) found_.push_back({i, j});
        });
    }
}

void Broadphase::collectSweepPairs(WorkerPool* pool) {
    // Drop entries of bodies that left, add the newcomers.
    std::erase_if(sweep_, [&](const SweepEntry& e) {
        return e.body >= slots_.size() || !slots_[e.body].inSweep;
    });
    size_t newcomers = 0;
    for (const uint32_t i : dynamic_) {
        if (!slots_[i].inSweep) {
            sweep_.push_back({0.0, i});
            slots_[i].inSweep = true;
            ++newcomers;
        }
    }
    if (sweep_.size() < 2) return;

    // Sweep along the axis where the boxes spread most; switch only for a clear gain, since
    // a new axis costs a full re-sort.
    Vec3 sum = Vec3::Zero();
    Vec3 sumSquares = Vec3::Zero();
    for (const SweepEntry& e : sweep_) {
        const Vec3 c = boxes_[e.body].center();
        sum += c;
        sumSquares += c.cwiseProduct(c);
    }
    const double n = static_cast<double>(sweep_.size());
    const Vec3 variance = sumSquares / n - (sum / n).cwiseProduct(sum / n);
    int best = sweepAxis_;
    for (int axis = 0; axis < 3; ++axis) {
        if (variance[axis] > 1.5 * variance[best]) best = axis;
    }
    sweepAxis_ = best;
    const int a = sweepAxis_;
    const int b = (a + 1) % 3;
    const int c = (a + 2) % 3;

    for (SweepEntry& e : sweep_)
        e.min = boxes_[e.body].min[a];
    // Insertion sort: last frame's order is nearly right, so this is close to linear. Many
    // newcomers at the end (the first frame, an island woken) are sorted in n log n instead; the
    // order is the same (min, then body, a total order).
    auto before = [](const SweepEntry& x, const SweepEntry& y) {
        return x.min != y.min ? x.min < y.min : x.body < y.body;
    };
    if (newcomers > 64) std::sort(sweep_.begin(), sweep_.end(), before);
    for (size_t i = 1; i < sweep_.size(); ++i) {
        const SweepEntry entry = sweep_[i];
        size_t j = i;
        while (j > 0 && before(entry, sweep_[j - 1])) {
            sweep_[j] = sweep_[j - 1];
            --j;
        }
        sweep_[j] = entry;
    }

    // Gather the boxes in sweep order so the inner loop reads contiguous memory.
    const size_t count = sweep_.size();
    sweepMin_.resize(count + 1);
    sweepMax_.resize(count);
    sweepCross_.resize(count);
    for (size_t i = 0; i < count; ++i) {
        const Aabb& box = boxes_[sweep_[i].body];
        sweepMin_[i] = box.min[a];
        sweepMax_[i] = box.max[a];
        sweepCross_[i] = {box.min[b], box.max[b], box.min[c], box.max[c]};
    }
    // A sentinel past the end stops every scan without a bounds check.
    sweepMin_[count] = std::numeric_limits<double>::infinity();
    if (pool == nullptr || count < kMinParallelSweep) {
        sweepOverlaps(0, count, found_);
        return;
    }
    // In blocks of sweep positions, each block's pairs into its own list (it reads the sweep
    // arrays, written above, and writes its list alone), joined in block order: found_ is the
    // serial one whichever thread ran a block.
    const auto blocks = static_cast<size_t>(pool->blocksFor(count, kMinSweepBlock));
    if (blockFound_.size() < blocks) blockFound_.resize(blocks);
    pool->parallelFor(static_cast<int>(blocks), [&](int block) {
        std::vector<BodyPair>& out = blockFound_[static_cast<size_t>(block)];
        out.clear();
        sweepOverlaps(count * static_cast<size_t>(block) / blocks, count * static_cast<size_t>(block + 1) / blocks,
                      out);
    });
    for (size_t block = 0; block < blocks; ++block)
        found_.insert(found_.end(), blockFound_[block].begin(), blockFound_[block].end());
}

void Broadphase::sweepOverlaps(size_t first, size_t last, std::vector<BodyPair>& out) const {
    for (size_t i = first; i < last; ++i) {
        const double maxA = sweepMax_[i];
        const CrossExtent p = sweepCross_[i];
        // The boxes that overlap box i along the sweep axis (the sentinel ends the scan).
        size_t end = i + 1;
        while (sweepMin_[end] <= maxA) ++end;
        // Each of them is written as a pair and kept when the cross axes overlap too: the four
        // tests and the keep without a branch. In a pile one in ten or twenty overlaps, and the
        // short-circuit branches of each test were mispredicted (4 % of spheres1000's step).
        const size_t start = out.size();
        out.resize(start + (end - i - 1));
        BodyPair* next = out.data() + start;
        const uint32_t body = sweep_[i].body;
        for (size_t j = i + 1; j < end; ++j) {
            const CrossExtent& q = sweepCross_[j];
            *next = orderedPair(body, sweep_[j].body);
            next += static_cast<int>(q.minB <= p.maxB) & static_cast<int>(p.minB <= q.maxB) &
                    static_cast<int>(q.minC <= p.maxC) & static_cast<int>(p.minC <= q.maxC);
        }
        out.resize(static_cast<size_t>(next - out.data()));
    }
}

void Broadphase::collectPlanePairs(std::span<const Body> bodies) {
    for (const uint32_t p : planes_) {
        const Vec3& n = bodies[p].shape.normal;
        const double offset = bodies[p].shape.offset;
        const Vec3 nAbs = n.cwiseAbs();
        for (const uint32_t i : dynamic_)
            if (reachesPlane(boxes_[i], n, nAbs, offset)) found_.push_back(orderedPair(p, i));
    }
}

void Broadphase::collectSleepingPairs(std::span<const Body> bodies) {
    kept_.clear();
    if (frozen_.empty()) return;
    // Last update's pairs between slots that have not changed since (each pair has a sleeping
    // body: static and plane slots never pair with one another) still overlap as they did.
    const size_t slotCount = slots_.size();
    for (const BodyPair& pair : pairs_)
        if (pair.body1 < slotCount && slots_[pair.body0].kept && slots_[pair.body1].kept)
            kept_.push_back(pair);

    // Bodies that fell asleep: against the sleeping ones (a pair of two newcomers once), the
    // static bodies and the planes. The awake bodies found them already.
    for (const uint32_t i : newlyFrozen_) {
        const Aabb& box = boxes_[i];
        frozenTree_.query(box, [&](int32_t proxy) {
            const uint32_t j = frozenTree_.userData(proxy);
            if (j == i || (!slots_[j].kept && j < i)) return;
            if (boxes_[j].overlaps(box)) found_.push_back(orderedPair(i, j));
        });
        staticTree_.query(box, [&](int32_t proxy) {
            const uint32_t j = staticTree_.userData(proxy);
            if (boxes_[j].overlaps(box)) found_.push_back(orderedPair(i, j));
        });
        for (const uint32_t p : planes_) {
            const Vec3& n = bodies[p].shape.normal;
            if (reachesPlane(box, n, n.cwiseAbs(), bodies[p].shape.offset))
                found_.push_back(orderedPair(p, i));
        }
    }

    // Static bodies and planes that moved or changed: against the bodies that slept before.
    for (const uint32_t s : changedFixed_) {
        if (slots_[s].kind == Kind::Plane) {
            const Vec3& n = bodies[s].shape.normal;
            const Vec3 nAbs = n.cwiseAbs();
            for (const uint32_t i : frozen_)
                if (slots_[i].kept && reachesPlane(boxes_[i], n, nAbs, bodies[s].shape.offset))
                    found_.push_back(orderedPair(s, i));
            continue;
        }
        const Aabb& box = boxes_[s];
        frozenTree_.query(box, [&](int32_t proxy) {
            const uint32_t j = frozenTree_.userData(proxy);
            if (slots_[j].kept && boxes_[j].overlaps(box)) found_.push_back(orderedPair(s, j));
        });
    }
}

void Broadphase::sortPairs(size_t bodyCount) {
    // Counting sort by body0, then insertion sort, which only moves pairs within a body0 run.
    bucketStart_.assign(bodyCount + 1, 0);
    for (const BodyPair& pair : found_)
        ++bucketStart_[pair.body0 + 1];
    for (size_t i = 1; i <= bodyCount; ++i)
        bucketStart_[i] += bucketStart_[i - 1];
    pairs_.resize(found_.size());
    for (const BodyPair& pair : found_)
        pairs_[bucketStart_[pair.body0]++] = pair;
    for (size_t i = 1; i < pairs_.size(); ++i) {
        const BodyPair pair = pairs_[i];
        size_t j = i;
        while (j > 0 && pairLess(pair, pairs_[j - 1])) {
            pairs_[j] = pairs_[j - 1];
            --j;
        }
        pairs_[j] = pair;
    }
    if (kept_.empty()) return;
    // The kept pairs are in order already: merged with the new ones (no pair is in both).
    found_.resize(kept_.size() + pairs_.size());
    std::merge(kept_.begin(), kept_.end(), pairs_.begin(), pairs_.end(), found_.begin(), pairLess);
    pairs_.swap(found_);
}

}  // namespace substep

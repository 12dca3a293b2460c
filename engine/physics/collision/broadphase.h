#pragma once
/// The broadphase (paper 3.5): once per frame, every colliding body gets a box grown by how far
/// it may move during the frame, and the pairs of bodies whose boxes overlap become the
/// candidates the narrowphase examines at every substep.
///
/// A body's pairing box is its tight shape box grown on every side by
///   k·Δt·(|v| + |ω|·reach) + margin
/// (or, with `sweptGrowth`, swept by k·Δt·v and grown by the rest), reach being the largest
/// distance from its centre of mass to a point of its shape (the rotation term only for bodies that
/// rotate). k ≥ 1 covers accelerations within the frame (the paper uses 2); the small constant
/// margin keeps resting contacts paired when their velocities are nearly zero. The growth is
/// clamped to `maxGrowth`, so a huge or non-finite velocity makes a large but finite box (a body
/// moving farther than that in one frame may tunnel); a body whose pose is not finite gets no box
/// and no pairs.
///
/// Static bodies (inverse mass 0) live in a tree of their own that changes only when one of them
/// moves or changes, and they never search it: dynamic bodies search it for static partners.
/// Dynamic pairs come from a sweep and prune (or from a second tree, by setting). Planes are
/// infinite, so they stay out of both sets and are paired with every dynamic body whose box reaches
/// them (the box's lowest point along the normal at or below the plane).
///
/// Pairs are never static-static, never involve a dead slot, a body with collide == false or
/// ShapeType::None. Filtering by joints is the world's business.
///
/// Sleeping bodies (the world's sleep flags, passed to update) do not move, so their boxes and
/// their pairs with one another, with unchanged static bodies and with planes are kept from the
/// last update, not found again: a body falling asleep gets its box (still: no motion growth)
/// once and moves from the sweep into a tree of sleeping bodies, which the awake bodies, the
/// bodies falling asleep and the static bodies that moved search; waking puts it back in the
/// sweep. The pairs are the same as those of an update that treats every body alike.

#include "physics/body.h"
#include "physics/collision/aabb.h"
#include "physics/collision/aabb_tree.h"

#include <cstdint>
#include <span>
#include <vector>

namespace substep {

class WorkerPool;

/// A candidate pair of body indices, body0 < body1.
struct BodyPair {
    uint32_t body0 = 0;
    uint32_t body1 = 0;
    bool operator==(const BodyPair&) const = default;
};

/// How dynamic-dynamic pairs are found (static and plane pairs are found the same way by both).
enum class BroadphaseMethod {
    AabbTree,       ///< a dynamic AABB tree with fattened leaves; suits mixed sizes
    SweepAndPrune,  ///< boxes kept sorted along one axis (insertion sort from the last frame)
};

struct BroadphaseSettings {
    /// The sweep measured faster on every benchmark scene (1000 spheres falling and piled,
    /// 2000 mixed sizes): see tests/benchmarks/broadphase_benchmark.cpp.
    BroadphaseMethod method = BroadphaseMethod::SweepAndPrune;
    /// Added to every side of every box (m): keeps touching bodies at rest paired.
    double margin = 0.005;
    /// How far a leaf's stored box reaches beyond its pairing box (m), so that bodies moving
    /// slowly do not restructure the tree every frame.
    double fatMargin = 0.05;
    /// Upper bound of the motion growth k·Δt·(|v| + |ω|·reach) (m).
    double maxGrowth = 1000.0;
    /// Grow boxes along the velocity only: the tight box swept by k·Δt·v, plus the rotation
    /// growth and the margin on every side. Bodies falling side by side then stop pairing with
    /// their neighbours (1000 spheres in a grid falling at 8 m/s: 974 pairs instead of 57867),
    /// at the price of sideways motion within the frame beyond the margin (a body on a curved
    /// path, a sideways push) going unseen until the next frame. Off: the paper's k·Δt·|v|
    /// on every side.
    bool sweptGrowth = false;
};

class Broadphase {
  public:
    explicit Broadphase(const BroadphaseSettings& settings = {});

    /// Updates every body's box (grown by k·dt·|v| plus, for rotating bodies,
    /// k·dt·|ω|·reach, plus the margin) and collects the candidate pairs. `bodies` is indexed
    /// by body id; slots may die, be reused (a new generation) or change between calls.
    /// `asleep` (null: none) flags sleeping bodies, as many as `bodies`: a body flagged in two
    /// updates in a row must not have moved or changed between them (the world wakes every body
    /// it edits), and its box and kept pairs are not looked at again. With a `pool` the sweep's
    /// overlap tests run in blocks on its threads, the pairs joined in block order: the same
    /// pairs in the same order as without.
    void update(std::span<const Body> bodies, double dt, double k = 2.0, const uint8_t* asleep = nullptr,
                WorkerPool* pool = nullptr);

    /// The pairs of the last update, sorted by (body0, body1) so that runs are deterministic.
    std::span<const BodyPair> pairs() const { return pairs_; }

    /// The pairing box of body `index` in the last update; empty for bodies the broadphase
    /// leaves out, the infinite box for planes.
    const Aabb& bounds(uint32_t index) const;

    const BroadphaseSettings& settings() const { return settings_; }
    /// Changes the settings; the next update rebuilds everything.
    void setSettings(const BroadphaseSettings& settings);
    /// Forgets every body (the next update starts afresh).
    void clear();

    /// Number of bodies in the static and the dynamic set after the last update (diagnostics).
    int staticCount() const { return staticTree_.proxyCount(); }
    int dynamicCount() const { return static_cast<int>(dynamic_.size() + frozen_.size()); }
    /// Number of sleeping bodies among them, whose boxes and pairs were kept (diagnostics).
    int sleepingCount() const { return static_cast<int>(frozen_.size()); }

  private:
    enum class Kind : uint8_t { None, Static, Dynamic, Plane };

    /// What the broadphase remembers about one body slot.
    struct Slot {
        Vec3 position = Vec3::Zero();  ///< pose and shape a static box was made from
        Quat orientation = Quat::Identity();
        Shape shape;
        uint32_t generation = 0;
        int32_t proxy = AabbTree::kNull;
        Kind kind = Kind::None;
        bool inSweep = false;  ///< has an entry in sweep_
        bool frozen = false;   ///< a sleeping dynamic body: its proxy is in frozenTree_
        /// Its box and kind are those of the last update (a frozen body frozen before it, a
        /// static body or a plane that did not change): its pairs with other such slots are kept.
        bool kept = false;
    };

    /// One body in the sweep, sorted by the lower bound of its box along the sweep axis.
    struct SweepEntry {
        double min = 0.0;
        uint32_t body = 0;
    };
    /// The extent of a box across the sweep axis (B and C are the other two axes).
    struct CrossExtent {
        double minB, maxB, minC, maxC;
    };

    void syncSlot(uint32_t index, const Body& body, double dt, double k, bool asleep);
    void leave(uint32_t index);
    void collectStaticAndTreePairs();
    void collectSweepPairs(WorkerPool* pool);
    /// The sweep's overlaps of the boxes at sweep positions [first, last) with those after them.
    void sweepOverlaps(size_t first, size_t last, std::vector<BodyPair>& out) const;
    void collectPlanePairs(std::span<const Body> bodies);
    /// The pairs of bodies that fell asleep, and of static bodies and planes that changed, with
    /// the sleeping bodies; keeps last update's pairs between unchanged sleeping, static and
    /// plane slots in kept_.
    void collectSleepingPairs(std::span<const Body> bodies);
    void sortPairs(size_t bodyCount);

    BroadphaseSettings settings_;
    std::vector<Slot> slots_;
    std::vector<Aabb> boxes_;  ///< pairing box of each slot in the last update
    AabbTree staticTree_;
    AabbTree dynamicTree_;
    std::vector<uint32_t> dynamic_;  ///< awake dynamic bodies with a box, ascending
    std::vector<uint32_t> planes_;
    AabbTree frozenTree_;  ///< the sleeping bodies' boxes (no fat margin: they do not move)
    std::vector<uint32_t> frozen_;         ///< sleeping bodies with a box, ascending
    std::vector<uint32_t> newlyFrozen_;    ///< those that fell asleep since the last update
    std::vector<uint32_t> changedFixed_;   ///< static bodies and planes re-boxed in this update
    std::vector<BodyPair> kept_;           ///< last update's pairs between kept slots
    std::vector<SweepEntry> sweep_;
    // The boxes in sweep order, split so that the inner loop streams through lower bounds.
    std::vector<double> sweepMin_, sweepMax_;
    std::vector<CrossExtent> sweepCross_;
    int sweepAxis_ = 0;
    std::vector<BodyPair> found_;  ///< unsorted pairs of this update
    std::vector<std::vector<BodyPair>> blockFound_;  ///< per block of a parallel sweep: its pairs
    std::vector<BodyPair> pairs_;
    std::vector<uint32_t> bucketStart_;
};

}  // namespace substep

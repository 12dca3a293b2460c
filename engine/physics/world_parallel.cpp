/// The world's parallel step (WorldSettings::threads): integration and velocity derivation in
/// blocks of bodies, and the position solve and velocity pass by colour (constraint_colouring.h):
/// a colour's joints in blocks on the worker pool (each thread starting on its own run of blocks
/// and taking the others' last ones when done, worker_pool.h), a colour's contact pairs split
/// into each thread's fixed share, the threads waiting for one another between colours
/// (solveColours).
///
/// Why the bytes do not depend on the thread count or the blocks: a block of the body loops
/// writes its own bodies alone; a colour's constraints share no dynamic body, and each writes only
/// its own joint or pair, that pair's contact points and its two bodies (static ones never: every
/// write is guarded by invMass > 0), and reads only those and static bodies. So within a colour
/// no constraint reads what another writes, and any order or split gives the same results. The
/// colours, the joints around light bodies (one cluster solve moves many bodies), the overflow,
/// the velocity pass's joint damping and the restitution sweeps' chain of collisions run serially,
/// in a fixed order; the sweeps' looks over every touching pair (contact_restitution.h), the
/// narrowphase with the grouping of its touching pairs by colour (world_contacts.cpp) and the
/// broadphase's sweep (broadphase.h) run in blocks, each block into its own list, the lists
/// joined in block order.

#include "physics/world.h"

#include "physics/constraint_colouring.h"
#include "physics/joint_block_solve.h"
#include "physics/joints/joint_solver.h"
#include "physics/worker_pool.h"

#include <algorithm>

namespace substep {
namespace {

/// Fewer items than this are run by the calling thread alone: handing out a loop costs about a
/// microsecond, and the bodies' cache lines moving to the other core more; a colour of fewer
/// constraints does not repay it (chain100's colours of 50 joints at 2 threads: 0.47 ms/frame
/// split, against 0.27 ms at 1 thread).
constexpr size_t kMinParallelItems = 128;
/// The same for a colour of contact pairs: a pile's last colours hold 30 to 100 pairs (a
/// sphere pair costs 60-150 ns), and splitting them paid (spheres1000 at 2 threads 9.9-10.1
/// ms/frame at 32 against 10.2-10.3 at 128 with stealing blocks; with each thread's fixed share,
/// 16, 32 and 64 measure alike; docs/PERFORMANCE_LOG.md).
constexpr size_t kMinParallelPairs = 32;
/// Smallest block of a parallel loop (items).
constexpr size_t kMinBlockItems = 8;
/// Fewer bodies than this are integrated and derived by the calling thread alone.
constexpr size_t kMinParallelBodies = 256;

/// Calls run(first, last) over [0, count) in blocks on the pool, or at once on this thread when
/// there is no pool, `serial` asks for it or there are few items. WorkerPool::kBlocksPerThread per
/// thread, in order: each thread starts on its own run of them (the caller the first part of
/// every loop, a worker the next, worker_pool.h) and takes the others' last blocks when its own
/// are done. Bodies and pairs are listed by index, so each thread keeps working on mostly the
/// same bodies from stage to stage and colour to colour, and their cache lines stay in its core
/// (on this project's two-core machine a line moving between cores costs ~170 ns; with four
/// chunks per thread handed out as they came spheres1000 at 2 threads took 25.5 ms/frame
/// against 18-20 ms with one chunk per thread, docs/PERFORMANCE_LOG.md), while the stealing evens
/// out chunks of unequal cost (the floor's and walls' pairs, listed first, against the pile's).
template <class Run>
void forChunks(WorkerPool* pool, size_t count, bool serial, const Run& run, size_t minItems = kMinParallelItems) {
    if (serial || pool == nullptr || count < minItems) {
        run(size_t{0}, count);
        return;
    }
    const auto blocks = static_cast<size_t>(pool->blocksFor(count, kMinBlockItems));
    pool->parallelFor(static_cast<int>(blocks), [&](int block) {
        run(count * static_cast<size_t>(block) / blocks, count * static_cast<size_t>(block + 1) / blocks);
    });
}

/// Solves the colours of `touching` (the overflow aside) one after another, `solve(pairs)` for
/// each. With a pool, thread t solves the pairs of every colour from index firstPair[t] to
/// before firstPair[t + 1] (a colour lists its pairs by index), and the threads wait for one
/// another between colours (WorkerPool::forEachThread): each thread meets the same bodies and
/// pairs colour after colour, pass after pass, and their cache lines stay in its core. Blocks
/// handed out as they came moved them between the cores (docs/PERFORMANCE_LOG.md). A colour of
/// fewer than kMinParallelPairs is thread 0's alone. With more threads than cores, where a
/// barrier would wait for a thread to get a core, each colour is handed out in blocks as before.
template <class Solve>
void solveColours(WorkerPool* pool, const ColourGroups& touching, std::span<const uint32_t> firstPair,
                  const Solve& solve) {
    constexpr int kOverflow = ColourGroups::kOverflowGroup;
    if (pool == nullptr || !pool->threadsFitCores()) {
        for (int g = 0; g < kOverflow; ++g) {
            const std::span<const uint32_t> pairs = touching[g];
            forChunks(pool, pairs.size(), false, [&](size_t first, size_t last) {
                solve(pairs.subspan(first, last - first));
            }, kMinParallelPairs);
        }
        return;
    }
    pool->forEachThread([&](int thread) {
        const auto t = static_cast<size_t>(thread);
        uint32_t passed = 0;
        bool aloneBefore = false;  // thread 0 solved small colours: the next shared one waits
        for (int g = 0; g < kOverflow; ++g) {
            const std::span<const uint32_t> pairs = touching[g];
            if (pairs.empty()) continue;
            if (pairs.size() < kMinParallelPairs) {
                if (thread == 0) solve(pairs);
                aloneBefore = true;
                continue;
            }
            if (aloneBefore) pool->barrier(passed);
            aloneBefore = false;
            // Both ends from the whole colour, so that thread t's end is thread t + 1's start.
            const auto first = std::lower_bound(pairs.begin(), pairs.end(), firstPair[t]);
            const auto last = std::lower_bound(pairs.begin(), pairs.end(), firstPair[t + 1]);
            solve(pairs.subspan(static_cast<size_t>(first - pairs.begin()), static_cast<size_t>(last - first)));
            pool->barrier(passed);
        }
    });
}

}  // namespace

bool World::colouredSolveActive() const {
    return settings_.solver == SolverType::GaussSeidel && (settings_.threads > 1 || settings_.colouredSolve);
}

WorkerPool* World::workerPool() {
    const int threads = std::clamp(settings_.threads, 1, 64);
    if (threads == 1) return nullptr;
    if (!pool_ || pool_->threads() != threads) pool_ = std::make_unique<WorkerPool>(threads);
    return pool_.get();
}

void World::visitBodyRanges(BodyRangeTask task, const void* context) {
    const size_t count = sleepFlags_ ? awakeBodies_.size() : bodies_.size();
    WorkerPool* const pool = workerPool();
    if (pool == nullptr || count < kMinParallelBodies) {
        task(context, *this, 0, count);
        return;
    }
    // In blocks, each thread starting on its own run of them, as forChunks.
    const auto blocks = static_cast<size_t>(pool->blocksFor(count, kMinBlockItems));
    pool->parallelFor(static_cast<int>(blocks), [&](int block) {
        task(context, *this, count * static_cast<size_t>(block) / blocks, count * static_cast<size_t>(block + 1) / blocks);
    });
}

void World::colourConstraints() {
    if (!coloured_) coloured_ = std::make_unique<ColouredSolve>();
    ColouredSolve& state = *coloured_;
    // Joints first, then the pairs, each in its own colouring: joints are solved before contacts.
    state.colouring.begin(bodies_.size());
    state.jointColours.resize(joints_.size());
    for (size_t j = 0; j < joints_.size(); ++j) {
        const Joint& joint = joints_[j];
        state.jointColours[j] =
            joint.alive ? state.colouring.assign(joint.body0, bodies_[joint.body0].isDynamic(), joint.body1,
                                                 bodies_[joint.body1].isDynamic())
                        : ColourGroups::kSkip;
    }
    state.joints.groupAll(joints_.size(), state.jointColours.data());
    state.colouring.begin(bodies_.size());
    state.pairColours.resize(contactPairs_.size());
    for (size_t p = 0; p < contactPairs_.size(); ++p) {
        const ContactPair& pair = contactPairs_[p];
        state.pairColours[p] = state.colouring.assign(pair.body0, bodies_[pair.body0].isDynamic(), pair.body1,
                                                      bodies_[pair.body1].isDynamic());
    }
}

void World::groupTouchingPairs() {
    // The parallel narrowphase groups them as it lists them (world_contacts.cpp).
    if (coloured_->touchingGrouped)
        coloured_->touchingGrouped = false;
    else
        coloured_->touching.group(touchingPairs_, coloured_->pairColours.data());
    coloured_->overflow.plan(coloured_->touching[ColourGroups::kOverflowGroup], contactPairs_, bodies_);
    // Each thread's share of the colours: an equal part of the touching pairs, which are listed
    // by index (solveColours).
    std::vector<uint32_t>& firstPair = coloured_->threadFirstPair;
    const WorkerPool* const pool = workerPool();
    const size_t threads = pool != nullptr ? static_cast<size_t>(pool->threads()) : 1;
    const size_t touching = touchingPairs_.size();
    firstPair.resize(threads + 1);
    for (size_t t = 0; t < threads; ++t) firstPair[t] = t == 0 || touching == 0 ? 0u : touchingPairs_[touching * t / threads];
    firstPair[threads] = ~0u;
}

void World::solveColouredPositions(SolverContext& ctx, JointBlockSolver* clusters) {
    const ColouredSolve& state = *coloured_;
    WorkerPool* const pool = workerPool();
    constexpr int kOverflow = ColourGroups::kOverflowGroup;
    // Each chunk solves with its own copy of the context (it counts repairs).
    if (clusters != nullptr) {
        solveJointsInOrder(ctx, clusters);  // a cluster's block solve moves all its bodies
    } else {
        for (int g = 0; g < ColourGroups::kGroups; ++g) {
            const std::span<const uint32_t> joints = state.joints[g];
            forChunks(pool, joints.size(), g == kOverflow, [&](size_t first, size_t last) {
                SolverContext local = ctx;
                for (size_t k = first; k < last; ++k) {
                    Joint& joint = joints_[joints[k]];
                    if (!sleeps(joint)) solveJointPositions(joint, local);
                }
            });
        }
    }
    // A colour's pairs share no moving body: its one-point pairs go into lanes as they come.
    solveColours(pool, state.touching, state.threadFirstPair, [&](std::span<const uint32_t> pairs) {
        SolverContext local = ctx;
        solveIndependentPositions(pairs, contactPairs_, contacts_, local);
    });
    // The overflow's pairs may share bodies: they are solved serially in their schedule.
    solveTouchingPositions(state.overflow, contactPairs_, contacts_, ctx);
}

void World::solveColouredContactVelocities(double h, double gravity) {
    const ColouredSolve& state = *coloured_;
    solveColours(workerPool(), state.touching, state.threadFirstPair, [&](std::span<const uint32_t> pairs) {
        solveIndependentVelocities(pairs, contactPairs_, contacts_, bodies_.data(), h, gravity);
    });
    solveTouchingVelocities(state.overflow, contactPairs_, contacts_, bodies_.data(), h, gravity);
}

}  // namespace substep

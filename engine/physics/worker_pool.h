#pragma once
/// Worker threads for the step's parallel loops (WorldSettings::threads).
///
/// One loop runs at a time, over blocks [0, blocks). The blocks are dealt out in T runs of
/// consecutive blocks, one run per thread (the caller's is the first): each thread takes the
/// blocks of its own run from its front, and when its run is done takes blocks from the backs
/// of the others' runs, one at a time, until none is left (work stealing, as Box2D v3's solver
/// stages do). So each thread mostly visits the same part of every loop, loop after loop (the
/// bodies and pairs are listed by index: their cache lines stay in its core), and a thread that
/// is slower, late or has the dearer items is helped by the others instead of waited for.
/// parallelFor returns when every block is done.
///
/// Which thread runs a block varies from run to run, so a caller makes every block's result
/// depend on the block alone (its own output slots, merged in block order afterwards): the
/// step's output is then the same bytes for every thread count.
///
/// Between loops the workers spin for a while, then sleep on an atomic (a futex), so a pool
/// costs nothing while the solver runs its serial stages for long.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace substep {

class WorkerPool {
public:
    /// A pool of `threads` threads in all: the caller and threads − 1 workers.
    explicit WorkerPool(int threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    /// Threads taking part in a loop, the caller included.
    int threads() const { return static_cast<int>(workers_.size()) + 1; }
    /// Whether every thread can have a core of its own: as many CPUs as threads at least are
    /// open to this process (its affinity mask, on Linux). forEachThread's barriers wait for
    /// every thread, so with more threads than cores each barrier waits for a thread to get a
    /// core back (spheres1000 at 4 threads on 2 cores took 30 ms/frame where blocks handed out
    /// as they come take 11).
    bool threadsFitCores() const { return threads() <= cores_; }

    /// Blocks per thread a loop over many items is cut into: enough that a thread done early
    /// finds blocks to take from the others, few enough that a block's hand-out (an atomic
    /// exchange) is small beside its work.
    static constexpr int kBlocksPerThread = 8;
    /// Blocks for a loop over `count` items: kBlocksPerThread per thread, fewer where a block
    /// would hold under `minItems` items, at least one.
    int blocksFor(size_t count, size_t minItems) const {
        const size_t most = static_cast<size_t>(threads()) * kBlocksPerThread;
        const size_t fit = minItems > 0 ? count / minItems : count;
        return static_cast<int>(std::max<size_t>(1, std::min(most, fit)));
    }

    /// Calls body(block) for every block in [0, blocks), spread over the threads; returns when
    /// all are done. `body` must not throw.
    template <class Body>
    void parallelFor(int blocks, Body&& body) {
        if (blocks <= 0) return;
        if (workers_.empty() || blocks == 1) {
            for (int i = 0; i < blocks; ++i) body(i);
            return;
        }
        if (blocks <= kMaxBlocks) {
            run(blocks, [](void* context, int block) { (*static_cast<Body*>(context))(block); }, &body);
            return;
        }
        // More blocks than a run's counters hold: groups of consecutive blocks.
        auto groups = [&body, blocks](int group) {
            const long long first = static_cast<long long>(group) * blocks / kMaxBlocks;
            const long long last = static_cast<long long>(group + 1) * blocks / kMaxBlocks;
            for (long long i = first; i < last; ++i) body(static_cast<int>(i));
        };
        run(kMaxBlocks, [](void* context, int group) { (*static_cast<decltype(groups)*>(context))(group); },
            &groups);
    }

    /// Calls body(thread) once on every thread of the pool at the same time, thread 0 being the
    /// caller's, none taking another's call; returns when all are done. For loops split the same
    /// way stage after stage: thread t then always visits the same bodies and pairs, and their
    /// cache lines stay in its core (stealing moves them: on a machine where a line takes
    /// ~160 ns from core to core, a pair solved by the thread that did not last write it cost
    /// 75 to 108 ns against 62). Inside, barrier() waits for the other threads. `body` must not
    /// throw, and every thread must call barrier() as often as the others.
    template <class Body>
    void forEachThread(Body&& body) {
        if (workers_.empty()) return body(0);
        arrivals_.store(0, std::memory_order_relaxed);
        pinned_.store(true, std::memory_order_relaxed);
        run(threads(), [](void* context, int thread) { (*static_cast<Body*>(context))(thread); }, &body);
        pinned_.store(false, std::memory_order_relaxed);
    }
    /// Inside forEachThread: returns once every thread has called it as often as this one has;
    /// `passed` counts this thread's calls (zero at the start of the body).
    void barrier(uint32_t& passed);

    /// Most blocks one loop hands out (more are grouped).
    static constexpr int kMaxBlocks = 0xffff;

private:
    using Task = void (*)(void*, int);
    void run(int blocks, Task task, void* context);
    /// Runs blocks of the loop of `epoch` as thread `self` (0: the caller) until none is left.
    void drain(uint32_t epoch, int self);
    void work(int self);

    /// A thread's run of blocks in the current loop: the loop's epoch in the high 32 bits, the
    /// next block from the front in the next 16, the end (one past the next block from the back)
    /// in the low 16. One atomic, so a claim never mixes two loops; a cache line each, so a
    /// thread claiming from its own run does not disturb the others'.
    struct alignas(64) BlockRun {
        std::atomic<uint64_t> state{0};
    };
    /// Claims the front (owner) or back (thief) block of `run` in the loop of `epoch`; −1 when
    /// the run is empty or belongs to another loop.
    static int claimFront(BlockRun& run, uint32_t epoch);
    static int claimBack(BlockRun& run, uint32_t epoch);

    std::vector<std::thread> workers_;
    int cores_ = 1;  ///< CPUs this process may run on, when the pool was made
    std::unique_ptr<BlockRun[]> runs_;  ///< one per thread, the caller's first
    std::atomic<uint32_t> epoch_{0};    ///< the current loop; what idle workers wait on
    std::atomic<int> remaining_{0};     ///< blocks of the current loop not yet finished
    std::atomic<Task> task_{nullptr};
    std::atomic<void*> context_{nullptr};
    std::atomic<bool> stop_{false};
    /// The current loop is forEachThread's: a thread runs its own block alone. Written before
    /// the loop's epoch is published, so a thread that claims a block reads it right.
    std::atomic<bool> pinned_{false};
    /// Calls of barrier() in the current forEachThread, all threads together.
    alignas(64) std::atomic<uint32_t> arrivals_{0};
};

}  // namespace substep

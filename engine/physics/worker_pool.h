#pragma once
/// Worker threads for the step's parallel loops (WorldSettings::threads).
///
/// One loop runs at a time: its chunks are claimed one by one by the calling thread and the
/// workers, and parallelFor returns when every chunk is done. Which thread runs a chunk varies
/// from run to run, so a caller makes every chunk's result depend on the chunk alone (its own
/// output slots, merged in chunk order afterwards): the step's output is then the same bytes for
/// every thread count.
///
/// Between loops the workers spin briefly, then sleep on an atomic (a futex), so a pool costs
/// nothing while the solver runs its serial stages for long.

#include <atomic>
#include <cstdint>
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

    /// Calls body(chunk) for every chunk in [0, chunks), spread over the threads; returns when
    /// all are done. `body` must not throw.
    template <class Body>
    void parallelFor(int chunks, Body&& body) {
        if (chunks <= 0) return;
        if (workers_.empty() || chunks == 1) {
            for (int i = 0; i < chunks; ++i) body(i);
            return;
        }
        if (chunks <= kMaxChunks) {
            run(chunks, [](void* context, int chunk) { (*static_cast<Body*>(context))(chunk); }, &body);
            return;
        }
        // More chunks than the cursor counts: groups of consecutive chunks.
        auto groups = [&body, chunks](int group) {
            const long long first = static_cast<long long>(group) * chunks / kMaxChunks;
            const long long last = static_cast<long long>(group + 1) * chunks / kMaxChunks;
            for (long long i = first; i < last; ++i) body(static_cast<int>(i));
        };
        run(kMaxChunks, [](void* context, int group) { (*static_cast<decltype(groups)*>(context))(group); },
            &groups);
    }

    /// Most chunks one loop hands out (more are grouped).
    static constexpr int kMaxChunks = 0xffff;

private:
    using Task = void (*)(void*, int);
    void run(int chunks, Task task, void* context);
    /// Claims and runs chunks of the loop of `epoch` until none is left.
    void drain(uint32_t epoch);
    void work();

    std::vector<std::thread> workers_;
    /// The loop being run: its epoch in the high 32 bits, its chunk count in the next 16, the
    /// next chunk to claim in the low 16 (one atomic, so a claim never mixes two loops).
    std::atomic<uint64_t> cursor_{0};
    std::atomic<uint32_t> epoch_{0};  ///< what idle workers wait on
    std::atomic<int> remaining_{0};   ///< chunks of the current loop not yet finished
    std::atomic<Task> task_{nullptr};
    std::atomic<void*> context_{nullptr};
    std::atomic<bool> stop_{false};
};

}  // namespace substep

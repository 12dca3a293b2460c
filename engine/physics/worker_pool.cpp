#include "physics/worker_pool.h"

#include <algorithm>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace substep {
namespace {

/// Polls before a thread sleeps (some tens of µs): long enough for a loop's hand-over, short
/// enough not to steal a busy machine's cores from other work.
constexpr int kSpins = 2000;

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

}  // namespace

WorkerPool::WorkerPool(int threads) {
    const int workers = std::max(threads, 1) - 1;
    workers_.reserve(static_cast<size_t>(workers));
    for (int i = 0; i < workers; ++i) workers_.emplace_back([this] { work(); });
}

WorkerPool::~WorkerPool() {
    stop_.store(true, std::memory_order_release);
    epoch_.fetch_add(1, std::memory_order_acq_rel);
    epoch_.notify_all();
    for (std::thread& worker : workers_) worker.join();
}

void WorkerPool::run(int chunks, Task task, void* context) {
    // The task is published before the cursor that names its epoch; a worker that claims a
    // chunk of this epoch has acquired the cursor and so reads this task.
    const uint32_t epoch = epoch_.load(std::memory_order_relaxed) + 1;
    task_.store(task, std::memory_order_relaxed);
    context_.store(context, std::memory_order_relaxed);
    remaining_.store(chunks, std::memory_order_relaxed);
    cursor_.store(uint64_t{epoch} << 32 | uint64_t(chunks) << 16, std::memory_order_release);
    epoch_.store(epoch, std::memory_order_release);
    epoch_.notify_all();
    drain(epoch);
    // Wait for the chunks the workers claimed: spin a while, then sleep until the last one.
    for (int spin = 0; spin < kSpins; ++spin) {
        if (remaining_.load(std::memory_order_acquire) == 0) return;
        relax();
    }
    for (int left = remaining_.load(std::memory_order_acquire); left != 0;
         left = remaining_.load(std::memory_order_acquire))
        remaining_.wait(left, std::memory_order_acquire);
}

void WorkerPool::drain(uint32_t epoch) {
    for (;;) {
        uint64_t cursor = cursor_.load(std::memory_order_acquire);
        int chunk;
        // Claim the next chunk of this epoch's loop; a later loop's cursor means this one is over.
        do {
            if (static_cast<uint32_t>(cursor >> 32) != epoch) return;
            chunk = static_cast<int>(cursor & 0xffffu);
            if (chunk >= static_cast<int>((cursor >> 16) & 0xffffu)) return;
        } while (!cursor_.compare_exchange_weak(cursor, cursor + 1, std::memory_order_acq_rel,
                                                std::memory_order_acquire));
        task_.load(std::memory_order_relaxed)(context_.load(std::memory_order_relaxed), chunk);
        if (remaining_.fetch_sub(1, std::memory_order_acq_rel) == 1) remaining_.notify_all();
    }
}

void WorkerPool::work() {
    uint32_t seen = 0;
    for (;;) {
        uint32_t epoch = epoch_.load(std::memory_order_acquire);
        for (int spin = 0; spin < kSpins && epoch == seen; ++spin) {
            relax();
            epoch = epoch_.load(std::memory_order_acquire);
        }
        while (epoch == seen) {
            epoch_.wait(seen, std::memory_order_acquire);
            epoch = epoch_.load(std::memory_order_acquire);
        }
        seen = epoch;
        if (stop_.load(std::memory_order_acquire)) return;
        drain(epoch);
    }
}

}  // namespace substep

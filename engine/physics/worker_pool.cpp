#include "physics/worker_pool.h"

#include <algorithm>

#if defined(__linux__)
#include <sched.h>
#endif

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

constexpr uint64_t kFrontUnit = uint64_t{1} << 16;

uint64_t runState(uint32_t epoch, int front, int end) {
    return uint64_t{epoch} << 32 | uint64_t(front) << 16 | uint64_t(end);
}

/// CPUs this process may run on: its affinity mask's (taskset, a container's limit) on Linux,
/// else the machine's.
int availableCores() {
#if defined(__linux__)
    cpu_set_t mask;
    if (sched_getaffinity(0, sizeof(mask), &mask) == 0) return std::max(CPU_COUNT(&mask), 1);
#endif
    return std::max(static_cast<int>(std::thread::hardware_concurrency()), 1);
}

}  // namespace

WorkerPool::WorkerPool(int threads) : cores_(availableCores()) {
    const int workers = std::max(threads, 1) - 1;
    runs_ = std::make_unique<BlockRun[]>(static_cast<size_t>(workers) + 1);
    workers_.reserve(static_cast<size_t>(workers));
    for (int i = 0; i < workers; ++i) workers_.emplace_back([this, i] { work(i + 1); });
}

WorkerPool::~WorkerPool() {
    stop_.store(true, std::memory_order_release);
    epoch_.fetch_add(1, std::memory_order_acq_rel);
    epoch_.notify_all();
    for (std::thread& worker : workers_) worker.join();
}

int WorkerPool::claimFront(BlockRun& run, uint32_t epoch) {
    uint64_t state = run.state.load(std::memory_order_acquire);
    int front;
    do {
        if (static_cast<uint32_t>(state >> 32) != epoch) return -1;
        front = static_cast<int>((state >> 16) & 0xffffu);
        if (front >= static_cast<int>(state & 0xffffu)) return -1;
    } while (!run.state.compare_exchange_weak(state, state + kFrontUnit, std::memory_order_acq_rel,
                                              std::memory_order_acquire));
    return front;
}

int WorkerPool::claimBack(BlockRun& run, uint32_t epoch) {
    uint64_t state = run.state.load(std::memory_order_acquire);
    int end;
    do {
        if (static_cast<uint32_t>(state >> 32) != epoch) return -1;
        end = static_cast<int>(state & 0xffffu);
        if (static_cast<int>((state >> 16) & 0xffffu) >= end) return -1;
    } while (!run.state.compare_exchange_weak(state, state - 1, std::memory_order_acq_rel,
                                              std::memory_order_acquire));
    return end - 1;
}

void WorkerPool::run(int blocks, Task task, void* context) {
    // The task is published before the runs that name its epoch; a thread that claims a block
    // of this epoch has acquired its run and so reads this task, which stays until the loop
    // ends: the loop cannot end before that claimed block is done (remaining_).
    const uint32_t epoch = epoch_.load(std::memory_order_relaxed) + 1;
    task_.store(task, std::memory_order_relaxed);
    context_.store(context, std::memory_order_relaxed);
    remaining_.store(blocks, std::memory_order_relaxed);
    const int threads = this->threads();
    for (int t = 0; t < threads; ++t)
        runs_[static_cast<size_t>(t)].state.store(
            runState(epoch, static_cast<int>(static_cast<long long>(blocks) * t / threads),
                     static_cast<int>(static_cast<long long>(blocks) * (t + 1) / threads)),
            std::memory_order_release);
    epoch_.store(epoch, std::memory_order_release);
    epoch_.notify_all();
    drain(epoch, 0);
    // Wait for the blocks the workers claimed: spin a while, then sleep until the last one.
    for (int spin = 0; spin < kSpins; ++spin) {
        if (remaining_.load(std::memory_order_acquire) == 0) return;
        relax();
    }
    for (int left = remaining_.load(std::memory_order_acquire); left != 0;
         left = remaining_.load(std::memory_order_acquire))
        remaining_.wait(left, std::memory_order_acquire);
}

void WorkerPool::drain(uint32_t epoch, int self) {
    const auto execute = [&](int block) {
        task_.load(std::memory_order_relaxed)(context_.load(std::memory_order_relaxed), block);
        if (remaining_.fetch_sub(1, std::memory_order_acq_rel) == 1) remaining_.notify_all();
    };
    // Its own run from the front, then the others' from their backs, the next thread's first.
    for (int block = claimFront(runs_[static_cast<size_t>(self)], epoch); block >= 0;
         block = claimFront(runs_[static_cast<size_t>(self)], epoch))
        execute(block);
    const int threads = this->threads();
    if (pinned_.load(std::memory_order_relaxed)) return;  // forEachThread: its own block only
    for (int k = 1; k < threads; ++k) {
        BlockRun& other = runs_[static_cast<size_t>((self + k) % threads)];
        for (int block = claimBack(other, epoch); block >= 0; block = claimBack(other, epoch)) execute(block);
    }
}

void WorkerPool::barrier(uint32_t& passed) {
    ++passed;
    const uint32_t all = passed * static_cast<uint32_t>(threads());
    arrivals_.fetch_add(1, std::memory_order_acq_rel);
    // Spin, as the others are a colour's work away; yield after a while, in case there are more
    // threads than cores and the one waited for needs this core.
    for (int spin = 0; arrivals_.load(std::memory_order_acquire) < all; ++spin) {
        if (spin < kSpins)
            relax();
        else
            std::this_thread::yield();
    }
}

void WorkerPool::work(int self) {
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
        drain(epoch, self);
    }
}

}  // namespace substep

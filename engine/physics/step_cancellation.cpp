#include "physics/step_cancellation.h"

#include <atomic>

namespace substep {

namespace {

// Relaxed order: the flag carries no data, and a step that sees it one pair late loses nothing.
std::atomic<bool> gCancelled{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler may only touch lock-free atomics");

}  // namespace

void requestStepCancellation() noexcept {
    gCancelled.store(true, std::memory_order_relaxed);
}

void clearStepCancellation() noexcept {
    gCancelled.store(false, std::memory_order_relaxed);
}

bool stepCancellationRequested() noexcept {
    return gCancelled.load(std::memory_order_relaxed);
}

}  // namespace substep

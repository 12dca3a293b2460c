#pragma once
/// A cooperative stop for long world steps. A program that catches SIGINT or SIGTERM calls
/// requestStepCancellation() from its handler; World::step then returns at the next substep or
/// after the current contact pair instead of finishing a frame that may take minutes (thousands
/// of bodies at one point). The world is left part-way through its step: the caller is expected
/// to discard it and exit.

namespace substep {

/// Asks every running World::step to return early. Async-signal-safe (a lock-free atomic).
void requestStepCancellation() noexcept;
/// Lets steps run to the end again.
void clearStepCancellation() noexcept;
/// True between a request and the next clear.
bool stepCancellationRequested() noexcept;

}  // namespace substep

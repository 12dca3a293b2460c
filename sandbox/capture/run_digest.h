#pragma once
/// A digest of a whole captured run for a one-line determinism check (as Box2D's determinism
/// test hashes a shared scene): FNV-1a (64 bits) over the bit patterns of every value of the
/// state at every frame from 0 to the last captured one. Same build, scene and settings: the
/// same line; any change anywhere in the run, even between captured frames, changes it.

#include "capture/capture_state.h"

#include <cstdint>
#include <string>

namespace substep::capture {

class RunDigest {
  public:
    /// Adds one frame's state (call for every frame in order).
    void add(const CaptureState& state);

    /// The digest file's line: `fnv1a64 0123456789abcdef frames 0-120`, with a newline.
    std::string line() const;

  private:
    void addValue(double value);

    std::uint64_t hash_ = 14695981039346656037ull;  // FNV-1a 64 offset basis
    long long firstFrame_ = -1;
    long long lastFrame_ = -1;
};

}  // namespace substep::capture

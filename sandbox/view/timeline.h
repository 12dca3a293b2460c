#pragma once
/// The viewer's timeline: the last seconds of a run's states, one LiveSceneSnapshot per frame,
/// for pausing, scrubbing back and forth and resuming from any frame (the later history is then
/// dropped). A restored snapshot repeats the original run byte for byte (live_scene.h), so
/// resuming from a frame replays what the run did from there until something is changed.
/// Knows nothing of windows; ViewSession records and restores through it.

#include "scenes/live_scene.h"

#include <cstddef>
#include <deque>

namespace substep::view {

class Timeline {
  public:
    /// Keeps at most `seconds` of frames of `dt`, and fewer when that many snapshots would take
    /// more than `byteBudget` (WorldSnapshot::bytes).
    Timeline(double seconds = 10.0, std::size_t byteBudget = std::size_t{256} << 20)
        : seconds_(seconds), byteBudget_(byteBudget) {}

    /// Forgets every frame (a new build, or an edit the stored frames did not see).
    void clear();
    /// Adds the state after a frame. When the cursor stands on an earlier frame, the frames
    /// after it are dropped first: the run resumes from there. The oldest frames go once the
    /// history is full. `dt` is the scene's frame length.
    void record(LiveSceneSnapshot snapshot, double dt);

    bool empty() const { return frames_.empty(); }
    /// Frames kept.
    std::size_t size() const { return frames_.size(); }
    /// How many frames the history holds at most (known after the first record).
    std::size_t capacity() const { return capacity_; }
    /// The frame numbers of the oldest and newest states kept.
    long long firstFrame() const { return frames_.empty() ? 0 : frames_.front().frame; }
    long long lastFrame() const { return frames_.empty() ? 0 : frames_.back().frame; }
    /// The frame shown: the newest unless scrubbed back.
    long long cursorFrame() const { return frames_.empty() ? 0 : frames_[cursor_].frame; }
    /// Whether the shown frame is an earlier one than the newest.
    bool scrubbed() const { return !frames_.empty() && cursor_ + 1 < frames_.size(); }

    /// Moves the cursor to `frame` (clamped to the kept range) and returns its snapshot, or
    /// nullptr when nothing is kept.
    const LiveSceneSnapshot* seek(long long frame);

  private:
    double seconds_;
    std::size_t byteBudget_;
    std::size_t capacity_ = 0;
    std::deque<LiveSceneSnapshot> frames_;
    std::size_t cursor_ = 0;
};

}  // namespace substep::view

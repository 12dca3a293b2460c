#pragma once
/// Honest frame timing for the panel: frames per second from the whole frame (events, physics,
/// drawing and the buffer swap, where a software rasteriser does most of its work), and the
/// real-time factor, simulated seconds per wall second over the last second, so a scene that
/// cannot keep up says so instead of silently playing slow.

#include <cstddef>
#include <vector>

namespace substep::view {

/// What one drawn frame cost (ms) and how much simulated time it advanced (s).
struct FrameSample {
    double frameMs = 0.0;    ///< wall time from the start of this frame to the start of the next
    double physicsMs = 0.0;  ///< the steps taken in it
    double renderMs = 0.0;   ///< the renderer's and the panel's draw calls (CPU side)
    double swapMs = 0.0;     ///< the buffer swap: where queued drawing is finished
    double simulatedSeconds = 0.0;
    bool playing = false;
};

class FrameStats {
  public:
    /// Averages over the frames of the last `windowSeconds` of wall time.
    explicit FrameStats(double windowSeconds = 1.0) : windowSeconds_(windowSeconds) {}

    void record(const FrameSample& sample);
    /// Forgets the frames so far (after a pause, a load, a restart).
    void clear();

    /// Means over the window (0 with no frame yet).
    double fps() const;
    double frameMs() const;
    double physicsMs() const;
    double renderMs() const;
    double swapMs() const;
    /// Simulated seconds per wall second over the window's playing frames; -1 when nothing
    /// played in it.
    double realTimeFactor() const;
    /// The last frame recorded.
    const FrameSample& last() const { return last_; }

  private:
    double mean(double FrameSample::*member) const;

    double windowSeconds_;
    std::vector<FrameSample> frames_;  ///< oldest first, within the window
    FrameSample last_;
};

/// True when a run playing at `timeScale` keeps less than 95 % of that pace: the panel then says
/// the scene runs slower than real time and why.
bool slowerThanRealTime(double realTimeFactor, double timeScale);

}  // namespace substep::view

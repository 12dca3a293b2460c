#include "view/frame_stats.h"

#include <algorithm>

namespace substep::view {

void FrameStats::record(const FrameSample& sample) {
    last_ = sample;
    frames_.push_back(sample);
    // Drop the oldest frames beyond the window, keeping the newest even when it alone is longer.
    double total = 0.0;
    std::size_t keep = 0;
    for (auto it = frames_.rbegin(); it != frames_.rend(); ++it) {
        if (keep > 0 && total >= windowSeconds_ * 1000.0) break;
        total += it->frameMs;
        ++keep;
    }
    frames_.erase(frames_.begin(), frames_.end() - static_cast<std::ptrdiff_t>(keep));
}

void FrameStats::clear() {
    frames_.clear();
    last_ = {};
}

double FrameStats::mean(double FrameSample::*member) const {
    if (frames_.empty()) return 0.0;
    double sum = 0.0;
    for (const FrameSample& frame : frames_) sum += frame.*member;
    return sum / static_cast<double>(frames_.size());
}

double FrameStats::fps() const {
    const double ms = frameMs();
    return ms > 0.0 ? 1000.0 / ms : 0.0;
}

double FrameStats::frameMs() const { return mean(&FrameSample::frameMs); }
double FrameStats::physicsMs() const { return mean(&FrameSample::physicsMs); }
double FrameStats::renderMs() const { return mean(&FrameSample::renderMs); }
double FrameStats::swapMs() const { return mean(&FrameSample::swapMs); }

double FrameStats::realTimeFactor() const {
    double simulated = 0.0;
    double wallMs = 0.0;
    for (const FrameSample& frame : frames_) {
        if (!frame.playing) continue;
        simulated += frame.simulatedSeconds;
        wallMs += frame.frameMs;
    }
    return wallMs > 0.0 ? simulated / (wallMs / 1000.0) : -1.0;
}

bool slowerThanRealTime(double realTimeFactor, double timeScale) {
    return realTimeFactor >= 0.0 && realTimeFactor < 0.95 * timeScale;
}

}  // namespace substep::view

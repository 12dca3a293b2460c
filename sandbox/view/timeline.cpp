#include "view/timeline.h"

#include <algorithm>
#include <cmath>

namespace substep::view {

void Timeline::clear() {
    frames_.clear();
    cursor_ = 0;
    capacity_ = 0;
}

void Timeline::record(LiveSceneSnapshot snapshot, double dt) {
    if (capacity_ == 0) {
        // Sized once per history from the first frame's snapshot: a scene's storage does not
        // grow while it runs.
        const double byTime = dt > 0.0 ? std::ceil(seconds_ / dt) : 1.0;
        const double byMemory = static_cast<double>(byteBudget_) /
                                static_cast<double>(std::max<std::size_t>(snapshot.world.bytes(), 1));
        capacity_ = static_cast<std::size_t>(std::clamp(std::min(byTime, byMemory), 2.0, 1e7));
    }
    if (scrubbed()) frames_.erase(frames_.begin() + static_cast<std::ptrdiff_t>(cursor_) + 1, frames_.end());
    frames_.push_back(std::move(snapshot));
    while (frames_.size() > capacity_) frames_.pop_front();
    cursor_ = frames_.size() - 1;
}

const LiveSceneSnapshot* Timeline::seek(long long frame) {
    if (frames_.empty()) return nullptr;
    const long long clamped = std::clamp(frame, firstFrame(), lastFrame());
    // Frames are consecutive: the index is the offset from the oldest.
    cursor_ = static_cast<std::size_t>(clamped - firstFrame());
    return &frames_[cursor_];
}

}  // namespace substep::view

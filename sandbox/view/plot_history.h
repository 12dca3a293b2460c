#pragma once
/// A fixed number of the latest samples of one quantity, oldest first, for ImGui::PlotLines
/// (which draws a contiguous float array starting at an offset, so a ring buffer fits as is).

#include <algorithm>
#include <cstddef>
#include <vector>

namespace substep::view {

class PlotHistory {
  public:
    explicit PlotHistory(std::size_t capacity) : values_(capacity, 0.0f) {}

    void push(float value) {
        values_[next_] = value;
        next_ = (next_ + 1) % values_.size();
        count_ = std::min(count_ + 1, values_.size());
        latest_ = value;
    }
    void clear() {
        std::fill(values_.begin(), values_.end(), 0.0f);
        next_ = 0;
        count_ = 0;
        latest_ = 0.0f;
    }

    /// Forgets the `n` newest samples (all when there are fewer): a run resumed from an earlier
    /// frame replaces them.
    void dropNewest(std::size_t n) {
        n = std::min(n, count_);
        next_ = (next_ + values_.size() - n) % values_.size();
        count_ -= n;
        latest_ = count_ > 0 ? values_[(next_ + values_.size() - 1) % values_.size()] : 0.0f;
    }
    /// Sample `i` of the count() held, counted from the oldest.
    float at(std::size_t i) const { return values_[(next_ + values_.size() - count_ + i) % values_.size()]; }

    /// The buffer and the index of its oldest sample, as PlotLines takes them. Before the buffer
    /// is full the unused slots read 0.
    const float* data() const { return values_.data(); }
    int size() const { return static_cast<int>(values_.size()); }
    int offset() const { return static_cast<int>(next_); }
    std::size_t count() const { return count_; }
    float latest() const { return latest_; }

    /// Smallest and largest of the samples held, for the plot's scale ({0, 0} when empty).
    std::pair<float, float> range() const {
        if (count_ == 0) return {0.0f, 0.0f};
        float lowest = latest_;
        float highest = latest_;
        for (std::size_t i = 0; i < count_; ++i) {
            const float value = values_[(next_ + values_.size() - 1 - i) % values_.size()];
            lowest = std::min(lowest, value);
            highest = std::max(highest, value);
        }
        return {lowest, highest};
    }

  private:
    std::vector<float> values_;
    std::size_t next_ = 0;
    std::size_t count_ = 0;
    float latest_ = 0.0f;
};

}  // namespace substep::view

#include "physics/collision/static_bvh.h"

#include <algorithm>

namespace substep {

void StaticBvh::build(const std::vector<Aabb>& boxes) {
    nodes_.clear();
    items_.clear();
    itemBoxes_.clear();
    if (boxes.empty()) return;
    std::vector<Vec3> centres(boxes.size());
    items_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        centres[i] = boxes[i].center();
        items_[i] = static_cast<int32_t>(i);
    }
    nodes_.reserve(2 * boxes.size() / kBvhLeafSize + 1);
    buildRange(boxes, centres, 0, static_cast<int>(boxes.size()));
    itemBoxes_.reserve(items_.size());
    for (int32_t item : items_)
        itemBoxes_.push_back(boxes[item]);
}

int StaticBvh::buildRange(const std::vector<Aabb>& boxes, std::vector<Vec3>& centres, int begin,
                          int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Aabb box;
    Aabb centreBox;
    for (int i = begin; i < end; ++i) {
        box.grow(boxes[items_[i]]);
        centreBox.grow(centres[items_[i]]);
    }
    nodes_[index].box = box;
    if (end - begin <= kBvhLeafSize) {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    // Median split along the widest spread of centres: balanced, so the depth stays bounded.
    int axis = 0;
    centreBox.extents().maxCoeff(&axis);
    const int middle = begin + (end - begin) / 2;
    std::nth_element(items_.begin() + begin, items_.begin() + middle, items_.begin() + end,
                     [&](int32_t a, int32_t b) { return centres[a][axis] < centres[b][axis]; });
    buildRange(boxes, centres, begin, middle);  // left child at index + 1
    const int right = buildRange(boxes, centres, middle, end);
    nodes_[index].first = right;
    nodes_[index].count = 0;
    return index;
}

}  // namespace substep

#pragma once
/// A bounding-volume hierarchy over a fixed set of boxes (spline segments, mesh triangles),
/// built once and queried many times. Nodes live in one array in depth-first order, so a query
/// walks memory forwards and needs no allocation.

#include "physics/collision/aabb.h"

#include <cstdint>
#include <vector>

namespace substep {

class StaticBvh {
  public:
    /// Builds the tree over `boxes`; item i of a query is boxes[i]. Empty input gives an empty
    /// tree.
    void build(const std::vector<Aabb>& boxes);

    /// Calls visit(int item) for exactly the items whose boxes overlap `box`.
    template <class Visitor>
    void query(const Aabb& box, Visitor&& visit) const;

    bool empty() const { return nodes_.empty(); }
    /// Bounds of everything (empty box for an empty tree).
    Aabb bounds() const { return nodes_.empty() ? Aabb{} : nodes_[0].box; }

  private:
    /// Aabb::overlaps written out: scalar tests that stop at the first separated axis.
    static bool overlap(const Aabb& a, const Aabb& b) {
        return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() &&
               b.min.y() <= a.max.y() && a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
    }
    struct Node {
        Aabb box;
        int32_t first = 0;  ///< leaf: first entry in items_; inner: index of the right child
        int32_t count = 0;  ///< leaf: number of items (> 0); inner: 0 (left child follows)
    };
    int buildRange(const std::vector<Aabb>& boxes, std::vector<Vec3>& centres, int begin, int end);

    std::vector<Node> nodes_;
    std::vector<int32_t> items_;
    std::vector<Aabb> itemBoxes_;  ///< the box of items_[i], stored alongside for the leaf test
};

/// Leaves hold up to this many items; a deeper tree costs more node tests than it saves.
inline constexpr int kBvhLeafSize = 2;
/// Median splits keep the depth near log2(n / kBvhLeafSize) + 1; 64 covers any array in memory.
inline constexpr int kBvhMaxDepth = 64;

template <class Visitor>
void StaticBvh::query(const Aabb& box, Visitor&& visit) const {
    if (nodes_.empty()) return;
    int stack[kBvhMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const int index = stack[--top];
        const Node& node = nodes_[index];
        if (!overlap(node.box, box)) continue;
        if (node.count > 0) {
            for (int i = node.first; i < node.first + node.count; ++i) {
                if (overlap(itemBoxes_[i], box)) visit(static_cast<int>(items_[i]));
            }
        } else {
            stack[top++] = node.first;  // right child
            stack[top++] = index + 1;   // left child, visited first
        }
    }
}

}  // namespace substep

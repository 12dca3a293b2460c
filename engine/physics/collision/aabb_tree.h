#pragma once
/// A dynamic AABB tree (bounding volume hierarchy) over "proxies": leaves that hold a box and a
/// user value. Leaves store fattened boxes so that a proxy moving a little inside its fat box
/// costs nothing; one that leaves it is taken out and inserted again. Insertion descends by the
/// surface-area cost of the merged boxes, and on the path back to the root each node may swap a
/// child with a grandchild where that shrinks the total surface area (rotations by area rather
/// than by height: queries cost what the boxes' areas cost).
///
/// All nodes live in one vector with a free list; proxy ids are node indices and stay valid
/// until destroyed. Queries use a stack kept by the tree, so one tree must not be queried from
/// two threads at once.

#include "physics/collision/aabb.h"

#include <cstdint>
#include <vector>

namespace substep {

class AabbTree {
  public:
    static constexpr int32_t kNull = -1;

    /// `fatMargin`: how far a leaf's box reaches beyond the box it was given (m).
    explicit AabbTree(double fatMargin = 0.05) : fatMargin_(fatMargin) {}

    /// Adds a leaf holding `box` grown by the fat margin; returns its proxy id.
    int32_t createProxy(const Aabb& box, uint32_t userData);
    /// Removes a leaf; its id may be handed out again.
    void destroyProxy(int32_t proxy);
    /// Keeps the leaf when its fat box still contains `box` and is not far too large for it
    /// (a body that slowed down gets a tight box back); otherwise re-inserts it with a fresh fat
    /// box. Returns whether the tree changed.
    bool moveProxy(int32_t proxy, const Aabb& box);
    /// Removes every proxy.
    void clear();

    const Aabb& fatBox(int32_t proxy) const { return nodes_[proxy].box; }
    uint32_t userData(int32_t proxy) const { return nodes_[proxy].userData; }
    int proxyCount() const { return proxyCount_; }
    /// Height of the root (0 for a single leaf, -1 when empty).
    int height() const { return root_ == kNull ? -1 : nodes_[root_].height; }
    double fatMargin() const { return fatMargin_; }

    /// Calls onLeaf(proxy) for every leaf whose fat box overlaps `box`, in a fixed order.
    template <class OnLeaf>
    void query(const Aabb& box, OnLeaf&& onLeaf) const;

    /// Checks the structure: parent links, heights, boxes enclosing their children, free-list
    /// size. For tests; returns an empty string when sound, else what is wrong.
    const char* validate() const;

  private:
    struct Node {
        Aabb box;
        int32_t parent = kNull;  ///< next free node while on the free list
        int32_t child0 = kNull;
        int32_t child1 = kNull;
        int32_t height = -1;  ///< 0 for leaves, -1 for free nodes
        uint32_t userData = 0;
        bool isLeaf() const { return child0 == kNull; }
    };

    int32_t allocateNode();
    void freeNode(int32_t node);
    void insertLeaf(int32_t leaf);
    void removeLeaf(int32_t leaf);
    /// Refits boxes and heights from `node` up to the root, rotating on the way.
    void refitUpwards(int32_t node);
    /// Swaps a child of `a` with a grandchild under its other child when that shrinks the
    /// surface area of the tree (the node `a` itself keeps its place and its box).
    void rotate(int32_t a);
    int32_t validateNode(int32_t node, const char*& error) const;

    std::vector<Node> nodes_;
    int32_t root_ = kNull;
    int32_t freeList_ = kNull;
    int proxyCount_ = 0;
    double fatMargin_;
    mutable std::vector<int32_t> stack_;
};

template <class OnLeaf>
void AabbTree::query(const Aabb& box, OnLeaf&& onLeaf) const {
    if (root_ == kNull || !nodes_[root_].box.overlaps(box)) return;
    // Depth-first, testing children before pushing them: the stack never holds more than one
    // pending sibling per level.
    stack_.resize(static_cast<size_t>(nodes_[root_].height) + 2);
    int32_t* stack = stack_.data();
    int top = 0;
    stack[top++] = root_;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (node.isLeaf()) {
            onLeaf(static_cast<int32_t>(&node - nodes_.data()));
            continue;
        }
        // child1 is pushed first so that child0's subtree is visited first (a fixed order).
        if (nodes_[node.child1].box.overlaps(box)) stack[top++] = node.child1;
        if (nodes_[node.child0].box.overlaps(box)) stack[top++] = node.child0;
    }
}

}  // namespace substep

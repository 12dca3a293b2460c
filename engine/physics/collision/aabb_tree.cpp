#include "physics/collision/aabb_tree.h"

#include <algorithm>

namespace substep {

int32_t AabbTree::allocateNode() {
    int32_t index;
    if (freeList_ != kNull) {
        index = freeList_;
        freeList_ = nodes_[index].parent;
        nodes_[index] = Node{};
    } else {
        index = static_cast<int32_t>(nodes_.size());
        nodes_.emplace_back();
    }
    nodes_[index].height = 0;
    return index;
}

void AabbTree::freeNode(int32_t node) {
    nodes_[node] = Node{};  // height -1 marks it free
    nodes_[node].parent = freeList_;
    freeList_ = node;
}

int32_t AabbTree::createProxy(const Aabb& box, uint32_t userData) {
    const int32_t leaf = allocateNode();
    nodes_[leaf].box = box.inflated(fatMargin_);
    nodes_[leaf].userData = userData;
    insertLeaf(leaf);
    ++proxyCount_;
    return leaf;
}

void AabbTree::destroyProxy(int32_t proxy) {
    removeLeaf(proxy);
    freeNode(proxy);
    --proxyCount_;
}

bool AabbTree::moveProxy(int32_t proxy, const Aabb& box) {
    const Aabb fresh = box.inflated(fatMargin_);
    const Aabb& fat = nodes_[proxy].box;
    // A fat box four times the area of a fresh one belongs to a body that has slowed down:
    // shrinking it keeps queries from wading through stale, oversized leaves.
    if (fat.contains(box) && fat.halfArea() <= 4.0 * fresh.halfArea()) return false;
    removeLeaf(proxy);
    nodes_[proxy].box = fresh;
    insertLeaf(proxy);
    return true;
}

void AabbTree::clear() {
    nodes_.clear();
    root_ = kNull;
    freeList_ = kNull;
    proxyCount_ = 0;
}

void AabbTree::insertLeaf(int32_t leaf) {
    if (root_ == kNull) {
        root_ = leaf;
        nodes_[leaf].parent = kNull;
        return;
    }

    // Walk down towards the cheapest sibling by the surface-area heuristic: pairing the leaf
    // with a node costs the merged area, descending further costs every ancestor's growth.
    const Aabb leafBox = nodes_[leaf].box;
    int32_t index = root_;
    while (!nodes_[index].isLeaf()) {
        const Node& node = nodes_[index];
        const double area = node.box.halfArea();
        const double combinedArea = node.box.merged(leafBox).halfArea();
        const double pairCost = 2.0 * combinedArea;
        const double inheritedCost = 2.0 * (combinedArea - area);
        auto descendCost = [&](int32_t child) {
            const Node& c = nodes_[child];
            const double merged = c.box.merged(leafBox).halfArea();
            return (c.isLeaf() ? merged : merged - c.box.halfArea()) + inheritedCost;
        };
        const double cost0 = descendCost(node.child0);
        const double cost1 = descendCost(node.child1);
        if (pairCost < cost0 && pairCost < cost1) break;
        index = cost0 <= cost1 ? node.child0 : node.child1;
    }
    const int32_t sibling = index;

    // A new parent takes the sibling's place and holds the sibling and the leaf.
    const int32_t oldParent = nodes_[sibling].parent;
    const int32_t newParent = allocateNode();  // may reallocate: no references held across
    Node& parent = nodes_[newParent];
    parent.parent = oldParent;
    parent.box = leafBox.merged(nodes_[sibling].box);
    parent.height = nodes_[sibling].height + 1;
    parent.child0 = sibling;
    parent.child1 = leaf;
    if (oldParent == kNull) {
        root_ = newParent;
    } else if (nodes_[oldParent].child0 == sibling) {
        nodes_[oldParent].child0 = newParent;
    } else {
        nodes_[oldParent].child1 = newParent;
    }
    nodes_[sibling].parent = newParent;
    nodes_[leaf].parent = newParent;

    refitUpwards(oldParent);
}

void AabbTree::removeLeaf(int32_t leaf) {
    if (leaf == root_) {
        root_ = kNull;
        return;
    }
    const int32_t parent = nodes_[leaf].parent;
    const int32_t grandParent = nodes_[parent].parent;
    const int32_t sibling =
        nodes_[parent].child0 == leaf ? nodes_[parent].child1 : nodes_[parent].child0;

    // The sibling takes the parent's place; the parent node is freed.
    nodes_[sibling].parent = grandParent;
    if (grandParent == kNull) {
        root_ = sibling;
    } else if (nodes_[grandParent].child0 == parent) {
        nodes_[grandParent].child0 = sibling;
    } else {
        nodes_[grandParent].child1 = sibling;
    }
    freeNode(parent);
    refitUpwards(grandParent);
}

void AabbTree::refitUpwards(int32_t node) {
    while (node != kNull) {
        Node& n = nodes_[node];
        const Node& c0 = nodes_[n.child0];
        const Node& c1 = nodes_[n.child1];
        n.height = 1 + std::max(c0.height, c1.height);
        n.box = c0.box.merged(c1.box);
        rotate(node);
        node = nodes_[node].parent;
    }
}

void AabbTree::rotate(int32_t a) {
    Node& A = nodes_[a];
    if (A.height < 2) return;
    const int32_t b = A.child0;
    const int32_t c = A.child1;
    Node& B = nodes_[b];
    Node& C = nodes_[c];

    // Candidate swaps of one child of A with one grandchild under the other child: the swap
    // leaves A's box alone and changes the box of the child that receives the other one, so
    // its area is the whole cost. Take the swap that shrinks that area most, if any.
    enum class Swap { None, BwithC0, BwithC1, CwithB0, CwithB1 };
    Swap best = Swap::None;
    double bestGain = 0.0;
    if (!C.isLeaf()) {
        const double area = C.box.halfArea();
        const Node& c0 = nodes_[C.child0];
        const Node& c1 = nodes_[C.child1];
        const double gain0 = area - B.box.merged(c1.box).halfArea();  // B takes c0's place
        const double gain1 = area - B.box.merged(c0.box).halfArea();  // B takes c1's place
        if (gain0 > bestGain) bestGain = gain0, best = Swap::BwithC0;
        if (gain1 > bestGain) bestGain = gain1, best = Swap::BwithC1;
    }
    if (!B.isLeaf()) {
        const double area = B.box.halfArea();
        const Node& b0 = nodes_[B.child0];
        const Node& b1 = nodes_[B.child1];
        const double gain0 = area - C.box.merged(b1.box).halfArea();
        const double gain1 = area - C.box.merged(b0.box).halfArea();
        if (gain0 > bestGain) bestGain = gain0, best = Swap::CwithB0;
        if (gain1 > bestGain) bestGain = gain1, best = Swap::CwithB1;
    }
    if (best == Swap::None) return;

    // `mover` (a child of A) trades places with `grandchild` under `receiver`.
    const bool moveB = best == Swap::BwithC0 || best == Swap::BwithC1;
    const int32_t mover = moveB ? b : c;
    const int32_t receiver = moveB ? c : b;
    Node& R = nodes_[receiver];
    const bool first = best == Swap::BwithC0 || best == Swap::CwithB0;
    const int32_t grandchild = first ? R.child0 : R.child1;
    (first ? R.child0 : R.child1) = mover;
    (moveB ? A.child0 : A.child1) = grandchild;
    nodes_[mover].parent = receiver;
    nodes_[grandchild].parent = a;

    const Node& r0 = nodes_[R.child0];
    const Node& r1 = nodes_[R.child1];
    R.box = r0.box.merged(r1.box);
    R.height = 1 + std::max(r0.height, r1.height);
    A.height = 1 + std::max(nodes_[A.child0].height, nodes_[A.child1].height);
}

int32_t AabbTree::validateNode(int32_t node, const char*& error) const {
    const Node& n = nodes_[node];
    if (n.isLeaf()) {
        if (n.child1 != kNull) error = "leaf with one child";
        if (n.height != 0) error = "leaf height not 0";
        return 1;
    }
    const Node& c0 = nodes_[n.child0];
    const Node& c1 = nodes_[n.child1];
    if (c0.parent != node || c1.parent != node) error = "broken parent link";
    if (n.height != 1 + std::max(c0.height, c1.height)) error = "wrong height";
    if (!n.box.contains(c0.box) || !n.box.contains(c1.box)) error = "box misses a child";
    return 1 + validateNode(n.child0, error) + validateNode(n.child1, error);
}

const char* AabbTree::validate() const {
    const char* error = "";
    int32_t used = 0;
    if (root_ != kNull) {
        if (nodes_[root_].parent != kNull) error = "root has a parent";
        used = validateNode(root_, error);
    }
    int32_t freeCount = 0;
    for (int32_t f = freeList_; f != kNull && freeCount <= static_cast<int32_t>(nodes_.size());
         f = nodes_[f].parent)
        ++freeCount;
    if (used + freeCount != static_cast<int32_t>(nodes_.size())) error = "nodes lost";
    if (proxyCount_ > 0 && used != 2 * proxyCount_ - 1) error = "node count does not match";
    return error;
}

}  // namespace substep

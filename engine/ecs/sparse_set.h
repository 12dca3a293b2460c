#pragma once
/// A sparse set of entities: a dense array of the members, in insertion order until a removal,
/// and a sparse array from entity index to dense position. Membership, insertion and removal are
/// O(1); iteration walks the dense array, which is contiguous. Removal is swap-and-pop: the last
/// member moves into the hole, so the dense order after removals depends only on the sequence of
/// operations (deterministic), not on addresses or hashing.

#include "ecs/entity.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace substep::ecs {

class SparseSet {
  public:
    SparseSet() = default;
    SparseSet(const SparseSet&) = delete;
    SparseSet& operator=(const SparseSet&) = delete;
    SparseSet(SparseSet&&) = default;
    SparseSet& operator=(SparseSet&&) = default;
    virtual ~SparseSet() = default;

    /// True when this exact entity (index and generation) is a member.
    bool contains(Entity entity) const {
        if (entity.index >= sparse_.size()) return false;
        const uint32_t position = sparse_[entity.index];
        return position != kAbsent && dense_[position] == entity;
    }

    /// Number of members.
    std::size_t size() const { return dense_.size(); }
    bool empty() const { return dense_.empty(); }

    /// The members in dense order (valid until the next insertion or removal).
    std::span<const Entity> entities() const { return dense_; }

    /// Dense position of a member. Precondition: contains(entity).
    std::size_t position(Entity entity) const { return sparse_[entity.index]; }

    /// Removes the entity if it is a member (swap-and-pop); returns whether it was one. Virtual
    /// so a registry can strip an entity from pools whose component type it does not know;
    /// typed pools are final, so calls through them are resolved statically.
    virtual bool remove(Entity entity) {
        if (!contains(entity)) return false;
        const uint32_t position = sparse_[entity.index];
        const Entity last = dense_.back();
        dense_[position] = last;
        sparse_[last.index] = position;
        dense_.pop_back();
        sparse_[entity.index] = kAbsent;
        return true;
    }

  protected:
    /// Appends a non-member at the end of the dense array; returns its position.
    std::size_t insert(Entity entity) {
        if (entity.index >= sparse_.size()) sparse_.resize(entity.index + 1, kAbsent);
        sparse_[entity.index] = static_cast<uint32_t>(dense_.size());
        dense_.push_back(entity);
        return dense_.size() - 1;
    }

    void reserveDense(std::size_t capacity) { dense_.reserve(capacity); }

  private:
    static constexpr uint32_t kAbsent = std::numeric_limits<uint32_t>::max();

    std::vector<Entity> dense_;
    std::vector<uint32_t> sparse_;  ///< entity index -> dense position, or kAbsent
};

}  // namespace substep::ecs

#pragma once
/// The storage of one component type: a sparse set of entities with the components in a second
/// dense array kept parallel to it (component i belongs to entity i of the set).
///
/// Reference stability: a reference or pointer to a component stays valid until the next
/// insertion into, or removal from, the same pool. Insertion may reallocate the array (reserve()
/// first to avoid it); removal moves the last component into the removed one's place. Work on
/// other component types never moves this pool's components.

#include "ecs/sparse_set.h"

#include <cassert>
#include <cstddef>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace substep::ecs {

template <class T>
class ComponentPool final : public SparseSet {
  public:
    /// Adds the entity's component (it must not have one yet); returns it.
    template <class... Args>
    T& emplace(Entity entity, Args&&... args) {
        assert(!contains(entity));
        // Aggregates (most components) take braces; classes with constructors take parentheses.
        if constexpr (std::is_aggregate_v<T>) {
            components_.push_back(T{std::forward<Args>(args)...});
        } else {
            components_.emplace_back(std::forward<Args>(args)...);
        }
        insert(entity);
        return components_.back();
    }

    /// The entity's component. Precondition: contains(entity).
    T& get(Entity entity) {
        assert(contains(entity));
        return components_[position(entity)];
    }
    const T& get(Entity entity) const {
        assert(contains(entity));
        return components_[position(entity)];
    }

    /// The entity's component, or nullptr when it has none.
    T* tryGet(Entity entity) { return contains(entity) ? &components_[position(entity)] : nullptr; }
    const T* tryGet(Entity entity) const {
        return contains(entity) ? &components_[position(entity)] : nullptr;
    }

    /// Removes the entity's component if it has one (swap-and-pop, mirroring the entity array).
    bool remove(Entity entity) override {
        if (!contains(entity)) return false;
        const std::size_t position = this->position(entity);
        if (position + 1 != components_.size())
            components_[position] = std::move(components_.back());
        components_.pop_back();
        return SparseSet::remove(entity);
    }

    /// Makes room for `capacity` components, so insertions up to it keep references valid.
    void reserve(std::size_t capacity) {
        reserveDense(capacity);
        components_.reserve(capacity);
    }

    /// The components in dense order, parallel to entities().
    std::span<T> components() { return components_; }
    std::span<const T> components() const { return components_; }

    /// Records that the entity's component was changed in place (Registry::patch), for the
    /// systems that mirror it elsewhere (the physics system into the world). An entity may be
    /// listed more than once; readers treat the list as a set.
    void markChanged(Entity entity) { changed_.push_back(entity); }
    /// The entities marked since the last takeChanged(), in the order they were marked; the
    /// list is handed over and the pool's own emptied (its storage kept in `out`).
    void takeChanged(std::vector<Entity>& out) {
        out.clear();
        out.swap(changed_);
    }
    bool anyChanged() const { return !changed_.empty(); }

  private:
    std::vector<T> components_;
    std::vector<Entity> changed_;
};

}  // namespace substep::ecs

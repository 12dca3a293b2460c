#pragma once
/// Views: the entities that have every one of a list of component types, with those components.
///
/// A view walks the smallest of its pools and tests the others, so its cost follows the rarest
/// component. It walks that pool's dense array from the back to the front, which makes the order
/// deterministic (the reverse of the pool's dense order) and makes this rule safe:
///
///   While iterating, you may remove components from the current entity or destroy it, and you
///   may create entities and add components to any entity. Entities added to the walked pool
///   during the walk are not visited. Do not remove components from, or destroy, entities other
///   than the current one: that may move an unvisited entity into the visited part.
///
/// Swap-and-pop removal of the current entity moves the last member, which has already been
/// visited, into its place; the members still to come sit at lower positions and do not move.
/// Component references handed to the callback follow the pool rule (component_pool.h): adding
/// a component of one of the view's types may move that type's components, so fetch again after.

#include "ecs/component_pool.h"
#include "ecs/entity.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <iterator>
#include <tuple>
#include <type_traits>

namespace substep::ecs {

template <class... Ts>
class View {
    static_assert(sizeof...(Ts) > 0, "a view needs at least one component type");
    static_assert((std::is_same_v<Ts, std::remove_cvref_t<Ts>> && ...),
                  "views name plain component types");

  public:
    /// A view over the given pools; a null pool (a type never used) makes the view empty.
    explicit View(ComponentPool<Ts>*... pools) : pools_(pools...) {
        const std::array<const SparseSet*, sizeof...(Ts)> all{pools...};
        for (const SparseSet* pool : all) {
            if (pool == nullptr) {
                leading_ = nullptr;
                return;
            }
            // Ties keep the first listed type, so the choice is deterministic.
            if (leading_ == nullptr || pool->size() < leading_->size()) leading_ = pool;
        }
    }

    /// True when the entity has every component of the view.
    bool contains(Entity entity) const {
        return std::apply(
            [&](auto*... pool) { return ((pool != nullptr && pool->contains(entity)) && ...); },
            pools_);
    }

    /// Calls f(entity, components&...) or f(components&...) for every entity of the view, under
    /// the iteration rule at the top of this file.
    template <class F>
    void each(F&& f) {
        if (leading_ == nullptr) return;
        for (std::size_t next = leading_->size(); next > 0;) {
            // The walked pool may have shrunk below `next` if the callback broke the rule above;
            // clamping keeps the walk inside the array either way.
            next = std::min(next, leading_->size());
            if (next == 0) break;
            --next;
            const Entity entity = leading_->entities()[next];
            if (!contains(entity)) continue;
            if constexpr (std::is_invocable_v<F&, Entity, Ts&...>) {
                std::invoke(f, entity, std::get<ComponentPool<Ts>*>(pools_)->get(entity)...);
            } else {
                std::invoke(f, std::get<ComponentPool<Ts>*>(pools_)->get(entity)...);
            }
        }
    }

    /// Forward iterator over the view's entities, in the same order and under the same rule as
    /// each(); for `for (Entity e : view)` with get<T>(e) in the body.
    class Iterator {
      public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = Entity;
        using difference_type = std::ptrdiff_t;
        using pointer = const Entity*;
        using reference = Entity;

        Iterator() = default;
        Entity operator*() const { return view_->leading_->entities()[next_ - 1]; }
        Iterator& operator++() {
            next_ = std::min(next_ - 1, view_->leading_->size());
            skipNonMembers();
            return *this;
        }
        Iterator operator++(int) {
            Iterator before = *this;
            ++*this;
            return before;
        }
        friend bool operator==(const Iterator& a, const Iterator& b) { return a.next_ == b.next_; }

      private:
        friend class View;
        Iterator(const View* view, std::size_t next) : view_(view), next_(next) {
            skipNonMembers();
        }
        void skipNonMembers() {
            while (next_ > 0 && !view_->contains(view_->leading_->entities()[next_ - 1]))
                --next_;
        }

        const View* view_ = nullptr;
        std::size_t next_ = 0;  ///< dense position + 1 of the current entity; 0 is the end
    };

    Iterator begin() const {
        return leading_ == nullptr ? end() : Iterator(this, leading_->size());
    }
    Iterator end() const { return Iterator(); }

    /// The view's component T of an entity in it.
    template <class T>
    T& get(Entity entity) const {
        return std::get<ComponentPool<std::remove_const_t<T>>*>(pools_)->get(entity);
    }

    /// An upper bound of the number of entities (the walked pool's size).
    std::size_t sizeHint() const { return leading_ == nullptr ? 0 : leading_->size(); }

  private:
    std::tuple<ComponentPool<Ts>*...> pools_;
    const SparseSet* leading_ = nullptr;  ///< the smallest pool, the one walked
};

}  // namespace substep::ecs

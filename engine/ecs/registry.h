#pragma once
/// The registry: it issues entities and keeps one component pool per component type.
///
/// Entities are index + generation (entity.h). Destroyed slots are reused, newest first, with the
/// generation bumped, so stale handles stay invalid. Each component type has its own sparse-set
/// pool (component_pool.h), found by a RTTI-free type id (component_type_id.h); views
/// (view.h) join pools. The registry is movable, not copyable; pools live on the heap, so moving
/// a registry moves no component and keeps references into pools valid.

#include "ecs/component_pool.h"
#include "ecs/component_type_id.h"
#include "ecs/entity.h"
#include "ecs/sparse_set.h"
#include "ecs/view.h"

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace substep::ecs {

class Registry {
  public:
    Registry() = default;
    Registry(const Registry&) = delete;
    Registry& operator=(const Registry&) = delete;
    Registry(Registry&&) noexcept = default;
    Registry& operator=(Registry&&) noexcept = default;

    /// A new entity without components: a free slot (the most recently freed first) or a new one.
    Entity create() {
        ++aliveCount_;
        if (!freeSlots_.empty()) {
            const uint32_t index = freeSlots_.back();
            freeSlots_.pop_back();
            slots_[index].alive = true;
            return {index, slots_[index].generation};
        }
        slots_.push_back({.generation = 1, .alive = true});
        return {static_cast<uint32_t>(slots_.size() - 1), 1};
    }

    /// Removes every component of the entity and frees its slot; the slot's next occupant gets a
    /// new generation. Invalid entities are ignored.
    void destroy(Entity entity) {
        if (!isValid(entity)) return;
        for (const std::unique_ptr<SparseSet>& pool : pools_)
            if (pool) pool->remove(entity);
        Slot& slot = slots_[entity.index];
        slot.alive = false;
        // Skip 0 on wrap-around: generation 0 means null.
        slot.generation = slot.generation == UINT32_MAX ? 1 : slot.generation + 1;
        freeSlots_.push_back(entity.index);
        --aliveCount_;
    }

    /// True for an entity this registry issued and has not destroyed since.
    bool isValid(Entity entity) const {
        return !entity.isNull() && entity.index < slots_.size() && slots_[entity.index].alive &&
               slots_[entity.index].generation == entity.generation;
    }

    /// Number of live entities.
    std::size_t aliveCount() const { return aliveCount_; }

    /// Gives a valid entity a component T built from args (braces for aggregates). If it already
    /// has one, that one is replaced in place. Throws std::invalid_argument for an invalid entity.
    template <class T, class... Args>
    T& emplace(Entity entity, Args&&... args) {
        if (!isValid(entity)) throw std::invalid_argument("ecs::Registry::emplace: invalid entity");
        ComponentPool<T>& pool = this->pool<T>();
        if (T* existing = pool.tryGet(entity)) {
            if constexpr (std::is_aggregate_v<T>) {
                *existing = T{std::forward<Args>(args)...};
            } else {
                *existing = T(std::forward<Args>(args)...);
            }
            return *existing;
        }
        return pool.emplace(entity, std::forward<Args>(args)...);
    }

    /// The entity's component T. Precondition: has<T>(entity).
    template <class T>
    T& get(Entity entity) {
        ComponentPool<T>* pool = findPool<T>();
        assert(pool != nullptr);
        return pool->get(entity);
    }
    template <class T>
    const T& get(Entity entity) const {
        const ComponentPool<T>* pool = findPool<T>();
        assert(pool != nullptr);
        return pool->get(entity);
    }

    /// Changes the entity's component T in place through `change(T&)` and records the change,
    /// so that a system mirroring T (the physics system: Transform, RigidBody, Collider, Joint)
    /// applies it before its next step. A component written directly through get() is not seen
    /// by such systems. Precondition: has<T>(entity). Returns the component.
    template <class T, class Change>
    T& patch(Entity entity, Change&& change) {
        ComponentPool<T>* pool = findPool<T>();
        assert(pool != nullptr);
        T& component = pool->get(entity);
        std::forward<Change>(change)(component);
        pool->markChanged(entity);
        return component;
    }

    /// The entity's component T, or nullptr (also for invalid entities).
    template <class T>
    T* tryGet(Entity entity) {
        ComponentPool<T>* pool = findPool<T>();
        return pool != nullptr ? pool->tryGet(entity) : nullptr;
    }
    template <class T>
    const T* tryGet(Entity entity) const {
        const ComponentPool<T>* pool = findPool<T>();
        return pool != nullptr ? pool->tryGet(entity) : nullptr;
    }

    /// True when the entity has a component T (false for invalid entities).
    template <class T>
    bool has(Entity entity) const {
        const ComponentPool<T>* pool = findPool<T>();
        return pool != nullptr && pool->contains(entity);
    }

    /// Removes the entity's component T if it has one; returns whether it had.
    template <class T>
    bool remove(Entity entity) {
        ComponentPool<T>* pool = findPool<T>();
        return pool != nullptr && pool->remove(entity);
    }

    /// The entities having every type in Ts, with those components; see view.h for the order
    /// and what may change during iteration.
    template <class... Ts>
    View<Ts...> view() {
        return View<Ts...>(findPool<Ts>()...);
    }

    /// The pool of T, created on first use (for reserve(), size() or direct dense access).
    template <class T>
    ComponentPool<T>& pool() {
        static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "components are plain types");
        const uint32_t id = componentTypeId<T>();
        if (id >= pools_.size()) pools_.resize(id + 1);
        if (!pools_[id]) pools_[id] = std::make_unique<ComponentPool<T>>();
        return static_cast<ComponentPool<T>&>(*pools_[id]);
    }

    /// The pool of T, or nullptr if no T was ever added to this registry.
    template <class T>
    ComponentPool<T>* findPool() {
        static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "components are plain types");
        const uint32_t id = componentTypeId<T>();
        return id < pools_.size() ? static_cast<ComponentPool<T>*>(pools_[id].get()) : nullptr;
    }
    template <class T>
    const ComponentPool<T>* findPool() const {
        static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "components are plain types");
        const uint32_t id = componentTypeId<T>();
        return id < pools_.size() ? static_cast<const ComponentPool<T>*>(pools_[id].get())
                                  : nullptr;
    }

  private:
    struct Slot {
        uint32_t generation = 1;  ///< the generation of the slot's current or next occupant
        bool alive = false;
    };

    std::vector<Slot> slots_;
    std::vector<uint32_t> freeSlots_;                ///< destroyed slots, reused last-in first-out
    std::vector<std::unique_ptr<SparseSet>> pools_;  ///< indexed by componentTypeId
    std::size_t aliveCount_ = 0;
};

}  // namespace substep::ecs

#pragma once
/// Component type ids without RTTI: each component type draws a small integer from one
/// process-wide counter the first time it is used, so a registry can keep its pools in a vector
/// indexed by type. Ids depend on first-use order and are only meaningful within one process.

#include <atomic>
#include <cstdint>
#include <type_traits>

namespace substep::ecs {

namespace detail {
/// The next unused type id. Atomic because two threads may meet two new types at once.
inline uint32_t nextComponentTypeId() {
    static std::atomic<uint32_t> counter{0};
    return counter.fetch_add(1, std::memory_order_relaxed);
}

/// One id per unqualified type, drawn on first use.
template <class T>
uint32_t unqualifiedTypeId() {
    static const uint32_t id = nextComponentTypeId();
    return id;
}
}  // namespace detail

/// The id of component type T; T, const T and T& share it.
template <class T>
uint32_t componentTypeId() {
    return detail::unqualifiedTypeId<std::remove_cvref_t<T>>();
}

}  // namespace substep::ecs

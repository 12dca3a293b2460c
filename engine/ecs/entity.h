#pragma once
/// Entities: value handles made of a slot index and a generation. Destroying an entity bumps its
/// slot's generation, so a handle kept from before tells itself apart from the slot's next
/// occupant. Generation 0 is never issued: a default-constructed Entity is null.

#include <cstdint>

namespace substep::ecs {

struct Entity {
    uint32_t index = 0;
    uint32_t generation = 0;

    /// True for the default (null) entity, which no registry ever issues.
    bool isNull() const { return generation == 0; }
    friend bool operator==(Entity, Entity) = default;
};

/// The null entity, for readability at call sites (a joint's "world" side, "no entity").
inline constexpr Entity kNullEntity{};

}  // namespace substep::ecs

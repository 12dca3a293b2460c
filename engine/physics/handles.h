#pragma once
/// Value handles for world objects: an index into contiguous storage plus a generation that
/// tells a live object from a destroyed one whose slot was reused. Generation 0 is never issued,
/// so a default-constructed id is null.

#include <cstdint>

namespace substep {

struct BodyId {
    uint32_t index = 0;
    uint32_t generation = 0;
    bool isNull() const { return generation == 0; }
    friend bool operator==(BodyId, BodyId) = default;
};

struct JointId {
    uint32_t index = 0;
    uint32_t generation = 0;
    bool isNull() const { return generation == 0; }
    friend bool operator==(JointId, JointId) = default;
};

/// A soft body (engine/physics/soft): its particles, elements and attachments.
struct SoftBodyId {
    uint32_t index = 0;
    uint32_t generation = 0;
    bool isNull() const { return generation == 0; }
    friend bool operator==(SoftBodyId, SoftBodyId) = default;
};

}  // namespace substep

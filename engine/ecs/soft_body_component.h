#pragma once
/// The SoftBody component of the engine layer: a hexahedral soft body (physics/soft/soft_body.h)
/// as an entity sees it. Kept apart from components.h so the many files that include that one
/// do not depend on the soft-body definitions.

#include "ecs/entity.h"
#include "physics/handles.h"
#include "physics/soft/soft_body.h"

#include <vector>

namespace substep::ecs {

/// A soft body. def.attachments[i].body is ignored: the PhysicsSystem fills it from the body of
/// attachedBodies[i] (a RigidBody entity), as it does a Joint's bodies. Fixed at creation (a
/// patch changes nothing): to change a soft body, destroy its entity and make another.
struct SoftBody {
    SoftBodyDef def;
    std::vector<Entity> attachedBodies;  ///< one per def.attachments entry, same order
    SoftBodyId id;                       ///< null until PhysicsSystem::sync() creates it

    /// Written by the PhysicsSystem when it creates the soft body (whole) and by every
    /// write-back (after each step, and once when buildScene has made the scene): centre of
    /// mass, mean velocity, axis-aligned extent, mass and counts, but not the volume, a sum over
    /// every element that most steps nobody reads: NaN there. DESIGN.md's CSV columns, the
    /// volume among them, come from ecs::softBodyReadout (physics_system.h).
    SoftBodyReadout readout;
};

}  // namespace substep::ecs

#pragma once
/// A world's state at one frame boundary, for rewinding (the viewer's timeline): what
/// World::snapshot() copies and World::restore() puts back. Everything a step reads that lives
/// from one frame to the next is in it, so steps after a restore repeat the original steps byte
/// for byte: bodies (poses, velocities, previous poses), joints (a motor's reached angle, the
/// last readouts), the contact pairs and points (whose multipliers the velocity pass reads),
/// the broadphase's boxes and trees (their order feeds the pairs), each body's sleep state,
/// soft particles. The settings
/// are not: a restore keeps the world's current ones.

#include "physics/world.h"
#include "physics/soft/soft_system.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace substep {

class WorldSnapshot {
  public:
    WorldSnapshot() = default;

    /// Roughly the heap memory the snapshot holds (bytes), for a history's budget.
    std::size_t bytes() const;
    /// Number of body slots (index 0 is the world's anchor); 0 for a default-made snapshot.
    std::size_t bodyCount() const { return bodies_.size(); }

  private:
    friend class World;

    std::vector<Body> bodies_;
    std::vector<uint32_t> freeBodies_;
    std::vector<Joint> joints_;
    std::vector<uint32_t> freeJoints_;
    Broadphase broadphase_;
    std::vector<ContactPair> contactPairs_;
    std::vector<ContactPair> previousPairs_;
    std::vector<double> reaches_;
    std::vector<Pose> poses_;
    std::vector<Contact> contacts_;
    std::vector<BodyPair> jointExclusions_;
    bool jointsChanged_ = true;
    int collidingBodies_ = 0;
    uint32_t nextGeneration_ = 1;
    double lastSubstep_ = 0.0;
    bool anyDamping_ = false;
    bool repairPending_ = false;
    SleepIslands sleep_;  ///< rest times, asleep flags and islands (WorldSettings::sleeping)
    /// Which bodies a collision reached lately (contact_restitution.h): the next substeps'
    /// velocity pass depends on it.
    RestitutionScratch restitution_;
    std::optional<SoftSystem> soft_;  ///< empty when the world had no soft system
};

}  // namespace substep

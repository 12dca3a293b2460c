#include "physics/world_snapshot.h"

#include "physics/substep_corrections.h"

namespace substep {
namespace {

template <class T>
std::size_t heapBytes(const std::vector<T>& v) {
    return v.capacity() * sizeof(T);
}

}  // namespace

std::size_t WorldSnapshot::bytes() const {
    // The broadphase and soft system are counted by their body count: their own storage is
    // private, and per body it is of the order of a Body's.
    const std::size_t perBodyExtra = sizeof(Aabb) * 2 + 64;
    return sizeof(*this) + heapBytes(bodies_) + heapBytes(freeBodies_) + heapBytes(joints_) +
           heapBytes(freeJoints_) + heapBytes(contactPairs_) + heapBytes(previousPairs_) +
           heapBytes(reaches_) + heapBytes(poses_) + heapBytes(contacts_) +
           heapBytes(jointExclusions_) + heapBytes(restitution_.velocities) + heapBytes(restitution_.stamp) +
           heapBytes(restitution_.changedIn) + heapBytes(restitution_.collidedIn) + heapBytes(restitution_.pairs) +
           bodies_.size() * perBodyExtra +
           (soft_ ? soft_->elementCount() * 256 : 0);
}

WorldSnapshot World::snapshot() const {
    WorldSnapshot s;
    s.bodies_ = bodies_;
    s.freeBodies_ = freeBodies_;
    s.joints_ = joints_;
    s.freeJoints_ = freeJoints_;
    s.broadphase_ = broadphase_;
    s.contactPairs_ = contactPairs_;
    s.previousPairs_ = previousPairs_;
    s.reaches_ = reaches_;
    s.poses_ = poses_;
    s.contacts_ = contacts_;
    s.jointExclusions_ = jointExclusions_;
    s.jointsChanged_ = jointsChanged_;
    s.collidingBodies_ = collidingBodies_;
    s.nextGeneration_ = nextGeneration_;
    s.lastSubstep_ = lastSubstep_;
    s.anyDamping_ = anyDamping_;
    s.repairPending_ = repairPending_;
    s.sleep_ = sleep_;
    s.restitution_ = restitutionScratch_;
    if (soft_) s.soft_ = *soft_;
    return s;
}

void World::restore(const WorldSnapshot& s) {
    // A frame left open (stepped a substep at a time) is abandoned: the snapshot is a frame
    // boundary, and its sleep flags belong to the state being replaced.
    frame_ = {};
    sleepFlags_ = nullptr;
    if (corrections_) corrections_->beginSubstep(0, 0);
    bodies_ = s.bodies_;
    freeBodies_ = s.freeBodies_;
    joints_ = s.joints_;
    freeJoints_ = s.freeJoints_;
    broadphase_ = s.broadphase_;
    contactPairs_ = s.contactPairs_;
    previousPairs_ = s.previousPairs_;
    reaches_ = s.reaches_;
    poses_ = s.poses_;
    contacts_ = s.contacts_;
    jointExclusions_ = s.jointExclusions_;
    jointsChanged_ = s.jointsChanged_;
    clustersChanged_ = true;  // the joints may not be the ones the clusters were made of
    collidingBodies_ = s.collidingBodies_;
    nextGeneration_ = s.nextGeneration_;
    lastSubstep_ = s.lastSubstep_;
    anyDamping_ = s.anyDamping_;
    repairPending_ = s.repairPending_;
    sleep_ = s.sleep_;
    awakeBodiesListedAt_ = awakePairsListedAt_ = ~uint64_t{0};  // the flags are the snapshot's
    restitutionScratch_ = s.restitution_;
    if (s.soft_) {
        if (soft_)
            *soft_ = *s.soft_;
        else
            soft_ = std::make_unique<SoftSystem>(*s.soft_);
    } else {
        soft_.reset();
    }
}

}  // namespace substep

#pragma once
/// Sleeping (as Box2D, Jolt and Bullet have it): islands of bodies that touch or are jointed,
/// and whose every body has stayed slow for a while, stop being simulated until something
/// wakes them.
///
/// An island is a connected set of dynamic bodies; joints and contact pairs that touched in the
/// last frame connect them, static bodies do not (the ground would otherwise join everything).
/// After each step, a body slower than WorldSettings::sleepSpeed at every point of its shape
/// (|v| + |ω|·reach) and turning slower than sleepAngularSpeed gathers rest time; one that is
/// not starts again from zero. An island whose every body has rested sleepTime falls asleep
/// whole: its velocities are set to zero and the step skips its bodies, their joints and their
/// contacts: the broadphase keeps their boxes and pairs (broadphase.h), and the per-substep
/// loops run over lists of the awake bodies and pairs (a joint still costs a flag test).
///
/// Waking is conservative, so that no awake body ever meets a sleeping one in the solve: before
/// the substeps, every broadphase pair and joint that links a sleeping body to an awake one (an
/// awake dynamic body, or a static body moved since the last step) wakes the sleeping body's
/// whole island, repeated until nothing changes. The broadphase's boxes are grown by the motion
/// of the frame, so an island wakes in the frame a body would hit it, before the hit. Changes
/// made through the world's edit functions (a pose or velocity set, a surface, a joint created,
/// changed or destroyed, a body destroyed) wake what they touch.

#include "physics/body.h"
#include "physics/collision/broadphase.h"
#include "physics/contact.h"
#include "physics/joints/joint.h"

#include <cstdint>
#include <span>
#include <vector>

namespace substep {

/// Thresholds of sleeping (WorldSettings carries them).
struct SleepSettings {
    double speed = 0.05;         ///< m/s: largest point speed |v| + |ω|·reach that counts as rest
    double angularSpeed = 0.05;  ///< rad/s: largest turning rate that counts as rest
    double time = 0.5;           ///< s of rest, for every body of an island, before it sleeps
};

/// Per-body sleep state and the island bookkeeping, indexed like the world's bodies.
class SleepIslands {
public:
    /// Makes room for `bodies` body slots (new slots are awake).
    void resize(size_t bodies);
    /// Whether body `index` is asleep.
    bool asleep(uint32_t index) const { return index < asleep_.size() && asleep_[index] != 0; }
    /// The per-body flags (1: asleep), for the solver's loops; as long as the body storage.
    const uint8_t* flags() const { return asleep_.data(); }
    /// Number of sleeping bodies.
    int sleepingCount() const { return sleeping_; }
    /// Counts the changes of the flags (a body falling asleep or waking), so that lists of the
    /// awake bodies are rebuilt only when it moves.
    uint64_t changes() const { return changes_; }

    /// Wakes the island of a sleeping body and restarts the body's rest time. A static body
    /// (moved, or changed) is remembered instead: the next wakeLinked wakes what touches it.
    void wake(uint32_t index, const Body& body);
    /// Wakes every island and restarts every rest time.
    void wakeAll();

    /// Before the substeps: wakes every sleeping island that a pair or a joint links to an
    /// awake body, until nothing changes (see the file comment).
    void wakeLinked(std::span<const Body> bodies, std::span<const ContactPair> pairs,
                    std::span<const Joint> joints);

    /// After the substeps: updates every awake body's rest time over a step of dt, builds the
    /// islands of awake bodies from the joints and the pairs that touched (`touching`), and puts
    /// to sleep each island that has rested long enough (zeroing its velocities).
    void update(std::span<Body> bodies, std::span<const BodyPair> touching,
                std::span<const Joint> joints, double dt, const SleepSettings& settings);

private:
    void wakeIsland(uint32_t index);
    uint32_t find(uint32_t index);

    std::vector<double> restTime_;
    std::vector<uint8_t> asleep_;
    std::vector<uint8_t> moved_;        ///< static bodies changed since the last step
    std::vector<uint32_t> nextInIsland_;  ///< a sleeping island's bodies, a circular list
    std::vector<uint32_t> parent_;      ///< union-find scratch of update()
    std::vector<double> islandRest_;    ///< per union-find root: its bodies' least rest time
    std::vector<uint32_t> islandLast_;  ///< per root: the body last linked into its list
    bool anyMoved_ = false;
    int sleeping_ = 0;
    uint64_t changes_ = 0;
};

}  // namespace substep

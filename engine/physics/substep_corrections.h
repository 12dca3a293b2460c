#pragma once
/// What each constraint did in one substep: for every joint and every contact pair the position
/// solve projected, the displacement of each of its bodies' centres of mass and the rotation it
/// gave each of them (summed over the substep's iterations). The viewer draws these when it
/// steps one substep at a time (issue 20: which constraint moved what, by how much).
///
/// Recorded, not derived from the multipliers: a joint's stored impulses (joint_parts.h) give a
/// body's displacement exactly (Eq. 6, Δx = p / m), but its rotation is Σ I⁻¹ (r × p) over parts
/// whose lever arms r change from part to part and from iteration to iteration, the quaternion
/// update (Eq. 8, Eq. 9) is not linear, and a contact patch's friction rows keep no directions.
/// Reading the bodies' poses (Gauss-Seidel) or the gathered deltas (Jacobi) before and after each
/// constraint's projection is exact for every type and both solvers. The world records only while
/// World::recordCorrections is on; otherwise its solve runs the plain loops and pays nothing.

#include "physics/body.h"
#include "physics/contact.h"
#include "physics/correction.h"
#include "physics/joint_block_solve.h"
#include "physics/joints/joint.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace substep {

class SoftSystem;

/// Which kind of constraint a correction comes from.
enum class ConstraintKind : uint8_t {
    Joint,    ///< World::joints()[index]
    Contact,  ///< World::contactPairs()[index] (the pairs of the current frame)
    /// The soft bodies' attachments (all of them), as they moved one rigid body (body0 == body1).
    SoftAttachments,
    /// The soft bodies' particle contacts (all of them), as they moved one rigid body.
    SoftContacts,
};

/// A soft-body stage of the substep (soft_system.h), whose per-particle corrections are kept.
enum class SoftStage : uint8_t {
    Elements,           ///< shape matching (and volume), position solve
    Attachments,        ///< particles held to rigid bodies (Eqs. 2-9), position solve
    Contacts,           ///< particle contacts (Eqs. 26-28), position solve
    ContactVelocities,  ///< particle contacts in the velocity pass (Eqs. 29-34): velocities
};
inline constexpr int kSoftStages = 4;

/// What one constraint moved in one substep (world axes; body 0 and 1 as the constraint names
/// them; a static body's motion is zero).
struct ConstraintCorrection {
    ConstraintKind kind = ConstraintKind::Joint;
    uint32_t index = 0;
    uint32_t body0 = 0;
    uint32_t body1 = 0;
    Vec3 displacement0 = Vec3::Zero();  ///< of body 0's centre of mass (m)
    Vec3 rotation0 = Vec3::Zero();      ///< rotation vector of body 0 (rad)
    Vec3 displacement1 = Vec3::Zero();
    Vec3 rotation1 = Vec3::Zero();
};

/// What one constraint changed in one substep's velocity pass (Eqs. 29-35: joint damping,
/// restitution, dynamic friction; world axes; a static body's change is zero).
struct VelocityCorrection {
    ConstraintKind kind = ConstraintKind::Contact;
    uint32_t index = 0;
    uint32_t body0 = 0;
    uint32_t body1 = 0;
    Vec3 velocity0 = Vec3::Zero();         ///< change of body 0's centre-of-mass velocity (m/s)
    Vec3 angularVelocity0 = Vec3::Zero();  ///< change of body 0's angular velocity (rad/s)
    Vec3 velocity1 = Vec3::Zero();
    Vec3 angularVelocity1 = Vec3::Zero();
};

/// The corrections of the last substep the world solved, in solve order (joints, then contact
/// pairs, then what the soft bodies' attachments and contacts moved of each rigid body). Filled
/// by the world's position solve and velocity pass while recording.
class SubstepCorrections {
  public:
    std::span<const ConstraintCorrection> constraints() const { return constraints_; }
    /// The velocity pass's changes, in its order (joint damping, then contact pairs; the soft
    /// contacts' share of each rigid body last, as SoftContacts).
    std::span<const VelocityCorrection> velocityChanges() const { return velocityChanges_; }
    /// Per particle of the soft system (SoftSystem::particlePositions' order), what `stage` did
    /// to it in this substep: a displacement (m), or for ContactVelocities a velocity change
    /// (m/s). Empty when the world has no soft bodies.
    std::span<const Vec3> particleCorrections(SoftStage stage) const {
        return particles_[static_cast<int>(stage)];
    }
    /// The substep they belong to: 1-based within the frame, of frameSubsteps() in all.
    int substep() const { return substep_; }
    int frameSubsteps() const { return frameSubsteps_; }

    /// Called by the world: a new substep begins (what was recorded is dropped).
    void beginSubstep(int substep, int frameSubsteps);
    /// Called by the world in place of its plain loops: one iteration of the rigid position
    /// solve, joints then contact pairs, each projection recorded. `asleep` (per body, may be
    /// null) skips the joints of sleeping islands as the world does. `clusters` (may be null)
    /// solves the joints around light bodies by cluster as the world does; a cluster is one
    /// projection, recorded under its first joint with that joint's two bodies.
    void solveRecorded(std::span<Joint> joints, const uint8_t* asleep, JointBlockSolver* clusters,
                       std::span<ContactPair> pairs, std::span<Contact> contacts, SolverContext& ctx);
    /// Called by the world in place of SoftSystem::solvePositions: one iteration of the soft
    /// bodies' stages, each particle's and each rigid body's motion recorded per stage.
    void solveSoftRecorded(SoftSystem& soft, std::size_t bodyCount, SolverContext& ctx);

    /// Called by the world's velocity pass around one constraint's velocity solve: the
    /// velocities before it, then what it changed (the next entry of velocityChanges()).
    struct VelocitiesBefore {
        Vec3 v0, w0, v1, w1;
    };
    static VelocitiesBefore captureVelocities(const Body* bodies, uint32_t body0, uint32_t body1);
    void recordVelocities(const Body* bodies, ConstraintKind kind, uint32_t index, uint32_t body0,
                          uint32_t body1, const VelocitiesBefore& before);
    /// Called by the world in place of SoftSystem::solveVelocities: the particle contacts'
    /// velocity pass, each particle's and each rigid body's change recorded.
    void solveSoftVelocitiesRecorded(SoftSystem& soft, Body* bodies, std::size_t bodyCount, double h,
                                     double gravity);

  private:
    /// A rigid body's motion (or velocity change) summed over a soft stage.
    struct BodyMotion {
        Vec3 linear = Vec3::Zero();
        Vec3 angular = Vec3::Zero();
    };
    /// Body poses (or Jacobi deltas) before a projection.
    struct Before {
        Vec3 x0, x1;
        Quat q0, q1;
        Vec3 d0, d1;  ///< Jacobi: gathered position deltas
        Vec3 r0, r1;  ///< Jacobi: gathered rotation deltas
    };
    Before capture(const SolverContext& ctx, uint32_t body0, uint32_t body1) const;
    /// Adds what the projection since `before` did to the next entry (made on the first
    /// iteration, accumulated on later ones).
    void record(const SolverContext& ctx, ConstraintKind kind, uint32_t index, uint32_t body0,
                uint32_t body1, const Before& before);

    /// Soft stage `stage` just ran: adds each particle's motion since particlesBefore_ and each
    /// rigid body's since bodiesBefore_ to its sums.
    void captureSoft(const SoftSystem& soft, std::size_t bodyCount, const SolverContext& ctx);
    void recordSoft(const SoftSystem& soft, SoftStage stage, const SolverContext& ctx);
    /// constraints() after the rigid entries: one per rigid body the soft stages moved.
    void rebuildSoftEntries();

    std::vector<ConstraintCorrection> constraints_;
    std::vector<VelocityCorrection> velocityChanges_;
    std::size_t cursor_ = 0;  ///< the entry the next projection adds to, this iteration
    std::size_t rigidEntries_ = 0;  ///< constraints_ of joints and contact pairs (the rest: soft)
    std::array<std::vector<Vec3>, kSoftStages> particles_;
    /// Per rigid body: what the soft attachments and the soft contacts moved it this substep.
    std::array<std::vector<BodyMotion>, 2> softBodyMotion_;
    std::vector<Vec3> particlesBefore_;
    std::vector<Before> bodiesBefore_;  ///< x0/q0 (and d0/r0 under Jacobi) per rigid body
    std::vector<BodyMotion> velocitiesBefore_;  ///< v, ω per rigid body before the soft velocity pass
    int substep_ = 0;
    int frameSubsteps_ = 0;
};

/// The rotation vector (rad) that turns `from` into `to` (the shorter way): the inverse of
/// integrateRotation.
Vec3 rotationBetween(const Quat& from, const Quat& to);

}  // namespace substep

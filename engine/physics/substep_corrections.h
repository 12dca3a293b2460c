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

#include <cstdint>
#include <span>
#include <vector>

namespace substep {

/// Which kind of constraint a correction comes from.
enum class ConstraintKind : uint8_t {
    Joint,    ///< World::joints()[index]
    Contact,  ///< World::contactPairs()[index] (the pairs of the current frame)
};

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

/// The corrections of the last substep the world solved, in solve order (joints, then contact
/// pairs). Filled by the world's position solve while recording.
class SubstepCorrections {
  public:
    std::span<const ConstraintCorrection> constraints() const { return constraints_; }
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

  private:
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

    std::vector<ConstraintCorrection> constraints_;
    std::size_t cursor_ = 0;  ///< the entry the next projection adds to, this iteration
    int substep_ = 0;
    int frameSubsteps_ = 0;
};

/// The rotation vector (rad) that turns `from` into `to` (the shorter way): the inverse of
/// integrateRotation.
Vec3 rotationBetween(const Quat& from, const Quat& to);

}  // namespace substep

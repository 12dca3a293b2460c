#include "physics/substep_corrections.h"

#include "physics/joints/joint_solver.h"

#include <cmath>

namespace substep {

Vec3 rotationBetween(const Quat& from, const Quat& to) {
    const Quat dq = to * from.conjugate();
    const Vec3 v = dq.w() < 0.0 ? Vec3(-dq.vec()) : Vec3(dq.vec());
    const double s = v.norm();  // sin(|θ|/2)
    if (!(s > 0.0)) return Vec3::Zero();
    return (2.0 * std::atan2(s, std::abs(dq.w())) / s) * v;
}

void SubstepCorrections::beginSubstep(int substep, int frameSubsteps) {
    constraints_.clear();
    cursor_ = 0;
    substep_ = substep;
    frameSubsteps_ = frameSubsteps;
}

SubstepCorrections::Before SubstepCorrections::capture(const SolverContext& ctx, uint32_t body0,
                                                       uint32_t body1) const {
    const Body& b0 = ctx.bodies[body0];
    const Body& b1 = ctx.bodies[body1];
    Before before{.x0 = b0.x, .x1 = b1.x, .q0 = b0.q, .q1 = b1.q};
    if (ctx.solver == SolverType::Jacobi) {
        before.d0 = ctx.deltas[body0].position;
        before.d1 = ctx.deltas[body1].position;
        before.r0 = ctx.deltas[body0].rotation;
        before.r1 = ctx.deltas[body1].rotation;
    }
    return before;
}

void SubstepCorrections::record(const SolverContext& ctx, ConstraintKind kind, uint32_t index,
                                uint32_t body0, uint32_t body1, const Before& before) {
    if (cursor_ == constraints_.size())
        constraints_.push_back({.kind = kind, .index = index, .body0 = body0, .body1 = body1});
    ConstraintCorrection& entry = constraints_[cursor_++];
    const Body& b0 = ctx.bodies[body0];
    const Body& b1 = ctx.bodies[body1];
    if (ctx.solver == SolverType::Jacobi) {
        // The bodies stay put until the iteration's end; the gathered deltas are what moved.
        entry.displacement0 += ctx.deltas[body0].position - before.d0;
        entry.rotation0 += ctx.deltas[body0].rotation - before.r0;
        if (body1 != body0) {
            entry.displacement1 += ctx.deltas[body1].position - before.d1;
            entry.rotation1 += ctx.deltas[body1].rotation - before.r1;
        }
        return;
    }
    entry.displacement0 += b0.x - before.x0;
    entry.rotation0 += rotationBetween(before.q0, b0.q);
    if (body1 != body0) {
        entry.displacement1 += b1.x - before.x1;
        entry.rotation1 += rotationBetween(before.q1, b1.q);
    }
}

void SubstepCorrections::solveRecorded(std::span<Joint> joints, const uint8_t* asleep,
                                       JointBlockSolver* clusters, std::span<ContactPair> pairs,
                                       std::span<Contact> contacts, SolverContext& ctx) {
    // Each iteration visits the same constraints in the same order, so entry k is the same
    // constraint in every iteration of the substep.
    cursor_ = 0;
    for (std::size_t j = 0; j < joints.size(); ++j) {
        Joint& joint = joints[j];
        if (!joint.alive || (asleep != nullptr && (asleep[joint.body0] | asleep[joint.body1]) != 0))
            continue;
        const bool clustered = clusters != nullptr && clusters->clustered(static_cast<uint32_t>(j));
        if (clustered && !clusters->leadsCluster(static_cast<uint32_t>(j))) continue;
        const Before before = capture(ctx, joint.body0, joint.body1);
        if (clustered) clusters->solveAt(ctx, joints, static_cast<uint32_t>(j));
        else solveJointPositions(joint, ctx);
        record(ctx, ConstraintKind::Joint, static_cast<uint32_t>(j), joint.body0, joint.body1,
               before);
    }
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        ContactPair& pair = pairs[p];
        if (pair.count == 0) continue;
        const Before before = capture(ctx, pair.body0, pair.body1);
        solveContactPositions(pair, contacts.subspan(pair.first, pair.count), ctx);
        record(ctx, ConstraintKind::Contact, static_cast<uint32_t>(p), pair.body0, pair.body1,
               before);
    }
}

}  // namespace substep

#include "physics/substep_corrections.h"

#include "physics/joints/joint_solver.h"
#include "physics/soft/soft_system.h"

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
    velocityChanges_.clear();
    for (std::vector<Vec3>& particles : particles_) particles.clear();
    for (std::vector<BodyMotion>& motion : softBodyMotion_) motion.clear();
    cursor_ = 0;
    rigidEntries_ = 0;
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
    rigidEntries_ = cursor_;
}

void SubstepCorrections::captureSoft(const SoftSystem& soft, std::size_t bodyCount,
                                     const SolverContext& ctx) {
    const std::span<const Vec3> x = soft.particlePositions();
    particlesBefore_.assign(x.begin(), x.end());
    bodiesBefore_.resize(bodyCount);
    for (std::size_t i = 0; i < bodyCount; ++i) {
        const auto index = static_cast<uint32_t>(i);
        bodiesBefore_[i] = capture(ctx, index, index);
    }
}

void SubstepCorrections::recordSoft(const SoftSystem& soft, SoftStage stage,
                                    const SolverContext& ctx) {
    const std::span<const Vec3> x = soft.particlePositions();
    std::vector<Vec3>& moved = particles_[static_cast<int>(stage)];
    if (moved.size() != x.size()) moved.assign(x.size(), Vec3::Zero());
    for (std::size_t i = 0; i < x.size() && i < particlesBefore_.size(); ++i)
        moved[i] += x[i] - particlesBefore_[i];
    if (stage != SoftStage::Attachments && stage != SoftStage::Contacts) return;
    // Only the coupling stages move rigid bodies: the attachments and contacts pulling them.
    std::vector<BodyMotion>& bodies =
        softBodyMotion_[stage == SoftStage::Attachments ? 0 : 1];
    if (bodies.size() != bodiesBefore_.size()) bodies.assign(bodiesBefore_.size(), BodyMotion{});
    for (std::size_t i = 0; i < bodiesBefore_.size(); ++i) {
        const Body& b = ctx.bodies[i];
        const Before& before = bodiesBefore_[i];
        if (b.invMass == 0.0) continue;
        if (ctx.solver == SolverType::Jacobi) {
            bodies[i].linear += ctx.deltas[i].position - before.d0;
            bodies[i].angular += ctx.deltas[i].rotation - before.r0;
        } else {
            bodies[i].linear += b.x - before.x0;
            bodies[i].angular += rotationBetween(before.q0, b.q);
        }
    }
}

void SubstepCorrections::rebuildSoftEntries() {
    constraints_.resize(rigidEntries_);
    const ConstraintKind kinds[2] = {ConstraintKind::SoftAttachments, ConstraintKind::SoftContacts};
    for (int stage = 0; stage < 2; ++stage) {
        const std::vector<BodyMotion>& bodies = softBodyMotion_[stage];
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            if (bodies[i].linear.isZero(0.0) && bodies[i].angular.isZero(0.0)) continue;
            const auto index = static_cast<uint32_t>(i);
            constraints_.push_back({.kind = kinds[stage],
                                    .index = index,
                                    .body0 = index,
                                    .body1 = index,
                                    .displacement0 = bodies[i].linear,
                                    .rotation0 = bodies[i].angular});
        }
    }
}

void SubstepCorrections::solveSoftRecorded(SoftSystem& soft, std::size_t bodyCount,
                                           SolverContext& ctx) {
    // SoftSystem::solvePositions' stages one by one, each diffed: the particles' motion per
    // stage, and the rigid bodies' (the only other thing they move).
    captureSoft(soft, bodyCount, ctx);
    soft.solveElements(ctx.invH2);
    recordSoft(soft, SoftStage::Elements, ctx);
    captureSoft(soft, bodyCount, ctx);
    soft.solveAttachments(ctx);
    recordSoft(soft, SoftStage::Attachments, ctx);
    captureSoft(soft, bodyCount, ctx);
    soft.solveContacts(ctx);
    recordSoft(soft, SoftStage::Contacts, ctx);
    rebuildSoftEntries();
}

SubstepCorrections::VelocitiesBefore SubstepCorrections::captureVelocities(const Body* bodies,
                                                                         uint32_t body0,
                                                                         uint32_t body1) {
    return {.v0 = bodies[body0].v, .w0 = bodies[body0].omega, .v1 = bodies[body1].v, .w1 = bodies[body1].omega};
}

void SubstepCorrections::recordVelocities(const Body* bodies, ConstraintKind kind, uint32_t index,
                                          uint32_t body0, uint32_t body1,
                                          const VelocitiesBefore& before) {
    VelocityCorrection entry{.kind = kind, .index = index, .body0 = body0, .body1 = body1};
    entry.velocity0 = bodies[body0].v - before.v0;
    entry.angularVelocity0 = bodies[body0].omega - before.w0;
    if (body1 != body0) {
        entry.velocity1 = bodies[body1].v - before.v1;
        entry.angularVelocity1 = bodies[body1].omega - before.w1;
    }
    velocityChanges_.push_back(entry);
}

void SubstepCorrections::solveSoftVelocitiesRecorded(SoftSystem& soft, Body* bodies,
                                                     std::size_t bodyCount, double h, double gravity) {
    const std::span<const Vec3> v = soft.particleVelocities();
    particlesBefore_.assign(v.begin(), v.end());
    std::vector<BodyMotion>& before = velocitiesBefore_;
    before.resize(bodyCount);
    for (std::size_t i = 0; i < bodyCount; ++i) before[i] = {bodies[i].v, bodies[i].omega};
    soft.solveVelocities(bodies, h, gravity);
    std::vector<Vec3>& changed = particles_[static_cast<int>(SoftStage::ContactVelocities)];
    changed.assign(v.size(), Vec3::Zero());
    for (std::size_t i = 0; i < v.size() && i < particlesBefore_.size(); ++i) changed[i] = v[i] - particlesBefore_[i];
    for (std::size_t i = 0; i < bodyCount; ++i) {
        const Vec3 linear = bodies[i].v - before[i].linear;
        const Vec3 angular = bodies[i].omega - before[i].angular;
        if (linear.isZero(0.0) && angular.isZero(0.0)) continue;
        const auto index = static_cast<uint32_t>(i);
        velocityChanges_.push_back({.kind = ConstraintKind::SoftContacts,
                                    .index = index,
                                    .body0 = index,
                                    .body1 = index,
                                    .velocity0 = linear,
                                    .angularVelocity0 = angular});
    }
}

}  // namespace substep

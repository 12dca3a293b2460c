#include "physics/world.h"

#include "physics/step_cancellation.h"
#include "physics/substep_corrections.h"

#include "physics/constraint_colouring.h"
#include "physics/gyroscopic_step.h"
#include "physics/joint_block_solve.h"
#include "physics/joints/joint_frame.h"
#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_solver.h"
#include "physics/soft/soft_system.h"
#include "physics/worker_pool.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace substep {
namespace {

using Clock = std::chrono::steady_clock;

/// Whether a body takes part in collision detection.
bool collides(const Body& b) { return b.alive && b.collide && b.shape.type != ShapeType::None; }

/// The type's own parameters from its definition (`joint` has its frames already, for the
/// hinge motor's starting angle). Keys a type does not use are ignored (the loader rejects
/// them in files).
JointModel makeJointModel(const JointDef& def, const Joint& joint, const Body* bodies) {
    // A velocity motor starts from the current hinge angle; a position drive from its target.
    JointDrive drive = JointDrive::None;
    double target = 0.0;
    if (def.targetVelocity) {
        drive = JointDrive::Velocity;
        target = def.type == JointType::Hinge ? hingeAngle(joint, bodies) : 0.0;
    } else if (def.targetAngle || def.targetOffset) {
        drive = JointDrive::Position;
        target = def.targetAngle ? *def.targetAngle : *def.targetOffset;
    }
    switch (def.type) {
        case JointType::Distance: return DistanceJoint{.maxDistance = def.maxDistance};
        case JointType::Fixed: return FixedJoint{};
        case JointType::Hinge:
            return HingeJoint{.hasLimits = def.limits.has_value(),
                              .limits = def.limits.value_or(Range{}),
                              .limitCompliance = def.limitCompliance,
                              .drive = drive,
                              .target = target,
                              .targetVelocity = def.targetVelocity.value_or(0.0),
                              .driveCompliance = def.driveCompliance};
        case JointType::Spherical:
            return SphericalJoint{.hasSwingLimit = def.swingLimit.has_value(),
                                  .swingLimit = def.swingLimit.value_or(0.0),
                                  .swingCompliance = def.limitCompliance,
                                  .hasTwistLimits = def.twistLimits.has_value(),
                                  .twistLimits = def.twistLimits.value_or(Range{}),
                                  .twistCompliance = def.twistCompliance.value_or(def.limitCompliance)};
        case JointType::Prismatic:
            return PrismaticJoint{.hasLimits = def.limits.has_value(),
                                  .limits = def.limits.value_or(Range{}),
                                  .limitCompliance = def.limitCompliance,
                                  .drive = drive == JointDrive::Position ? drive : JointDrive::None,
                                  .target = target,
                                  .driveCompliance = def.driveCompliance};
    }
    return DistanceJoint{};
}

}  // namespace

void World::setJointParameters(Joint& joint, const JointDef& def) {
    // Anchors and frames go from each body's user frame into its principal frame; the world's
    // are already in world coordinates.
    const Body& b0 = bodies_[joint.body0];
    const Body& b1 = bodies_[joint.body1];
    joint.anchor0 = b0.userRotation * def.anchor0 + b0.userOrigin;
    joint.anchor1 = b1.userRotation * def.anchor1 + b1.userOrigin;
    joint.frame0 = (b0.userRotation * jointFrame(def.axis0, def.normal0)).normalized();
    joint.frame1 = (b1.userRotation * jointFrame(def.axis1, def.normal1)).normalized();
    joint.compliance = def.compliance;
    joint.model = makeJointModel(def, joint, bodies_.data());
    joint.linearDamping = def.linearDamping;
    joint.angularDamping = def.angularDamping;
    joint.collide = def.collide;
}

void World::invalidHandle(const char* what, uint32_t index, uint32_t generation) const {
    const std::string message = std::string("World::") + what + ": invalid or stale handle {index " +
                                std::to_string(index) + ", generation " + std::to_string(generation) +
                                "} (destroyed, never created, or from another world)";
#ifndef NDEBUG
    std::fputs((message + "\n").c_str(), stderr);
    assert(!"invalid handle");
    std::abort();
#else
    throw std::invalid_argument(message);
#endif
}

World::World(const WorldSettings& settings) : settings_(settings) {
    // Index 0 is the world itself: a static body at the origin that joints "to the world"
    // attach to, so the solver never tests for a missing body.
    Body anchor;
    anchor.alive = true;
    anchor.generation = 0;
    bodies_.push_back(anchor);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

bool World::hasSoftBodies() const { return soft_ && !soft_->empty(); }

SoftBodyId World::createSoftBody(const SoftBodyDef& def) {
    if (!soft_) soft_ = std::make_unique<SoftSystem>();
    return soft_->create(def, bodies_, nextGeneration_++);
}

void World::destroySoftBody(SoftBodyId id) {
    if (soft_) soft_->destroy(id);
}

bool World::isValid(SoftBodyId id) const { return soft_ && soft_->isValid(id); }

SoftBodyReadout World::softBodyReadout(SoftBodyId id) const {
    return soft_ ? soft_->readout(id) : SoftBodyReadout{};
}

SoftSurface World::softBodySurface(SoftBodyId id) const { return soft_ ? soft_->surface(id) : SoftSurface{}; }

std::span<const Vec3> World::softBodyPositions(SoftBodyId id) const {
    return soft_ ? soft_->positions(id) : std::span<const Vec3>{};
}

BodyId World::createBody(const BodyDef& def) {
    Body body = makeBody(def);
    body.generation = nextGeneration_++;
    uint32_t index;
    if (!freeBodies_.empty()) {
        index = freeBodies_.back();
        freeBodies_.pop_back();
        bodies_[index] = body;
    } else {
        index = static_cast<uint32_t>(bodies_.size());
        bodies_.push_back(body);
    }
    if (collides(body)) ++collidingBodies_;
    sleep_.resize(bodies_.size());
    if (frame_.open) {
        // Created between substeps (a script or the window's substep view): the frame's
        // per-body scratch grows with it, and the sleep flags the substeps read may have moved.
        // It is not posed for contacts (reach 0) and joins the pairs next frame.
        if (reaches_.size() < bodies_.size()) reaches_.resize(bodies_.size(), 0.0);
        if (poses_.size() < bodies_.size()) poses_.resize(bodies_.size());
        if (settings_.solver == SolverType::Jacobi && jacobiDeltas_.size() < bodies_.size())
            jacobiDeltas_.resize(bodies_.size(), JacobiDelta{});
        if (sleepFlags_) sleepFlags_ = sleep_.flags();
    }
    return {index, body.generation};
}

void World::destroyBody(BodyId id) {
    if (!isValid(id)) return;
    // What it held up or touched wakes (its joints wake their bodies as they go).
    wakeBody(id);
    for (const ContactPair& pair : contactPairs_)
        if (pair.body0 == id.index || pair.body1 == id.index)
            sleep_.wake(pair.body0 == id.index ? pair.body1 : pair.body0,
                        bodies_[pair.body0 == id.index ? pair.body1 : pair.body0]);
    for (uint32_t j = 0; j < joints_.size(); ++j) {
        const Joint& joint = joints_[j];
        if (joint.alive && (joint.body0 == id.index || joint.body1 == id.index))
            destroyJoint({j, joint.generation});
    }
    if (collides(bodies_[id.index])) --collidingBodies_;
    if (soft_) soft_->forgetBody(id.index);
    bodies_[id.index] = Body{};  // dead: static, never integrated
    freeBodies_.push_back(id.index);
}

JointId World::createJoint(const JointDef& def) {
    Joint joint;
    joint.body0 = def.body0.isNull() ? 0 : def.body0.index;
    joint.body1 = def.body1.isNull() ? 0 : def.body1.index;
    setJointParameters(joint, def);
    joint.alive = true;
    joint.generation = nextGeneration_++;
    repairPending_ = true;
    sleep_.wake(joint.body0, bodies_[joint.body0]);
    sleep_.wake(joint.body1, bodies_[joint.body1]);
    jointsChanged_ = true;
    clustersChanged_ = true;

    uint32_t index;
    if (!freeJoints_.empty()) {
        index = freeJoints_.back();
        freeJoints_.pop_back();
        joints_[index] = joint;
    } else {
        index = static_cast<uint32_t>(joints_.size());
        joints_.push_back(joint);
    }
    return {index, joint.generation};
}

void World::destroyJoint(JointId id) {
    if (!isValid(id)) return;
    sleep_.wake(joints_[id.index].body0, bodies_[joints_[id.index].body0]);
    sleep_.wake(joints_[id.index].body1, bodies_[joints_[id.index].body1]);
    joints_[id.index] = Joint{};
    freeJoints_.push_back(id.index);
    jointsChanged_ = true;
    clustersChanged_ = true;
}

void World::step(double dt) {
    beginFrame(dt);
    while (frame_.open && frame_.done < frame_.substeps) {
        if (stepCancellationRequested()) break;  // SIGINT/SIGTERM: the caller discards the world
        substep();
    }
    endFrame();
}

void World::lap(double& bucket) {
    if (!settings_.measureTime) return;
    const auto now = Clock::now();
    bucket += std::chrono::duration<double, std::milli>(now - lapMark_).count();
    lapMark_ = now;
}

void World::beginFrame(double dt) {
    // A frame still open is abandoned, not finished: callers that step substeps by hand finish
    // theirs first (LiveScene::step does).
    frame_ = {};
    if (!(dt > 0.0) || !std::isfinite(dt)) return;
    const int substeps = std::max(settings_.substeps, 1);
    const double h = dt / substeps;
    lastSubstep_ = h;
    if (settings_.solver == SolverType::Jacobi) jacobiDeltas_.assign(bodies_.size(), JacobiDelta{});

    if (repairPending_) {
        repairPending_ = false;
        // The repair moves bodies by hand, sleeping ones included: everything wakes.
        if (settings_.sleeping) sleep_.wakeAll();
        if (settings_.repairDistance > 0.0 && settings_.repairAngle > 0.0) repairLargeViolations(h);
    }

    // Damping may be set on a live joint (world.joint(id)), so whether any joint damps is asked
    // once a frame rather than remembered from creation.
    anyDamping_ = std::any_of(joints_.begin(), joints_.end(), [](const Joint& joint) {
        return joint.alive && (joint.linearDamping > 0.0 || joint.angularDamping > 0.0);
    });

    // Each stage's time goes to its bucket when measuring (a clock read per stage).
    stepTimes_ = {};
    if (settings_.measureTime) lapMark_ = Clock::now();

    // Algorithm 2: pairs once per frame, their contacts on the current poses every substep.
    collectContactPairs(dt);
    // Sleeping: islands an awake body may reach this frame wake before any substep, so no
    // awake body ever meets a sleeping one in the solve (sleep_islands.h).
    const bool sleeping = sleepingActive();
    if (sleeping) sleep_.wakeLinked(bodies_, contactPairs_, joints_);
    sleepFlags_ = sleeping && sleep_.sleepingCount() > 0 ? sleep_.flags() : nullptr;
    if (sleepFlags_) listAwake(true);
    if (sleeping) pairTouched_.assign(contactPairs_.size(), 0);
    const bool soft = hasSoftBodies();
    if (soft) soft_->setPatchFriction(settings_.softPatchFriction);
    if (soft) soft_->setHeldContacts(settings_.softHeldContacts);
    if (soft) soft_->collectCandidates(bodies_, dt, settings_.contactMargin, settings_.gravity, workerPool());
    // The parallel step's order (world_parallel.cpp); recording corrections keeps the serial one.
    const bool coloured = colouredSolveActive() && !corrections_;
    if (coloured) colourConstraints();
    lap(stepTimes_.broadphase);
    frame_ = {.open = true, .dt = dt, .h = h, .substeps = substeps, .done = 0, .sleeping = sleeping, .soft = soft,
              .coloured = coloured};
}

bool World::substep() {
    if (!frame_.open || frame_.done >= frame_.substeps) return false;
    const double h = frame_.h;
    const bool soft = frame_.soft;
    if (settings_.measureTime) lapMark_ = Clock::now();
    if (sleepFlags_) listAwake(false);  // an edit between substeps may have woken an island
    if (corrections_) corrections_->beginSubstep(frame_.done + 1, frame_.substeps);
    // λ is zeroed before each substep's solve (paper 3.3.1); motors advance their target.
    for (Joint& joint : joints_)
        if (!sleeps(joint)) beginJointSubstep(joint, h);
    integrate(h);
    if (soft) soft_->integrate(h, settings_.gravity, workerPool());
    lap(stepTimes_.integrate);
    if (!contactPairs_.empty()) findContacts(frame_.sleeping);
    else touchingPairs_.clear();
    if (frame_.coloured)
        groupTouchingPairs();
    else
        contactSchedule_.plan(touchingPairs_, contactPairs_, bodies_);
    if (soft) soft_->findContacts(bodies_, settings_.contactMargin, workerPool());
    if (soft) soft_->holdContactParticles();  // none unless SoftSystem::setHeldContacts
    lap(stepTimes_.narrowphase);
    for (int i = 0; i < settings_.iterations; ++i) solvePositions(h);
    lap(stepTimes_.solve);
    deriveVelocities(h);
    if (soft) soft_->deriveVelocities(h, workerPool());
    lap(stepTimes_.integrate);
    if (settings_.velocityPass && (anyDamping_ || !contacts_.empty())) solveVelocities(h);
    if (soft && settings_.velocityPass) {
        if (corrections_) [[unlikely]]
            corrections_->solveSoftVelocitiesRecorded(*soft_, bodies_.data(), bodies_.size(), h, settings_.gravity.norm());
        else
            soft_->solveVelocities(bodies_.data(), h, settings_.gravity.norm(), workerPool());
    }
    lap(stepTimes_.velocities);
    ++frame_.done;
    return true;
}

void World::endFrame() {
    if (!frame_.open) return;
    if (frame_.soft) soft_->damp(frame_.dt, workerPool());
    if (frame_.sleeping) {
        touching_.clear();
        for (size_t i = 0; i < contactPairs_.size(); ++i)
            if (pairTouched_[i]) touching_.push_back({contactPairs_[i].body0, contactPairs_[i].body1});
        sleep_.update(bodies_, touching_, joints_, frame_.dt, settings_.sleep);
    }
    sleepFlags_ = nullptr;
    frame_.open = false;
}

void World::recordCorrections(bool on) {
    if (!on) {
        corrections_.reset();
    } else if (!corrections_) {
        corrections_ = std::make_unique<SubstepCorrections>();
    }
}

bool World::sleepingActive() const { return settings_.sleeping && !hasSoftBodies(); }

void World::setSettings(const WorldSettings& settings) {
    // Sleeping bodies rest under the old conditions: a new gravity or sleep rule wakes them.
    const bool wake = settings.gravity != settings_.gravity || settings.sleeping != settings_.sleeping ||
                      settings.sleep.speed != settings_.sleep.speed ||
                      settings.sleep.angularSpeed != settings_.sleep.angularSpeed ||
                      settings.sleep.time != settings_.sleep.time;
    settings_ = settings;
    if (wake) sleep_.wakeAll();
}

void World::wakeBody(BodyId id) {
    if (isValid(id)) sleep_.wake(id.index, bodies_[id.index]);
}

void World::repairLargeViolations(double h) {
    // One sweep looks for hard parts that are far off (hard drives included: a hard target far
    // from the starting pose is reached here, not in one violent substep). If it finds any,
    // Gauss-Seidel sweeps over every hard part bring the violations down to 1e-5 of the
    // thresholds, so that what is left for the substeps is small. Velocities are not derived
    // from these moves, so the repair adds no kinetic energy.
    constexpr int kMaxSweeps = 2000;
    constexpr double kResidual = 1e-5;
    SolverContext ctx{.bodies = bodies_.data(),
                      .h = h,
                      .invH2 = 1.0 / (h * h),
                      .repairDistance = settings_.repairDistance,
                      .repairAngle = settings_.repairAngle};
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
        ctx.repairs = 0;
        for (Joint& joint : joints_)
            if (joint.alive) solveJointPositions(joint, ctx);
        if (ctx.repairs == 0) break;
        ctx.repairDistance = kResidual * settings_.repairDistance;
        ctx.repairAngle = kResidual * settings_.repairAngle;
    }
    for (Joint& joint : joints_) joint.resetMultipliers();
}

void World::integrate(double h) {
    const Vec3 gravityStep = h * settings_.gravity;
    const auto advance = [&](Body& b) {
        if (b.invMass == 0.0) return;
        b.xPrev = b.x;
        b.v += gravityStep;
        b.x += h * b.v;
        if (!b.rotates()) return;
        b.qPrev = b.q;
        // Algorithm 2's gyroscopic term, taken implicitly (gyroscopic_step.h); with equal
        // moments ω × Iω vanishes, so cubes and spheres skip it.
        if (!b.isotropic) b.omega = gyroscopicStep(b, h);
        integrateRotation(b.q, h * b.omega);
    };
    // While some bodies sleep, the awake ones' list alone; in chunks with more than one thread.
    forEachMovingBody(advance);
}

void World::solvePositions(double h) {
    SolverContext ctx{.bodies = bodies_.data(),
                      .h = h,
                      .invH2 = 1.0 / (h * h),
                      .solver = settings_.solver,
                      .deltas = jacobiDeltas_.data(),
                      .capPushOut = settings_.velocityPass,
                      .projection = settings_.jointProjection};
    // Joints first, contacts last: a substep ends with the hard inequalities met. Joints around
    // light bodies are solved by cluster, each cluster in the place of its first joint (a cluster
    // sleeps whole, as it is jointed together). Recording each projection's corrections (the
    // viewer's substep stepping) runs the same loops apart.
    JointBlockSolver* const clusters = blockSolveActive() ? blocks_.get() : nullptr;
    if (corrections_) [[unlikely]] {
        corrections_->solveRecorded(joints_, sleepFlags_, clusters, contactPairs_, contacts_, ctx);
    } else if (frame_.coloured) {
        solveColouredPositions(ctx, clusters);  // by colour, in parallel (world_parallel.cpp)
    } else {
        solveJointsInOrder(ctx, clusters);
        solveTouchingPositions(contactSchedule_, contactPairs_, contacts_, ctx);
    }
    // Soft bodies after the rigid ones: elements, attachments, then their contacts.
    if (hasSoftBodies()) {
        if (corrections_) [[unlikely]] corrections_->solveSoftRecorded(*soft_, bodies_.size(), ctx);
        else soft_->solvePositions(ctx, workerPool());
    }
    // Jacobi: every constraint saw the iteration's starting state; the gathered corrections
    // are summed. Averaging them, or splitting a body's mass among its joints, shifts the fixed
    // point: the joints' λ then no longer balance the weights they carry.
    if (settings_.solver == SolverType::Jacobi)
        applyJacobiDeltas(bodies_.data(), jacobiDeltas_.data(), bodies_.size());
}

void World::solveJointsInOrder(SolverContext& ctx, JointBlockSolver* clusters) {
    if (clusters != nullptr) {
        for (uint32_t j = 0; j < joints_.size(); ++j) {
            if (!joints_[j].alive || sleeps(joints_[j])) continue;
            if (clusters->clustered(j)) clusters->solveAt(ctx, joints_, j);
            else solveJointPositions(joints_[j], ctx);
        }
    } else {
        for (Joint& joint : joints_)
            if (joint.alive && !sleeps(joint)) solveJointPositions(joint, ctx);
    }
}

bool World::blockSolveActive() {
    if (!settings_.blockSolve || settings_.solver != SolverType::GaussSeidel) return false;
    if (clustersChanged_) {
        clustersChanged_ = false;
        if (!blocks_) blocks_ = std::make_unique<JointBlockSolver>();
        blocks_->build(bodies_, joints_);
    }
    return !blocks_->empty();
}

size_t World::jointClusterCount() const {
    return blocks_ && settings_.blockSolve && settings_.solver == SolverType::GaussSeidel ? blocks_->clusterCount() : 0;
}

void World::deriveVelocities(double h) {
    const double invH = 1.0 / h;
    const auto derive = [&](Body& b) {
        if (b.invMass == 0.0) return;
        b.vPrev = b.v;
        b.v = (b.x - b.xPrev) * invH;
        if (!b.rotates()) return;
        b.omegaPrev = b.omega;
        // Algorithm 2's ω = ±2 Δq_xyz / h, made exact (see angularVelocityBetween).
        b.omega = angularVelocityBetween(b.qPrev, b.q, invH);
    };
    forEachMovingBody(derive);
}

void World::solveVelocities(double h) {
    // `around(kind, index, body0, body1, solve)` runs one constraint's velocity solve: plainly,
    // or while recording (the viewer's substep stepping) with its velocity change kept. The
    // pass is written once and compiled twice, so the plain one pays nothing for it.
    const auto pass = [&](const auto& around) {
        if (anyDamping_)
            for (uint32_t j = 0; j < joints_.size(); ++j) {
                const Joint& joint = joints_[j];
                if (joint.alive && !sleeps(joint))
                    around(ConstraintKind::Joint, j, joint.body0, joint.body1,
                           [&] { solveJointVelocities(joint, bodies_.data(), h); });
            }
        const double gravity = settings_.gravity.norm();
        // Collisions first, on the velocities before the derivation, so that an impact passes
        // through touching bodies whatever their order (contact_restitution.h). Their impulses add
        // up in any order, so they all go in before Eq. 34 sets the other contacts' velocities.
        const bool collided = settings_.sweptRestitution &&
                              findRestitutionImpulses(touchingPairs_, contactPairs_, contacts_, bodies_.data(), bodies_.size(), h,
                                                      gravity, restitutionScratch_, workerPool());
        // Only the pairs the sweeps visited (RestitutionScratch::pairs, in pair order) can take it.
        if (collided)
            for (const SweepPair& swept : restitutionScratch_.pairs) {
                const uint32_t p = swept.pair;
                const ContactPair& pair = contactPairs_[p];
                if (contacts_[pair.first].collisionPass)
                    around(ConstraintKind::Contact, p, pair.body0, pair.body1,
                           [&] { solveCollisionVelocities(pair, contacts_[pair.first], bodies_.data(), h); });
            }
        if (frame_.coloured && !corrections_) return solveColouredContactVelocities(h, gravity);
        // Recording the corrections goes pair by pair (around() reads the bodies before each).
        if (!corrections_)
            return solveTouchingVelocities(contactSchedule_, contactPairs_, contacts_, bodies_.data(), h, gravity);
        for (const uint32_t p : touchingPairs_) {
            const ContactPair& pair = contactPairs_[p];
            around(ConstraintKind::Contact, p, pair.body0, pair.body1, [&] {
                solveContactVelocities(pair, std::span(contacts_).subspan(pair.first, pair.count),
                                       bodies_.data(), h, gravity);
            });
        }
    };
    if (corrections_) [[unlikely]] {
        pass([&](ConstraintKind kind, uint32_t index, uint32_t body0, uint32_t body1, const auto& solve) {
            const SubstepCorrections::VelocitiesBefore before =
                SubstepCorrections::captureVelocities(bodies_.data(), body0, body1);
            solve();
            corrections_->recordVelocities(bodies_.data(), kind, index, body0, body1, before);
        });
    } else {
        pass([](ConstraintKind, uint32_t, uint32_t, uint32_t, const auto& solve) { solve(); });
    }
}

JointReadout World::jointReadout(JointId id) const {
    if (!isValid(id)) return {};
    return readJoint(joints_[id.index], bodies_.data(), lastSubstep_);
}

Energies World::energies() const {
    Energies e;
    for (const Body& b : bodies_) {
        if (b.invMass == 0.0) continue;
        e.kinetic += 0.5 * b.mass * b.v.squaredNorm();
        if (b.rotates()) {
            const Vec3 w = b.q.conjugate() * b.omega;
            e.kinetic += 0.5 * w.dot(b.inertia.cwiseProduct(w));
        }
        e.potential -= b.mass * settings_.gravity.dot(b.x);
    }
    for (const Joint& joint : joints_)
        if (joint.alive) e.elastic += readJoint(joint, bodies_.data(), lastSubstep_).elasticEnergy;
    if (hasSoftBodies()) {
        const SoftEnergies soft = soft_->energies(settings_.gravity);
        e.kinetic += soft.kinetic;
        e.potential += soft.potential;
        e.elastic += soft.elastic;
    }
    return e;
}

double World::maxJointError() const {
    double largest = 0.0;
    for (const Joint& joint : joints_)
        if (joint.alive) largest = std::max(largest, readJoint(joint, bodies_.data(), lastSubstep_).error);
    return largest;
}

double World::maxPenetration() const {
    double deepest = 0.0;
    for (const ContactPair& pair : contactPairs_)
        for (uint32_t i = pair.first; i < pair.first + pair.count; ++i)
            deepest = std::max(deepest, contactDepth(contacts_[i], bodies_[pair.body0], bodies_[pair.body1]));
    if (hasSoftBodies()) deepest = std::max(deepest, soft_->maxPenetration(bodies_));
    return deepest;
}

int World::activeContactCount() const {
    const int soft = hasSoftBodies() ? soft_->activeContactCount() : 0;
    return soft + static_cast<int>(std::count_if(contacts_.begin(), contacts_.end(),
                                                 [](const Contact& c) { return c.lambdaNormal > 0.0; }));
}

bool World::isFinite() const {
    return std::all_of(bodies_.begin(), bodies_.end(), [](const Body& b) {
        return b.x.allFinite() && b.q.coeffs().allFinite() && b.v.allFinite() &&
               b.omega.allFinite();
    }) && (!hasSoftBodies() || soft_->isFinite());
}

}  // namespace substep

#include "physics/soft/soft_system.h"

#include "physics/soft/element_damping.h"
#include "physics/soft/rigid_mode.h"
#include "physics/soft/shape_matching.h"
#include "physics/soft/soft_body_loops.h"
#include "physics/worker_pool.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace substep {
namespace {

/// The eight corners of an element, gathered from the particle array.
inline std::array<Vec3, 8> corners(const std::vector<Vec3>& x, const HexElement& e) {
    std::array<Vec3, 8> c;
    for (int j = 0; j < 8; ++j) c[j] = x[e[j]];
    return c;
}

}  // namespace

SoftBodyId SoftSystem::create(const SoftBodyDef& def, std::span<const Body> bodies, uint32_t generation) {
    const Lattice lattice = def.type == SoftBodyType::Box
                                ? buildBoxLattice(def.size, def.cells)
                                : buildTyreLattice(def.outerRadius, def.innerRadius, def.width, def.cells);
    SoftBodyData data;
    data.firstParticle = static_cast<uint32_t>(x_.size());
    data.particleCount = static_cast<uint32_t>(lattice.positions.size());
    data.firstElement = static_cast<uint32_t>(elements_.size());
    data.elementCount = static_cast<uint32_t>(lattice.elements.size());
    data.staticFriction = def.staticFriction;
    data.dynamicFriction = def.dynamicFriction;
    data.restitution = def.restitution;
    data.radius = def.particleRadius;
    data.collide = def.collide;
    data.collisionGroup = def.collisionGroup;
    data.collisionMask = def.collisionMask;
    data.preserveVolume = def.preserveVolume;
    data.alive = true;
    data.generation = generation;
    data.quads = boundaryQuads(lattice.elements);

    const Mat3 orientation = def.orientation.normalized().toRotationMatrix();
    const size_t particleCount = x_.size() + lattice.positions.size();
    for (auto* field : {&x_, &xPrev_, &v_, &vPrev_}) field->reserve(particleCount);
    for (const Vec3& local : lattice.positions) {
        const Vec3 position = def.position + orientation * local;
        const Vec3 velocity = def.velocity + def.angularVelocity.cross(position - def.position);
        x_.push_back(position);
        xPrev_.push_back(position);
        v_.push_back(velocity);
        vPrev_.push_back(velocity);
    }
    mass_.resize(particleCount, 0.0);
    invMass_.resize(particleCount, 0.0);

    // Each element's rest offsets are its shape's (lattice.h), and its rotation maps them to
    // the world: it starts at the body's orientation times the shape's turn to the element.
    // Cells of one shape so share their offsets, scale and compliance bit for bit, and the
    // batches read them once (element_batch.h).
    const std::vector<std::array<Vec3, 8>> shapes = restShapes(lattice);
    // Elements wave by wave: the lattice's sweep order, with runs of independent elements to
    // project side by side (element_batch.h); their scale, compliance and mass from their shape.
    const Quat bodyTurn = def.orientation.normalized();
    const std::vector<uint32_t> waves = elementWaves(lattice.elements, lattice.positions.size());
    std::vector<uint32_t> order(lattice.elements.size());
    for (uint32_t k = 0; k < order.size(); ++k)
        order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return waves[a] < waves[b]; });
    for (const uint32_t k : order) {
        const HexElement& local = lattice.elements[k];
        const std::array<Vec3, 8>& rest = shapes[lattice.shape[k]];
        double scale2 = 0.0;
        for (const Vec3& q : rest) scale2 += 0.125 * q.squaredNorm();
        elementWave_.push_back(waves[k]);
        HexElement e;
        for (int j = 0; j < 8; ++j) e[j] = local[j] + data.firstParticle;
        // The volume constraint's gradients (shape_matching.h), in the world frame.
        const std::array<Vec3, 8> x = corners(x_, e);
        Vec3 centre = Vec3::Zero();
        for (const Vec3& p : x) centre += p;
        centre *= 0.125;
        Mat3 aqq = Mat3::Zero();
        for (int j = 0; j < 8; ++j) aqq.noalias() += 0.125 * (x[j] - centre) * (x[j] - centre).transpose();
        // A degenerate cell (validation keeps sizes positive) still gets a finite mass and
        // compliance rather than a division by zero.
        const double safeVolume = std::max(std::abs(hexVolume(rest)), 1e-18);
        std::array<Vec3, 8> gradients{};
        Eigen::FullPivLU<Mat3> lu(aqq);
        if (lu.isInvertible()) {
            const Mat3 aqqInverse = lu.inverse();
            for (int j = 0; j < 8; ++j) gradients[j] = 0.125 * (aqqInverse * (x[j] - centre));
        }
        const double elementMass = std::max(def.density * safeVolume, 1e-12);
        for (int j = 0; j < 8; ++j) mass_[e[j]] += 0.125 * elementMass;
        elements_.push_back(e);
        restOffsets_.push_back(rest);
        volumeGradients_.push_back(gradients);
        rotations_.push_back(bodyTurn * lattice.shapeTurn[k]);
        scale2_.push_back(std::max(scale2, 1e-18));
        compliance_.push_back(def.compliance * scale2 / safeVolume);
        volumeCompliance_.push_back(def.preserveVolume ? def.volumeCompliance / safeVolume : -1.0);
        elementDamping_.push_back(def.damping);
        lambda_.push_back(0.0);
        volumeLambda_.push_back(0.0);
    }
    for (uint32_t i = data.firstParticle; i < particleCount; ++i) {
        if (!(mass_[i] > 0.0)) mass_[i] = 1e-12;  // a particle in no element
        invMass_[i] = 1.0 / mass_[i];
        data.mass += mass_[i];
    }
    const auto firstBatch = static_cast<uint32_t>(batches_.size());
    appendBatches(elementArrays(), std::span(elementWave_).subspan(data.firstElement),
                  data.firstElement, data.elementCount, batches_, batchShapes_);
    bodyBatches_.emplace_back(firstBatch, static_cast<uint32_t>(batches_.size()));
    indexParticleBatches();
    addAttachments(def, data, lattice, bodies);

    uint32_t index;
    if (!freeBodies_.empty()) {
        index = freeBodies_.back();
        freeBodies_.pop_back();
        bodies_[index] = std::move(data);
    } else {
        index = static_cast<uint32_t>(bodies_.size());
        bodies_.push_back(std::move(data));
    }
    ++liveBodies_;
    return {index, generation};
}

void SoftSystem::destroy(SoftBodyId id) {
    if (!isValid(id)) return;
    SoftBodyData& dead = bodies_[id.index];
    const uint32_t firstParticle = dead.firstParticle, particleCount = dead.particleCount;
    const uint32_t endParticle = firstParticle + particleCount;
    const uint32_t firstElement = dead.firstElement, elementCount = dead.elementCount;
    const auto eraseParticles = [&](auto& field) {
        field.erase(field.begin() + firstParticle, field.begin() + endParticle);
    };
    const auto eraseElements = [&](auto& field) {
        field.erase(field.begin() + firstElement, field.begin() + firstElement + elementCount);
    };
    eraseParticles(x_), eraseParticles(xPrev_), eraseParticles(v_), eraseParticles(vPrev_);
    eraseParticles(mass_), eraseParticles(invMass_);
    eraseElements(elements_), eraseElements(elementWave_), eraseElements(restOffsets_);
    eraseElements(volumeGradients_);
    eraseElements(rotations_), eraseElements(scale2_), eraseElements(compliance_);
    eraseElements(volumeCompliance_), eraseElements(elementDamping_), eraseElements(lambda_), eraseElements(volumeLambda_);
    // Later bodies' particles moved down by the removed count.
    for (HexElement& e : elements_)
        for (uint32_t& i : e)
            if (i >= endParticle) i -= particleCount;
    for (SoftBodyData& other : bodies_) {
        if (!other.alive || &other == &dead) continue;
        if (other.firstParticle >= endParticle) other.firstParticle -= particleCount;
        if (other.firstElement > firstElement) other.firstElement -= elementCount;
    }
    std::erase_if(attachments_, [&](const Attachment& a) {
        return a.particle >= firstParticle && a.particle < endParticle;
    });
    for (Attachment& a : attachments_)
        if (a.particle >= endParticle) a.particle -= particleCount;
    for (BodyCandidates& own : bodyCandidates_) own.clear();
    contacts_.clear();
    attachmentsChanged();
    dead = SoftBodyData{};
    freeBodies_.push_back(id.index);
    --liveBodies_;
    rebuildBatches();
    for (SoftBodyData& body : bodies_) body.momentsKept = false;
}

ElementArrays SoftSystem::elementArrays() {
    return {.positions = x_,
            .elements = elements_,
            .restOffsets = restOffsets_,
            .volumeGradients = volumeGradients_,
            .rotations = rotations_,
            .scale2 = scale2_,
            .compliance = compliance_,
            .volumeCompliance = volumeCompliance_,
            .lambda = lambda_,
            .volumeLambda = volumeLambda_,
            .invMass = invMass_,
            .shapes = batchShapes_,
            .holdNormals = holdNormal_,
            .heldBatches = heldBatches_,
            .heldImpulse = heldImpulse_};
}

void SoftSystem::rebuildBatches() {
    bodiesApart_ = false;  // the shares name the old batches: the serial solve until findContacts
    batches_.clear();
    batchShapes_.clear();
    bodyBatches_.clear();
    const ElementArrays arrays = elementArrays();
    for (const SoftBodyData& body : bodies_) {
        if (!body.alive) continue;
        const auto firstBatch = static_cast<uint32_t>(batches_.size());
        appendBatches(arrays, std::span(elementWave_).subspan(body.firstElement), body.firstElement,
                      body.elementCount, batches_, batchShapes_);
        bodyBatches_.emplace_back(firstBatch, static_cast<uint32_t>(batches_.size()));
    }
    indexParticleBatches();
}

void SoftSystem::indexParticleBatches() {
    const size_t particles = x_.size();
    holdNormal_.assign(particles, Vec3::Zero());
    heldImpulse_.assign(particles, 0.0);
    heldParticles_.clear();
    heldBatches_.assign(batches_.size(), 0);
    // Counting sort of the (particle, batch) pairs by particle.
    particleBatchStart_.assign(particles + 1, 0);
    for (const ElementBatch& batch : batches_)
        for (uint32_t l = 0; l < batch.lanes; ++l)
            for (int j = 0; j < 8; ++j) ++particleBatchStart_[batch.particle[j][l] + 1];
    for (size_t i = 0; i < particles; ++i) particleBatchStart_[i + 1] += particleBatchStart_[i];
    particleBatches_.resize(particleBatchStart_[particles]);
    std::vector<uint32_t> next(particleBatchStart_.begin(), particleBatchStart_.end() - 1);
    for (uint32_t b = 0; b < batches_.size(); ++b)
        for (uint32_t l = 0; l < batches_[b].lanes; ++l)
            for (int j = 0; j < 8; ++j) particleBatches_[next[batches_[b].particle[j][l]]++] = b;
}

void SoftSystem::holdContactParticles() {
    for (const uint32_t i : heldParticles_) {
        holdNormal_[i] = Vec3::Zero();
        heldImpulse_[i] = 0.0;
        for (uint32_t k = particleBatchStart_[i]; k < particleBatchStart_[i + 1]; ++k) heldBatches_[particleBatches_[k]] = 0;
    }
    heldParticles_.clear();
    if (!heldContacts_) return;
    // Every particle with a contact (touching, or within the margin: holding only those touching
    // after the prediction, a particle an element had lifted off by a hair was pushed in by
    // the next substep's elements and the tyres jittered) is held along its contacts' normal
    // (their sum, normalised).
    for (const ParticleContact& c : contacts_) {
        Vec3& n = holdNormal_[c.particle];
        if (n.isZero(0.0)) heldParticles_.push_back(c.particle);
        n += c.normal;
    }
    for (const uint32_t i : heldParticles_) {
        const double length = holdNormal_[i].norm();
        holdNormal_[i] = length > kDirectionEpsilon ? Vec3(holdNormal_[i] / length) : Vec3::Zero();
        for (uint32_t k = particleBatchStart_[i]; k < particleBatchStart_[i + 1]; ++k) heldBatches_[particleBatches_[k]] = 1;
    }
}

bool SoftSystem::isValid(SoftBodyId id) const {
    return !id.isNull() && id.index < bodies_.size() && bodies_[id.index].alive &&
           bodies_[id.index].generation == id.generation;
}

void SoftSystem::forgetBody(uint32_t bodyIndex) {
    for (SoftBodyData& body : bodies_) std::erase(body.attachedBodies, bodyIndex);
    std::erase_if(attachments_, [&](const Attachment& a) { return a.body == bodyIndex; });
    for (BodyCandidates& own : bodyCandidates_) {
        size_t kept = 0;
        for (size_t k = 0; k < own.candidates.size(); ++k) {
            if (own.candidates[k].body == bodyIndex) continue;
            own.candidates[kept] = own.candidates[k];
            own.skips.move(k, kept++);
        }
        own.candidates.resize(kept);
        own.skips.resize(kept);
    }
    attachmentsChanged();
    std::erase_if(contacts_, [&](const ParticleContact& c) { return c.body == bodyIndex; });
    bodiesApart_ = false;  // the shares' contact ranges are gone: the serial solve until findContacts
}

void SoftSystem::integrate(double h, const Vec3& gravity, WorkerPool* pool) {
    // Algorithm 2 without the rotation, except that each soft body's rigid mode turns on an
    // arc (rigid_mode.h): x += h v + (Rot(h ω) − 1 − h [ω₀]×)(x − c), where ω₀ = I⁻¹ L is the
    // spin in the velocities and ω the turn that keeps L. λ is zeroed before each substep's
    // solve.
    const Vec3 gravityStep = h * gravity;
    gravityStep_ = gravityStep;
    // The last substep's positions become x_prev as they are (the prediction writes the new x
    // into the other array): no copy of every particle.
    x_.swap(xPrev_);
    forEachBody(pool, [&](SoftBodyData& body) {
        const uint32_t first = body.firstParticle;
        // The moments the last velocity derivation summed (the velocity pass's changes added),
        // or afresh after damping and at the start.
        if (!body.momentsKept)
            body.moments = rigidModeMoments(xPrev_.data() + first, v_.data() + first, mass_.data() + first, body.particleCount);
        body.momentsKept = false;
        const RigidModeMoments& moments = body.moments;
        const Vec3 spin = momentumKeepingSpin(moments.inertia, moments.angularMomentum, h);
        body.turn = Quat::Identity();
        // A turn under 1e-7 rad per substep (the chord's loss, (h ω)², is below rounding) or
        // not finite: straight lines.
        if (!(h * h * spin.squaredNorm() >= 1e-14) || !spin.allFinite()) {
            predictOnArc(x_.data() + first, xPrev_.data() + first, v_.data() + first, body.particleCount, gravityStep,
                         h, Mat3::Zero(), moments.centre);
            return;
        }
        integrateRotation(body.turn, h * spin);
        const Vec3 linearSpin = moments.inertia.inverse() * moments.angularMomentum;
        const Mat3 arc =
            body.turn.toRotationMatrix() - Mat3::Identity() - h * crossMatrix(linearSpin);
        predictOnArc(x_.data() + first, xPrev_.data() + first, v_.data() + first, body.particleCount, gravityStep, h,
                     arc, moments.centre);
        // The elements turn with the body: their rotations' warm start.
        turnRotations(rotations_.data() + body.firstElement, body.elementCount, body.turn);
    });
    std::fill(lambda_.begin(), lambda_.end(), 0.0);
    std::fill(volumeLambda_.begin(), volumeLambda_.end(), 0.0);
    for (Attachment& a : attachments_) a.lambda = 0.0;
}

void SoftSystem::solvePositions(SolverContext& ctx, WorkerPool* pool) {
    if (pool && bodiesApart_ && shares_.size() > 1 && ctx.solver == SolverType::GaussSeidel && !patchFriction_) {
        // Each body's elements, attachments and contacts in turn, the bodies at once: what
        // one body's solve writes, no other's reads (planShares), so every order of the
        // bodies gives the bits of all elements, then all attachments, then all contacts.
        const ElementArrays arrays = elementArrays();
        pool->parallelFor(static_cast<int>(shares_.size()), [&](int index) {
            const BodyShare& share = shares_[static_cast<size_t>(index)];
            ElementArrays own = arrays;
            if (!own.heldBatches.empty())
                own.heldBatches = own.heldBatches.subspan(share.firstBatch, share.endBatch - share.firstBatch);
            solveElementBatches(std::span(batches_).subspan(share.firstBatch, share.endBatch - share.firstBatch), own,
                                ctx.invH2, ElementLanes::Widest);
            SolverContext shareCtx = ctx;
            solveAttachmentRange(shareCtx, share.firstAttachment, share.endAttachment);
            solveContactsPerParticle(shareCtx, share.firstContact, share.endContact);
        });
        return;
    }
    solveElements(ctx.invH2, ElementLanes::Widest, pool);
    solveAttachments(ctx);
    solveContacts(ctx);
}

void SoftSystem::listAttachmentRanges() {
    attachmentRanges_.assign(bodies_.size(), {0, 0});
    attachmentsGrouped_ = true;
    std::vector<uint8_t> seen(bodies_.size(), 0);
    size_t k = 0;
    while (k < attachments_.size()) {
        // The body whose particles hold attachment k, and how far its attachments run.
        const uint32_t particle = attachments_[k].particle;
        uint32_t owner = UINT32_MAX;
        for (uint32_t s = 0; s < bodies_.size() && owner == UINT32_MAX; ++s)
            if (bodies_[s].alive && particle >= bodies_[s].firstParticle &&
                particle < bodies_[s].firstParticle + bodies_[s].particleCount)
                owner = s;
        if (owner == UINT32_MAX || seen[owner]) {
            attachmentsGrouped_ = false;
            break;
        }
        seen[owner] = 1;
        const SoftBodyData& body = bodies_[owner];
        const size_t first = k;
        while (k < attachments_.size() && attachments_[k].particle >= body.firstParticle &&
               attachments_[k].particle < body.firstParticle + body.particleCount)
            ++k;
        attachmentRanges_[owner] = {first, k};
    }
    attachmentRangesListed_ = true;
}

void SoftSystem::planShares(std::span<const Body> bodies) {
    if (!attachmentRangesListed_) listAttachmentRanges();
    shares_.clear();
    bodiesApart_ = false;
    // A body created since the frame's candidates has none listed yet: together this substep.
    if (liveBodies_ < 2 || !attachmentsGrouped_ || bodyBatches_.size() != static_cast<size_t>(liveBodies_) ||
        bodyCandidates_.size() < bodies_.size())
        return;
    // The live bodies in order, as rebuildBatches lists their batches.
    size_t live = 0;
    for (uint32_t s = 0; s < bodies_.size(); ++s) {
        if (!bodies_[s].alive) continue;
        BodyShare share{.body = s};
        std::tie(share.firstBatch, share.endBatch) = bodyBatches_[live++];
        std::tie(share.firstAttachment, share.endAttachment) = attachmentRanges_[s];
        shares_.push_back(share);
    }
    // Contacts: the body's own (findContacts joined them in the bodies' order).
    for (BodyShare& share : shares_) {
        share.firstContact = bodyCandidates_[share.body].firstContact;
        share.endContact = bodyCandidates_[share.body].endContact;
    }
    // Apart: every moving rigid body is held or touched by one soft body at most.
    rigidOwner_.resize(bodies.size(), UINT32_MAX);
    bool apart = true;
    const auto claim = [&](uint32_t body, uint32_t soft) {
        if (bodies[body].invMass == 0.0) return;
        uint32_t& owner = rigidOwner_[body];
        if (owner == UINT32_MAX) owner = soft, ownedBodies_.push_back(body);
        else if (owner != soft) apart = false;
    };
    for (const BodyShare& share : shares_) {
        for (const uint32_t body : bodies_[share.body].attachedBodies) claim(body, share.body);
        for (size_t k = share.firstContact; k < share.endContact; ++k) claim(contacts_[k].body, share.body);
    }
    for (const uint32_t body : ownedBodies_) rigidOwner_[body] = UINT32_MAX;
    ownedBodies_.clear();
    bodiesApart_ = apart;
}

void SoftSystem::solveElements(double invH2, ElementLanes lanes, WorkerPool* pool) {
    const ElementArrays arrays = elementArrays();
    forEachBodyBatches(pool, [&](uint32_t first, uint32_t end) {
        ElementArrays own = arrays;  // the held flags are per batch
        if (!own.heldBatches.empty()) own.heldBatches = own.heldBatches.subspan(first, end - first);
        solveElementBatches(std::span(batches_).subspan(first, end - first), own, invH2, lanes);
    });
}

void SoftSystem::deriveVelocities(double h, WorkerPool* pool) {
    // v = (x − x_prev) / h, with each soft body's rigid turn R over the substep (the best-fit
    // rotation from x_prev to x about the centres of mass) counted on its arc rather than its
    // chord: v = v̄ + ω × r + (r − R r_prev) / h, ω = log(R) / h (rigid_mode.h). A rigid motion
    // gets its exact spin back, the momentum is the chord's, and the angular momentum about
    // the centre is I ω, since R zeroes Σ m r × R r_prev.
    const double invH = 1.0 / h;
    // Eq. 34's v̄_n in the velocity pass reads the contacts' particles' velocities from before
    // the derivation, the prediction's v + g h (predictOnArc does not store it): kept for those
    // particles only.
    for (const ParticleContact& c : contacts_) vPrev_[c.particle] = v_[c.particle] + gravityStep_;
    forEachBody(pool, [&](SoftBodyData& body) {
        const uint32_t first = body.firstParticle;
        Mat3 correction = Mat3::Zero();
        Mat3 turnBack = Mat3::Zero();
        Vec3 centre = Vec3::Zero(), centrePrev = Vec3::Zero();
        if (!body.turn.vec().isZero(0.0) && body.particleCount > 0) {
            const Vec3 origin = xPrev_[first];
            const TurnSums sums = turnSums(x_.data() + first, xPrev_.data() + first, mass_.data() + first, body.particleCount, origin);
            const double mass = sums.mass;
            const Vec3 d1 = sums.first / mass, d0 = sums.firstPrev / mass;
            centre = origin + d1;
            centrePrev = origin + d0;
            const Mat3 covariance = sums.cross - mass * d1 * d0.transpose();  // Σ m r r_prevᵀ
            const Mat3 r = extractRotation(covariance, sums.spread - mass * d0.squaredNorm(), body.turn);
            const Vec3 spin = angularVelocityBetween(Quat::Identity(), body.turn, invH);
            correction = crossMatrix(spin);
            turnBack = (r - Mat3::Identity()) * invH;
        }
        body.moments = deriveOnArc(x_.data() + first, xPrev_.data() + first, v_.data() + first, body.particleCount,
                                   invH, correction, centre, turnBack, centrePrev, mass_.data() + first);
        body.momentsKept = true;
    });
}

void SoftSystem::solveVelocities(Body* bodies, double h, double gravity, WorkerPool* pool) {
    // The contacts change their particles' velocities: each body's kept moments (deriveOnArc)
    // take the change of its momentum and angular momentum, Σ m Δv and Σ m (x − c) × Δv.
    // Each particle is listed once, where its first contact is.
    passed_.resize(x_.size(), 0);
    passedVelocities_.clear();
    for (const ParticleContact& c : contacts_) {
        if (passed_[c.particle] != 0) continue;
        passed_[c.particle] = 1;
        passedVelocities_.emplace_back(c.particle, v_[c.particle]);
    }
    if (pool && bodiesApart_ && shares_.size() > 1) {
        // Contacts come body by body, and so do the listed particles: each body's contacts and
        // moments on a thread of their own (one body's contacts change no particle or moving
        // body another one's read, planShares).
        size_t listed = 0;
        for (BodyShare& share : shares_) {
            const SoftBodyData& body = bodies_[share.body];
            share.firstPassed = listed;
            while (listed < passedVelocities_.size() && passedVelocities_[listed].first >= body.firstParticle &&
                   passedVelocities_[listed].first < body.firstParticle + body.particleCount)
                ++listed;
            share.endPassed = listed;
        }
        if (listed == passedVelocities_.size()) {
            pool->parallelFor(static_cast<int>(shares_.size()), [&](int index) {
                const BodyShare& own = shares_[static_cast<size_t>(index)];
                solveContactVelocities(bodies, h, gravity, own.firstContact, own.endContact);
                keepPassedMoments(own.firstPassed, own.endPassed);
            });
            return;
        }
    }
    solveContactVelocities(bodies, h, gravity, 0, contacts_.size());
    keepPassedMoments(0, passedVelocities_.size());
}

void SoftSystem::keepPassedMoments(size_t first, size_t end) {
    // The particles come grouped by soft body (the candidates' order): the sums of the last
    // one's body are kept in registers (not a load and a store per particle through memory the
    // byte stores to passed_ may alias), its body searched for again only when a particle lies
    // outside it. The same additions in the same order.
    SoftBodyData* owner = nullptr;
    uint32_t ownerFirst = 0, ownerEnd = 0;
    double mass = 0.0;
    Vec3 centre = Vec3::Zero(), velocity = Vec3::Zero(), angular = Vec3::Zero();
    const auto keep = [&] {
        if (owner == nullptr) return;
        owner->moments.velocity = velocity;
        owner->moments.angularMomentum = angular;
    };
    for (const auto& [i, before] : std::span(passedVelocities_).subspan(first, end - first)) {
        passed_[i] = 0;
        const Vec3 change = mass_[i] * (v_[i] - before);
        if (owner == nullptr || i < ownerFirst || i >= ownerEnd) {
            keep();
            owner = nullptr;
            for (SoftBodyData& body : bodies_)
                if (body.alive && i >= body.firstParticle && i < body.firstParticle + body.particleCount) {
                    owner = &body;
                    break;
                }
            if (owner == nullptr) continue;
            ownerFirst = owner->firstParticle, ownerEnd = owner->firstParticle + owner->particleCount;
            mass = owner->moments.mass, centre = owner->moments.centre;
            velocity = owner->moments.velocity, angular = owner->moments.angularMomentum;
        }
        if (mass > 0.0) velocity += change / mass;
        angular += (x_[i] - centre).cross(change);
    }
    keep();
}

void SoftSystem::damp(double dt, WorkerPool* pool, ElementLanes lanes) {
    for (SoftBodyData& body : bodies_) body.momentsKept = false;  // the velocities change
    // Each element's deformation rate, its batches' lanes side by side (element_damping.h);
    // with a pool, each body's batches on a thread of their own.
    const DampingArrays arrays{.positions = x_, .velocities = v_, .mass = mass_, .damping = elementDamping_};
    forEachBodyBatches(pool, [&](uint32_t first, uint32_t end) {
        dampElementBatches(std::span(batches_).subspan(first, end - first), arrays, dt, lanes);
    });
}

SoftEnergies SoftSystem::energies(const Vec3& gravity) const {
    SoftEnergies e;
    for (size_t i = 0; i < x_.size(); ++i) {
        e.kinetic += 0.5 * mass_[i] * v_[i].squaredNorm();
        e.potential -= mass_[i] * gravity.dot(x_[i]);
    }
    std::array<Vec3, 8> deviation;
    for (size_t k = 0; k < elements_.size(); ++k) {
        const std::array<Vec3, 8> x = corners(x_, elements_[k]);
        if (compliance_[k] > 0.0) {
            Quat rotation = rotations_[k];
            const Mat3 r = extractRotation(shapeMatrix(x, restOffsets_[k]), scale2_[k], rotation);
            const double c = shapeMatchingError(x, restOffsets_[k], r, deviation);
            e.elastic += c * c / (2.0 * compliance_[k]);
        }
        if (volumeCompliance_[k] > 0.0) {
            const double cv = volumeError(x, volumeGradients_[k], deviation);
            e.elastic += cv * cv / (2.0 * volumeCompliance_[k]);
        }
    }
    return e;
}

bool SoftSystem::isFinite() const {
    return std::all_of(x_.begin(), x_.end(), [](const Vec3& p) { return p.allFinite(); }) &&
           std::all_of(v_.begin(), v_.end(), [](const Vec3& p) { return p.allFinite(); });
}

SoftBodyReadout SoftSystem::readout(SoftBodyId id, bool withVolume) const {
    SoftBodyReadout out;
    if (!isValid(id)) return out;
    const SoftBodyData& body = bodies_[id.index];
    const uint32_t first = body.firstParticle, end = first + body.particleCount;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    Vec3 momentum = Vec3::Zero();
    for (uint32_t i = first; i < end; ++i) {
        out.mass += mass_[i];
        out.centreOfMass += mass_[i] * x_[i];
        momentum += mass_[i] * v_[i];
        lo = lo.cwiseMin(x_[i]);
        hi = hi.cwiseMax(x_[i]);
    }
    if (out.mass > 0.0) {
        out.centreOfMass /= out.mass;
        out.velocity = momentum / out.mass;
    }
    out.extent = body.particleCount > 0 ? Vec3(hi - lo) : Vec3::Zero();
    for (uint32_t k = body.firstElement; withVolume && k < body.firstElement + body.elementCount; ++k)
        out.volume += hexVolume(corners(x_, elements_[k]));
    out.particles = static_cast<int>(body.particleCount);
    out.elements = static_cast<int>(body.elementCount);
    return out;
}

std::span<const Vec3> SoftSystem::positions(SoftBodyId id) const {
    if (!isValid(id)) return {};
    return std::span(x_).subspan(bodies_[id.index].firstParticle, bodies_[id.index].particleCount);
}

std::span<const Vec3> SoftSystem::velocities(SoftBodyId id) const {
    if (!isValid(id)) return {};
    return std::span(v_).subspan(bodies_[id.index].firstParticle, bodies_[id.index].particleCount);
}

std::span<const double> SoftSystem::masses(SoftBodyId id) const {
    if (!isValid(id)) return {};
    return std::span(mass_).subspan(bodies_[id.index].firstParticle, bodies_[id.index].particleCount);
}

SoftSurface SoftSystem::surface(SoftBodyId id) const {
    SoftSurface out;
    if (!isValid(id)) return out;
    const std::span<const Vec3> x = positions(id);
    out.positions.assign(x.begin(), x.end());
    const SoftBodyData& body = bodies_[id.index];
    out.quads = body.quads;
    out.triangles.reserve(2 * body.quads.size());
    for (const auto& q : body.quads) {
        out.triangles.push_back({q[0], q[1], q[2]});
        out.triangles.push_back({q[0], q[2], q[3]});
    }
    return out;
}

}  // namespace substep

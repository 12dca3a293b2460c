// SoftSystem's coupling to rigid bodies: attachments (Eqs. 2-9) and the particle contacts'
// solve (Eqs. 26-30 and 34), each particle standing in for a body with w = 1/m and no rotation
// (paper section 4). Which contacts there are: soft_contacts.cpp; those with still bodies, one
// by one or in vector lanes: still_contacts.h.
#include "physics/collision/narrowphase.h"
#include "physics/soft/soft_system.h"
#include "physics/soft/still_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace substep {
namespace {

/// The rigid contacts' push-out speed and resting speed (contact_kinematics.h): a particle
/// created sunk into the ground rises as gently as a body.
using contact_detail::kPushOutSpeed;
using contact_detail::kRestingSpeed;

/// A body's generalised inverse mass for a correction along unit n at world offset r
/// (Eqs. 2-3); 0 for static bodies.
inline double bodyInverseMass(const Body& b, const Vec3& r, const Vec3& n) {
    return b.invMass > 0.0 ? b.positionalInverseMass(r, n) : 0.0;
}

/// Velocity of a body's point at world offset r.
inline Vec3 pointVelocity(const Body& b, const Vec3& r) { return b.v + b.omega.cross(r); }

/// Eq. 33 for a particle (velocity v, inverse mass w) against a body's point at r: changes
/// their relative velocity by `change`.
inline void applyVelocityChange(Vec3& v, double w, Body& b, const Vec3& r, const Vec3& change) {
    const double magnitude = change.norm();
    if (!(magnitude > kDirectionEpsilon)) return;
    const Vec3 n = change / magnitude;
    const double wb = bodyInverseMass(b, r, n);
    const Vec3 p = change / (w + wb);
    v += w * p;
    if (b.invMass > 0.0) {
        b.v -= b.invMass * p;
        if (b.rotates()) b.omega -= b.applyInverseInertia(r.cross(p));
    }
}

/// Where a body's point at world offset r was at the start of the substep (a static body does
/// not move; its previous pose is not kept).
inline Vec3 previousPoint(const Body& b, const Vec3& local) {
    if (b.invMass == 0.0) return b.pointToWorld(local);
    return b.xPrev + (b.rotates() ? Vec3(b.qPrev * local) : local);
}

/// Eq. 26 for one particle contact: pushes the particle at x (inverse mass w, velocity v) out
/// of body `body` along n, whose surface point is kept at `local1` in the body's frame (Eqs. 2-4,
/// α = 0), the depth capped as the rigid contacts' push-out is. Returns Δλ_n, 0 when apart.
double pushOut(SolverContext& ctx, uint32_t body, const Vec3& local1, const Vec3& n, double radius, Vec3& x,
               double w, const Vec3& v) {
    const Body& b = ctx.bodies[body];
    const Vec3 r = b.q * local1;
    // d = (p1 − p0)·n with p0 the particle's surface point.
    double depth = (b.x + r - (x - radius * n)).dot(n);
    if (depth > 0.0 && ctx.capPushOut) {
        const double approach = -(v - pointVelocity(b, r)).dot(n);
        depth = std::min(depth, ctx.h * std::max(approach, kPushOutSpeed));
    }
    if (!(depth > 0.0)) return 0.0;
    const double deltaLambda = depth / (w + bodyInverseMass(b, r, n));
    x += (w * deltaLambda) * n;
    if (b.invMass > 0.0) applyImpulse(ctx, body, 0, -deltaLambda * n, r.cross(-deltaLambda * n), Vec3::Zero());
    return deltaLambda;
}

/// Eqs. 27-28 for one particle contact: the particle's tangential motion during the substep
/// relative to the body's point at r (kept at `local1`), as a direction t and the Δλ_t that
/// undoes it. False when it did not slip.
bool staticSlip(const Body& b, const Vec3& r, const Vec3& local1, const Vec3& n, const Vec3& x, const Vec3& xPrev,
                double w, Vec3& t, double& deltaTangent) {
    const Vec3 motion = (x - xPrev) - (b.x + r - previousPoint(b, local1));
    const Vec3 slip = motion - motion.dot(n) * n;
    const double length = slip.norm();
    if (!(length > kDirectionEpsilon)) return false;
    t = slip / length;
    deltaTangent = length / (w + bodyInverseMass(b, r, t));
    return true;
}

}  // namespace

void SoftSystem::addAttachments(const SoftBodyDef& def, SoftBodyData& data,
                                const Lattice& lattice, std::span<const Body> bodies) {
    ContactManifold manifold;
    for (const SoftAttachmentDef& attach : def.attachments) {
        const uint32_t bodyIndex = attach.body.isNull() ? 0 : attach.body.index;
        if (bodyIndex >= bodies.size() || !bodies[bodyIndex].alive) continue;
        const Body& b = bodies[bodyIndex];
        const Pose pose{b.userPosition(), b.userOrientation()};
        const Shape probe = sphereShape(data.radius);
        data.attachedBodies.push_back(bodyIndex);
        for (uint32_t local = 0; local < data.particleCount; ++local) {
            const uint32_t i = data.firstParticle + local;
            bool held = true;
            if (attach.particles == SoftAttachmentParticles::Inner) held = lattice.inner[local] != 0;
            if (attach.particles == SoftAttachmentParticles::Below) {
                // Inside the shape: the particle's sphere overlaps it by at least its radius.
                collide(probe, Pose{x_[i], Quat::Identity()}, b.shape, pose, 0.0, manifold);
                held = false;
                for (int k = 0; k < manifold.count; ++k) held = held || manifold.points[k].depth >= data.radius;
            }
            if (!held) continue;
            attachments_.push_back({.particle = i,
                                    .body = bodyIndex,
                                    .local = b.q.conjugate() * (x_[i] - b.x),
                                    .compliance = attach.compliance});
        }
    }
    attachmentsChanged();
}

void SoftSystem::attachmentsChanged() {
    listAttachmentRuns(attachments_, attachmentRuns_);
    attachmentRangesListed_ = false;
}

void SoftSystem::solveAttachments(SolverContext& ctx) {
    // Eqs. 2-9 with body 0 the particle (w = 1/m, no rotation) and body 1 the rigid body:
    // the particle is moved onto the body's point, shared by generalised inverse mass.
    if (ctx.solver == SolverType::Jacobi) {
        for (Attachment& a : attachments_) {
            const Body& b = ctx.bodies[a.body];
            const Vec3 r = b.q * a.local;
            const Vec3 delta = b.x + r - x_[a.particle];
            const double c = delta.norm();
            if (!(c > kDirectionEpsilon)) continue;
            const Vec3 n = delta / c;
            const double w = invMass_[a.particle];
            const double wb = bodyInverseMass(b, r, n);
            const Vec3 p = attachmentImpulse(a.lambda, a.compliance * ctx.invH2, c * c, w + wb, 0.0) * delta;
            x_[a.particle] += w * p;                                                    // Eq. 6
            if (wb > 0.0) applyImpulse(ctx, a.body, 0, -p, r.cross(-p), Vec3::Zero());  // Eqs. 7-9
        }
        return;
    }
    solveAttachmentRange(ctx, 0, attachments_.size());
}

void SoftSystem::solveAttachmentRange(SolverContext& ctx, size_t first, size_t end) {
    // Gauss-Seidel: attachments come grouped by rigid body, and a run of them to one body (a
    // rim holds hundreds) keeps the body's pose in local variables: its rotation matrix and
    // world inverse inertia from the start of the run, turned to first order by the run's
    // accumulated rotation (microradians per substep), written back once at the end by the
    // exact map. The same corrections as one attachment after the other, to second order in
    // that rotation, without a quaternion update per particle.
    //
    // Each correction moves the body the next one starts from, so a run is one dependent chain
    // (a division and two dozen products per link). Runs that share no body and no particle
    // touch disjoint state, so up to kAttachmentLanes consecutive ones are stepped side by side,
    // link by link (attachment_run.h: in vector lanes where the CPU has them): the same
    // operations in the same order per run, the same bits as one run after the other, with the
    // chains overlapping in the processor (rc_car's four rims).
    //
    // The runs come from attachmentRuns_, listed when the attachments change, not every
    // substep; a run that [first, end) cuts (two soft bodies' shares holding one still body one
    // after the other) is found afresh.
    size_t cached = static_cast<size_t>(
        std::partition_point(attachmentRuns_.begin(), attachmentRuns_.end(),
                             [&](const AttachmentRun& run) { return run.next < first; }) -
        attachmentRuns_.begin());
    const auto runAt = [&](size_t k) {
        while (cached < attachmentRuns_.size() && attachmentRuns_[cached].next < k) ++cached;
        const bool kept = cached < attachmentRuns_.size() && attachmentRuns_[cached].next == k &&
                          attachmentRuns_[cached].end <= end;
        return kept ? attachmentRuns_[cached] : attachmentRunAt(attachments_, k, end);
    };
    size_t k = first;
    while (k < end) {
        std::array<AttachmentRun, kAttachmentLanes> lanes;
        int laneCount = 0;
        while (laneCount < kAttachmentLanes && k < end) {
            const AttachmentRun run = runAt(k);
            bool independent = true;
            for (int l = 0; l < laneCount; ++l)
                independent = independent && run.bodyIndex != lanes[l].bodyIndex &&
                              (run.lowParticle > lanes[l].highParticle || run.highParticle < lanes[l].lowParticle);
            if (!independent) break;
            k = run.end;
            lanes[laneCount++] = run;
        }
        for (int l = 0; l < laneCount; ++l) lanes[l].begin(ctx.bodies[lanes[l].bodyIndex]);
        solveAttachmentRuns(std::span(lanes.data(), laneCount), attachments_.data(), x_.data(), invMass_.data(),
                            ctx.invH2);
        for (int l = 0; l < laneCount; ++l) lanes[l].finish(ctx.bodies[lanes[l].bodyIndex]);
    }
}

void SoftSystem::groupContactPatches() {
    // Contacts come grouped by soft body, then rigid body (the candidates' order), so the last
    // patch is nearly always the one; any other order still finds its patch.
    patches_.clear();
    contactPatch_.resize(contacts_.size());
    frictionStep_.assign(contacts_.size(), Vec3::Zero());
    uint32_t owner = 0, ownerFirst = 0, ownerEnd = 0;
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        if (c.particle < ownerFirst || c.particle >= ownerEnd) {
            for (uint32_t s = 0; s < bodies_.size(); ++s) {
                const SoftBodyData& soft = bodies_[s];
                if (soft.alive && c.particle >= soft.firstParticle && c.particle < soft.firstParticle + soft.particleCount) {
                    owner = s, ownerFirst = soft.firstParticle, ownerEnd = soft.firstParticle + soft.particleCount;
                    break;
                }
            }
        }
        size_t patch = patches_.size();
        while (patch > 0 && (patches_[patch - 1].softBody != owner || patches_[patch - 1].body != c.body))
            --patch;
        if (patch == 0) {
            patches_.push_back({.softBody = owner, .body = c.body, .staticFriction = c.staticFriction,
                                .dynamicFriction = c.dynamicFriction});
            patch = patches_.size();
        }
        contactPatch_[k] = static_cast<uint32_t>(patch - 1);
    }
}

void SoftSystem::solveContacts(SolverContext& ctx) {
    if (patchFriction_) solveContactsPerPatch(ctx);
    else solveContactsPerParticle(ctx, 0, contacts_.size());
}

double SoftSystem::takeHeldImpulse(SolverContext& ctx, ParticleContact& c) {
    double& held = heldImpulse_[c.particle];
    if (!(held > 0.0)) return 0.0;
    const double taken = held;
    held = 0.0;
    c.lambdaNormal += taken;
    const Body& b = ctx.bodies[c.body];
    if (b.invMass > 0.0) {
        const Vec3 r = b.q * c.local1;
        applyImpulse(ctx, c.body, 0, -taken * c.normal, r.cross(-taken * c.normal), Vec3::Zero());
    }
    return taken;
}

ContactParticles SoftSystem::contactParticles() {
    return {.x = x_.data(), .xPrev = xPrev_.data(), .v = v_.data(), .vPrev = vPrev_.data(),
            .invMass = invMass_.data(), .heldImpulse = heldImpulse_.data()};
}

void SoftSystem::solveContactsPerParticle(SolverContext& ctx, size_t first, size_t end) {
    // The ground and the obstacles (still bodies) with the body's terms left out, each contact
    // changing its own particle only: groups of them on distinct particles side by side, in
    // lanes (still_contacts.h); every other contact one by one, in order.
    const ContactParticles particles = contactParticles();
    const ContactStep step{.h = ctx.h, .capPushOut = ctx.capPushOut, .gravityStep = gravityStep_};
    const std::span<ParticleContact> contacts = std::span(contacts_).subspan(first, end - first);
    const int group = stillContactGroup(StillContactLanes::Widest);
    forContactGroups(
        contacts, group,
        [&](size_t k, size_t count) { solveStillPositionGroups(&contacts[k], group, count, particles, step); },
        [&](size_t k) {
            ParticleContact& c = contacts[k];
            if (c.still) {
                solveStillContactPosition(c, particles, step);
                return;
            }
            const Body& b = ctx.bodies[c.body];
            const Vec3& n = c.normal;
            Vec3& x = x_[c.particle];
            const double w = invMass_[c.particle];
            // The elements' push this particle's normal did not take first (a moving body
            // receives it), then Eq. 26.
            const double held = takeHeldImpulse(ctx, c);
            const double pushed =
                pushOut(ctx, c.body, c.local1, n, c.radius, x, w, v_[c.particle] + gravityStep_);
            if (!(pushed > 0.0) && !(held > 0.0)) return;
            if (pushed > 0.0) c.lambdaNormal += pushed;
            if (!(c.staticFriction > 0.0)) return;
            // Eqs. 27-28: undo the tangential motion of the particle relative to the body's point
            // during the substep while λ_t stays within μ_s λ_n.
            const Vec3 r = b.q * c.local1;
            Vec3 t;
            double deltaTangent;
            if (!staticSlip(b, r, c.local1, n, x, xPrev_[c.particle], w, t, deltaTangent)) return;
            if (c.lambdaTangent + deltaTangent > c.staticFriction * c.lambdaNormal) return;
            c.lambdaTangent += deltaTangent;
            c.frictionImpulse -= deltaTangent * t;
            x -= (w * deltaTangent) * t;
            if (b.invMass > 0.0)
                applyImpulse(ctx, c.body, 0, deltaTangent * t, r.cross(deltaTangent * t), Vec3::Zero());
        });
}

void SoftSystem::solveContactsPerPatch(SolverContext& ctx) {
    groupContactPatches();
    // Eq. 26 for every contact first, so that static friction is judged on the patch's whole
    // normal multiplier of this substep.
    for (ParticleContact& c : contacts_) {
        takeHeldImpulse(ctx, c);
        const double pushed =
            pushOut(ctx, c.body, c.local1, c.normal, c.radius, x_[c.particle], invMass_[c.particle],
                    v_[c.particle] + gravityStep_);
        if (pushed > 0.0) c.lambdaNormal += pushed;
    }
    // Each patch's load: Σ λ_n, its λ_n-weighted centre and normal, and Σ λ_n ρ (ρ a particle's
    // distance from the centre across the normal), the twist μ_s holds per unit μ_s.
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        ContactPatch& patch = patches_[contactPatch_[k]];
        patch.normal += c.lambdaNormal;
        patch.centre += c.lambdaNormal * x_[c.particle];
        patch.direction += c.lambdaNormal * c.normal;
    }
    for (ContactPatch& patch : patches_) {
        if (!(patch.normal > 0.0)) continue;
        patch.centre /= patch.normal;
        const double length = patch.direction.norm();
        patch.direction = length > kDirectionEpsilon ? Vec3(patch.direction / length) : Vec3::Zero();
    }
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        ContactPatch& patch = patches_[contactPatch_[k]];
        if (!(c.lambdaNormal > 0.0) || !(patch.staticFriction > 0.0)) continue;
        const Vec3 offset = x_[c.particle] - patch.centre;
        patch.reach += c.lambdaNormal * (offset - offset.dot(patch.direction) * patch.direction).norm();
    }
    // Eqs. 27-28 for each pushing contact: the tangential motion of the particle relative to
    // the body's point during the substep is undone ...
    for (size_t k = 0; k < contacts_.size(); ++k) {
        ParticleContact& c = contacts_[k];
        if (!(c.lambdaNormal > 0.0) || !(patches_[contactPatch_[k]].staticFriction > 0.0)) continue;
        const Body& b = ctx.bodies[c.body];
        const Vec3& n = c.normal;
        Vec3& x = x_[c.particle];
        const double w = invMass_[c.particle];
        const Vec3 r = b.q * c.local1;
        Vec3 t;
        double deltaTangent;
        if (!staticSlip(b, r, c.local1, n, x, xPrev_[c.particle], w, t, deltaTangent)) continue;
        const Vec3 impulse = -deltaTangent * t;  // on the particle
        c.lambdaTangent += deltaTangent;
        c.frictionImpulse += impulse;
        frictionStep_[k] = impulse;
        x += w * impulse;
        if (b.invMass > 0.0) applyImpulse(ctx, c.body, 0, -impulse, r.cross(-impulse), Vec3::Zero());
    }
    // ... and kept whole where the patch's static friction, its force and its twist about the
    // patch's normal, stays within μ_s Σλ_n and μ_s Σλ_n ρ (combined as an ellipse): a patch
    // holds or slides as one, whatever share of the load each particle carries while the body
    // settles. Particle by particle, the least loaded ones (uphill on a slope) let go first and
    // a soft box slid off well below atan(μ_s).
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        ContactPatch& patch = patches_[contactPatch_[k]];
        patch.force += c.frictionImpulse;
        patch.twist += (x_[c.particle] - patch.centre).cross(c.frictionImpulse).dot(patch.direction);
    }
    for (ContactPatch& patch : patches_) {
        const double forceLimit = patch.staticFriction * patch.normal;
        // A twist limit of at least μ_s Σλ_n × 1 µm: a one-point patch holds no twist worth
        // the name, and the ratio stays finite.
        const double twistLimit = patch.staticFriction * std::max(patch.reach, 1e-6 * patch.normal);
        const double force = patch.force.norm() / forceLimit;
        const double twist = patch.twist / twistLimit;
        const double ratio = std::sqrt(force * force + twist * twist);
        // A patch past the limit slides, and keeps μ_d / μ_s of that, scaled back onto the
        // limit: kinetic friction μ_d Σλ_n at the position level. Eq. 30 in the velocity pass
        // would change the particles' velocities only, not take back the slip the elements'
        // pull made within the substep, and a box that broke loose slid on with less than μ_d.
        patch.kept = forceLimit > 0.0 ? (ratio <= 1.0 ? 1.0 : patch.dynamicFriction / (patch.staticFriction * ratio)) : 0.0;
    }
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const double kept = patches_[contactPatch_[k]].kept;
        if (kept >= 1.0 || frictionStep_[k].isZero(0.0)) continue;
        const Vec3 impulse = (1.0 - kept) * frictionStep_[k];  // the part taken back
        ParticleContact& c = contacts_[k];
        const Body& b = ctx.bodies[c.body];
        const Vec3 r = b.q * c.local1;
        c.lambdaTangent -= impulse.norm();
        c.frictionImpulse -= impulse;
        x_[c.particle] -= invMass_[c.particle] * impulse;
        if (b.invMass > 0.0) applyImpulse(ctx, c.body, 0, impulse, r.cross(impulse), Vec3::Zero());
    }
}

void SoftSystem::solveContactVelocities(Body* bodies, double h, double gravity, size_t first, size_t end) {
    const ContactParticles particles = contactParticles();
    const ContactStep step{.h = h, .restingSpeed = 2.0 * gravity * h};
    // Still contacts on distinct particles in lanes, as in the position solve; not with
    // friction per patch, whose sliding patches' contacts skip Eq. 30 here.
    const int group = patchFriction_ ? 0 : stillContactGroup(StillContactLanes::Widest);
    forContactGroups(
        std::span(contacts_).subspan(first, end - first), group,
        [&](size_t k, size_t count) {
            solveStillVelocityGroups(&contacts_[first + k], group, count, particles, step);
        },
        [&](size_t index) {
            const size_t k = first + index;
            const ParticleContact& c = contacts_[k];
            if (!(c.lambdaNormal > 0.0)) return;
            // A sliding patch's contact had its μ_d in the solve.
            const bool slid = patchFriction_ && c.lambdaTangent > 0.0 && k < contactPatch_.size() &&
                              patches_[contactPatch_[k]].kept < 1.0;
            if (c.still) {
                // The ground and the obstacles: the body's velocities and inverse mass, zero,
                // left out (the same bits).
                solveStillContactVelocity(c, particles, step, slid);
                return;
            }
            Body& b = bodies[c.body];
            const Vec3& n = c.normal;
            Vec3& v = v_[c.particle];
            const double w = invMass_[c.particle];
            const Vec3 r = b.q * c.local1;
            // Eq. 34: the normal velocity becomes −e v̄_n (no bounce below 2|g|h).
            const double vn = (v - pointVelocity(b, r)).dot(n);
            const double vnBefore = (vPrev_[c.particle] - (b.vPrev + b.omegaPrev.cross(r))).dot(n);
            const double e = std::abs(vnBefore) <= step.restingSpeed ? 0.0 : c.restitution;
            const double change = std::max(-e * vnBefore, 0.0) - vn;
            if (std::abs(change) > kRestingSpeed) applyVelocityChange(v, w, b, r, change * n);
            if (!(c.dynamicFriction > 0.0) || slid) return;
            // Eq. 30 (ERRATA item 2's units): slip removed by at most h μ_d |f_n| = μ_d λ_n / h.
            const Vec3 relative = v - pointVelocity(b, r);
            const Vec3 slip = relative - relative.dot(n) * n;
            const double slipSpeed = slip.norm();
            if (!(slipSpeed > kRestingSpeed)) return;
            const Vec3 t = slip / slipSpeed;
            const double maxChange = c.dynamicFriction * c.lambdaNormal / h * (w + bodyInverseMass(b, r, t));
            applyVelocityChange(v, w, b, r, -std::min(maxChange, slipSpeed) * t);
        });
}

int SoftSystem::activeContactCount() const {
    return static_cast<int>(std::count_if(contacts_.begin(), contacts_.end(),
                                          [](const ParticleContact& c) { return c.lambdaNormal > 0.0; }));
}

Vec3 SoftSystem::contactForce(double h) const {
    Vec3 impulse = Vec3::Zero();
    for (const ParticleContact& c : contacts_) impulse += c.lambdaNormal * c.normal + c.frictionImpulse;
    return impulse / (h * h);
}

double SoftSystem::maxPenetration(std::span<const Body> bodies) const {
    double deepest = 0.0;
    for (const ParticleContact& c : contacts_) {
        const Body& b = bodies[c.body];
        const Vec3 p1 = b.pointToWorld(c.local1);
        deepest = std::max(deepest, (p1 - (x_[c.particle] - c.radius * c.normal)).dot(c.normal));
    }
    return deepest;
}

}  // namespace substep

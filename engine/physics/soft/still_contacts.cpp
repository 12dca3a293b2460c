// Soft particles' contacts with still bodies one by one, and the choice of lanes
// (still_contacts.h). Compiled for the base ISA (no FMA to fuse with): the order the lanes copy.
#include "physics/soft/still_contacts.h"

#include "physics/soft/attachment_run.h"
#include "physics/soft/element_batch.h"

#include <algorithm>
#include <cmath>

namespace substep {

int stillContactGroup(StillContactLanes lanes) {
    // Four lanes cost more than one by one (rc_car's contacts: 6.5 % of the frame against 5.1;
    // eight: 4.2), so the widest is eight or none.
    if (lanes == StillContactLanes::Widest) return wideElementLanes() ? 8 : 0;
    if (lanes == StillContactLanes::Avx2 && attachmentVectorLanes()) return 4;
    return 0;
}

void solveStillContactPosition(ParticleContact& c, const ContactParticles& particles,
                               const ContactStep& step) {
    // The elements' push this particle's normal did not take first (SoftSystem::takeHeldImpulse;
    // a still body receives nothing of it).
    double& heldImpulse = particles.heldImpulse[c.particle];
    double held = 0.0;
    if (heldImpulse > 0.0) {
        held = heldImpulse;
        heldImpulse = 0.0;
        c.lambdaNormal += held;
    }
    // Eq. 26 against the body's point `anchor`: its velocity and generalised inverse mass are
    // zero (and w + 0 = w), so the moving body's depth, cap and Δλ_n without rotating r1.
    const Vec3& n = c.normal;
    Vec3& x = particles.x[c.particle];
    const double w = particles.invMass[c.particle];
    const Vec3 v = particles.v[c.particle] + step.gravityStep;
    double depth = (c.anchor - (x - c.radius * n)).dot(n);
    if (depth > 0.0 && step.capPushOut) {
        const double approach = -v.dot(n);
        depth = std::min(depth, step.h * std::max(approach, contact_detail::kPushOutSpeed));
    }
    double pushed = 0.0;
    if (depth > 0.0) {
        pushed = depth / w;
        x += (w * pushed) * n;
    }
    if (!(pushed > 0.0) && !(held > 0.0)) return;
    if (pushed > 0.0) c.lambdaNormal += pushed;
    if (!(c.staticFriction > 0.0)) return;
    // Eqs. 27-28: the body's point did not move, so the slip to undo is the particle's own
    // tangential motion during the substep, while λ_t stays within μ_s λ_n.
    const Vec3 motion = x - particles.xPrev[c.particle];
    const Vec3 slip = motion - motion.dot(n) * n;
    const double length = slip.norm();
    if (!(length > kDirectionEpsilon)) return;
    const Vec3 t = slip / length;
    const double deltaTangent = length / w;
    if (c.lambdaTangent + deltaTangent > c.staticFriction * c.lambdaNormal) return;
    c.lambdaTangent += deltaTangent;
    c.frictionImpulse -= deltaTangent * t;
    x -= (w * deltaTangent) * t;
}

namespace {

/// Eq. 33 against a still body: the particle takes the whole change.
inline void changeVelocityOnStill(Vec3& v, double w, const Vec3& change) {
    if (!(change.norm() > kDirectionEpsilon)) return;
    const Vec3 p = change / w;
    v += w * p;
}

}  // namespace

void solveStillContactVelocity(const ParticleContact& c, const ContactParticles& particles,
                               const ContactStep& step, bool slid) {
    if (!(c.lambdaNormal > 0.0)) return;
    const Vec3& n = c.normal;
    Vec3& v = particles.v[c.particle];
    const double w = particles.invMass[c.particle];
    // Eq. 34: the normal velocity becomes −e v̄_n (no bounce below 2|g|h).
    const double vn = v.dot(n);
    const double vnBefore = particles.vPrev[c.particle].dot(n);
    const double e = std::abs(vnBefore) <= step.restingSpeed ? 0.0 : c.restitution;
    const double change = std::max(-e * vnBefore, 0.0) - vn;
    if (std::abs(change) > contact_detail::kRestingSpeed) changeVelocityOnStill(v, w, change * n);
    if (!(c.dynamicFriction > 0.0) || slid) return;
    // Eq. 30 (ERRATA item 2's units): slip removed by at most h μ_d |f_n| = μ_d λ_n / h.
    const Vec3 slip = v - v.dot(n) * n;
    const double slipSpeed = slip.norm();
    if (!(slipSpeed > contact_detail::kRestingSpeed)) return;
    const Vec3 t = slip / slipSpeed;
    const double maxChange = c.dynamicFriction * c.lambdaNormal / step.h * w;
    changeVelocityOnStill(v, w, -std::min(maxChange, slipSpeed) * t);
}

void solveStillPositionGroups(ParticleContact* contacts, int group, size_t count,
                              const ContactParticles& particles, const ContactStep& step) {
    if (group == 8)
        solveStillPositionsInWideLanes(contacts, count, particles, step);
    else
        solveStillPositionsInLanes(contacts, count, particles, step);
}

void solveStillVelocityGroups(const ParticleContact* contacts, int group, size_t count,
                              const ContactParticles& particles, const ContactStep& step) {
    if (group == 8)
        solveStillVelocitiesInWideLanes(contacts, count, particles, step);
    else
        solveStillVelocitiesInLanes(contacts, count, particles, step);
}

}  // namespace substep

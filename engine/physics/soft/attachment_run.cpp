// Runs of attachments stepped one after the other in turn, link by link (attachment_run.h), and
// the choice of lanes. Compiled for the base ISA (no FMA to fuse with): Eigen's SSE2 order is
// the order attachment_lanes.cpp copies.
#include "physics/soft/attachment_run.h"

#include "physics/soft/element_batch.h"

#include <algorithm>

namespace substep {
namespace {

// Inlined into the runs' loop: a link is a few dozen operations, and a call's saves and the
// run's state reloaded after it cost a good part of them.
[[gnu::always_inline]] inline void solveAttachmentLink(AttachmentRun& run, Attachment& a, Vec3* x,
                                                       const double* invMass, double invH2) {
    const Vec3 r0 = run.rotation * a.local;
    const Vec3 r = r0 + run.turned.cross(r0);
    const Vec3 delta = run.position + r - x[a.particle];
    const double c2 = delta.squaredNorm();
    if (!(c2 > kDirectionEpsilon * kDirectionEpsilon)) return;
    const double w = invMass[a.particle];
    const Vec3 rd = r.cross(delta);
    const Vec3 spin = run.inverseInertia * rd;
    const double angular = rd.dot(spin);  // Eqs. 2-3, times c²
    // p = f delta, so I⁻¹ (r × p) = f I⁻¹ (r × delta): the body's turn reuses what its inverse
    // mass took, one multiplication after the division on the chain.
    const double factor = attachmentImpulse(a.lambda, a.compliance * invH2, c2, w + run.inverseMass, angular);
    x[a.particle] += (w * factor) * delta;               // Eq. 6
    run.position -= (run.inverseMass * factor) * delta;  // Eq. 7, the body receiving −p
    run.turned -= factor * spin;                         // Eq. 8
}

}  // namespace

bool attachmentVectorLanes() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}

void solveAttachmentRuns(std::span<AttachmentRun> runs, Attachment* attachments, Vec3* x, const double* invMass,
                         double invH2, AttachmentLanes lanes) {
    // A lone run gains nothing from lanes (at two threads each soft body's share holds one rim).
    const bool wide = lanes == AttachmentLanes::Widest && wideElementLanes();
    if (lanes != AttachmentLanes::OneByOne && runs.size() > 1 && (wide || attachmentVectorLanes())) {
        for (size_t first = 0; first < runs.size(); first += kAttachmentLanes) {
            const auto group = runs.subspan(first, std::min<size_t>(kAttachmentLanes, runs.size() - first));
            if (wide) solveAttachmentRunsInWideLanes(group, attachments, x, invMass, invH2);
            else solveAttachmentRunsInLanes(group, attachments, x, invMass, invH2);
        }
        return;
    }
    // The common length link by link across the runs, then each run's rest.
    size_t shortest = runs.empty() ? 0 : runs[0].end - runs[0].next;
    for (const AttachmentRun& run : runs) shortest = std::min(shortest, run.end - run.next);
    for (size_t link = 0; link < shortest; ++link)
        for (AttachmentRun& run : runs) solveAttachmentLink(run, attachments[run.next++], x, invMass, invH2);
    for (AttachmentRun& run : runs)
        while (run.next < run.end) solveAttachmentLink(run, attachments[run.next++], x, invMass, invH2);
}

AttachmentRun attachmentRunAt(std::span<const Attachment> attachments, size_t first, size_t end) {
    AttachmentRun run;
    run.bodyIndex = attachments[first].body;
    run.next = run.end = first;
    run.lowParticle = run.highParticle = attachments[first].particle;
    while (run.end < end && attachments[run.end].body == run.bodyIndex) {
        run.lowParticle = std::min(run.lowParticle, attachments[run.end].particle);
        run.highParticle = std::max(run.highParticle, attachments[run.end].particle);
        ++run.end;
    }
    return run;
}

void listAttachmentRuns(std::span<const Attachment> attachments, std::vector<AttachmentRun>& runs) {
    runs.clear();
    for (size_t k = 0; k < attachments.size(); k = runs.back().end)
        runs.push_back(attachmentRunAt(attachments, k, attachments.size()));
}

void AttachmentRun::begin(const Body& b) {
    moves = b.invMass > 0.0;
    turns = moves && b.rotates();
    rotation = b.q.toRotationMatrix();
    inverseInertia = turns ? Mat3(rotation * b.invInertia.asDiagonal() * rotation.transpose()) : Mat3::Zero();
    inverseMass = moves ? b.invMass : 0.0;
    position = b.x;
    turned = Vec3::Zero();
}

void AttachmentRun::finish(Body& b) const {
    if (!moves) return;
    b.x = position;
    if (turns) integrateRotation(b.q, turned);  // Eq. 9 by the exact map, as moveBody does
}

}  // namespace substep

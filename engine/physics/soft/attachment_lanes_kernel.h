#pragma once
/// The kernel of attachment runs in vector lanes (attachment_run.h): one run per lane of four
/// doubles, each lane doing the scalar link's operations (attachment_run.cpp) in its order, so
/// the same bits: Eigen's 3 x 3 product with SSE2 sums rows 0 and 1 as (p0 + p1) + p2 and row 2
/// as p0 + (p1 + p2), its dot products and squared norms as (p0 + p1) + p2, and the cross
/// product is the textbook one. The files that include it (attachment_lanes.cpp for AVX2,
/// attachment_lanes_wide.cpp for x86-64-v4's 32 registers) are compiled without fusing a
/// multiply and an add (-ffp-contract=off, engine/physics/CMakeLists.txt), where the scalar link
/// rounds both; they include it under their target pragma (GCC lowers the vector compares and
/// selects of a function for the target it is defined under, element_batch_kernel.h).

#include "physics/soft/attachment_run.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

namespace substep {
namespace {

using Lanes = double __attribute__((vector_size(4 * sizeof(double))));
/// A comparison's lanes: all ones where true.
using Mask = decltype(Lanes{} < Lanes{});

/// Three coordinates, a lane per run.
struct LaneVec {
    Lanes x, y, z;
};

/// Four doubles from memory (vectors are not passed by value: a different ABI with and without
/// AVX).
[[gnu::always_inline]] inline void load(Lanes& v, const double* p) { std::memcpy(&v, p, sizeof v); }

/// Eigen's Mat3 * Vec3 with SSE2 (see the top of the file), m column-major by lanes.
[[gnu::always_inline]] inline void multiply(const Lanes (&m)[9], const LaneVec& v, LaneVec& out) {
    out.x = (m[0] * v.x + m[3] * v.y) + m[6] * v.z;
    out.y = (m[1] * v.x + m[4] * v.y) + m[7] * v.z;
    out.z = m[2] * v.x + (m[5] * v.y + m[8] * v.z);
}

/// Eigen's a.cross(b).
[[gnu::always_inline]] inline void cross(const LaneVec& a, const LaneVec& b, LaneVec& out) {
    out.x = a.y * b.z - a.z * b.y;
    out.y = a.z * b.x - a.x * b.z;
    out.z = a.x * b.y - a.y * b.x;
}

/// Eigen's a.dot(b).
[[gnu::always_inline]] inline void dot(const LaneVec& a, const LaneVec& b, Lanes& out) {
    out = (a.x * b.x + a.y * b.y) + a.z * b.z;
}

/// Four rows of four doubles (one per lane) into four lanes of each column.
[[gnu::always_inline]] inline void transpose(const Lanes& r0, const Lanes& r1, const Lanes& r2, const Lanes& r3,
                                             Lanes& c0, Lanes& c1, Lanes& c2, Lanes& c3) {
    const Lanes t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6), t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
    const Lanes t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6), t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
    c0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5), c1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    c2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7), c3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

/// A vector member of each lane's run, by lanes.
[[gnu::always_inline]] inline void gather(AttachmentRun* const (&runs)[kAttachmentLanes], Vec3 AttachmentRun::*member,
                                          LaneVec& out) {
    const Vec3 &v0 = runs[0]->*member, &v1 = runs[1]->*member, &v2 = runs[2]->*member, &v3 = runs[3]->*member;
    out.x = Lanes{v0.x(), v1.x(), v2.x(), v3.x()};
    out.y = Lanes{v0.y(), v1.y(), v2.y(), v3.y()};
    out.z = Lanes{v0.z(), v1.z(), v2.z(), v3.z()};
}

/// `links` links of each lane's run (kAttachmentLanes runs, sharing no body and no particle but
/// for copies of one run), from their `next` on: attachment_run.cpp's link in every lane.
[[gnu::always_inline]] inline void stepInLanes(AttachmentRun* const (&runs)[kAttachmentLanes], size_t links,
                                               Attachment* attachments, Vec3* x, const double* invMass,
                                               double invH2) {
    // Each run's pose by lanes; the position and turn built whole and written back whole, so
    // they stay in registers through the links.
    Lanes rotation[9], inertia[9];
    for (int e = 0; e < 9; ++e) {
        rotation[e] = Lanes{runs[0]->rotation.data()[e], runs[1]->rotation.data()[e], runs[2]->rotation.data()[e],
                            runs[3]->rotation.data()[e]};
        inertia[e] = Lanes{runs[0]->inverseInertia.data()[e], runs[1]->inverseInertia.data()[e],
                           runs[2]->inverseInertia.data()[e], runs[3]->inverseInertia.data()[e]};
    }
    const Lanes bodyInverseMass = {runs[0]->inverseMass, runs[1]->inverseMass, runs[2]->inverseMass,
                                   runs[3]->inverseMass};
    LaneVec position, turned;
    gather(runs, &AttachmentRun::position, position);
    gather(runs, &AttachmentRun::turned, turned);
    const Lanes zero = {0.0, 0.0, 0.0, 0.0};
    const Lanes epsilon2 = zero + kDirectionEpsilon * kDirectionEpsilon;
    const Lanes scale = zero + invH2;
    Attachment* const first[kAttachmentLanes] = {attachments + runs[0]->next, attachments + runs[1]->next,
                                                 attachments + runs[2]->next, attachments + runs[3]->next};
    for (size_t n = 0; n < links; ++n) {
        Attachment* const link[kAttachmentLanes] = {first[0] + n, first[1] + n, first[2] + n, first[3] + n};
        Vec3* const point[kAttachmentLanes] = {x + link[0]->particle, x + link[1]->particle, x + link[2]->particle,
                                               x + link[3]->particle};
        // Each lane's local point and compliance (contiguous in Attachment) as columns.
        static_assert(offsetof(Attachment, compliance) == offsetof(Attachment, local) + 3 * sizeof(double));
        Lanes row0, row1, row2, row3;
        load(row0, link[0]->local.data()), load(row1, link[1]->local.data());
        load(row2, link[2]->local.data()), load(row3, link[3]->local.data());
        LaneVec local;
        Lanes compliance;
        transpose(row0, row1, row2, row3, local.x, local.y, local.z, compliance);
        LaneVec particle;
        Lanes w;
        for (int l = 0; l < kAttachmentLanes; ++l) {
            particle.x[l] = point[l]->x(), particle.y[l] = point[l]->y(), particle.z[l] = point[l]->z();
            w[l] = invMass[link[l]->particle];
        }

        // r0 = R local, r = r0 + turned × r0, delta = (x_body + r) − x (Eqs. 2-3's offsets).
        LaneVec r0, turn, r, delta;
        multiply(rotation, local, r0);
        cross(turned, r0, turn);
        r.x = r0.x + turn.x, r.y = r0.y + turn.y, r.z = r0.z + turn.z;
        delta.x = (position.x + r.x) - particle.x;
        delta.y = (position.y + r.y) - particle.y;
        delta.z = (position.z + r.z) - particle.z;
        Lanes c2;
        dot(delta, delta, c2);
        // A lane whose particle is on the body's point changes nothing.
        const Mask moved = c2 > epsilon2;
        LaneVec rd, spin;
        cross(r, delta, rd);
        multiply(inertia, rd, spin);
        Lanes angular;
        dot(rd, spin, angular);  // Eqs. 2-3, times c²

        // attachmentImpulse lane by lane: a hard lane's factor is c² / denominator, a soft
        // lane's (c² − α̃ λ c) / denominator and its λ takes Δλ (Eq. 4).
        const Lanes alphaTilde = compliance * scale;
        const Lanes denominator = ((w + bodyInverseMass) + alphaTilde) * c2 + angular;
        const Mask soft = moved & (alphaTilde != zero);
        Lanes numerator = c2;
        if ((soft[0] | soft[1]) | (soft[2] | soft[3])) {
            Lanes lambda, c;
            for (int l = 0; l < kAttachmentLanes; ++l) lambda[l] = link[l]->lambda, c[l] = std::sqrt(c2[l]);
            const Lanes deltaLambda = c2 * (c - alphaTilde * lambda) / denominator;  // Eq. 4
            numerator = soft ? c2 - alphaTilde * lambda * c : c2;
            const Lanes summed = lambda + deltaLambda;
            for (int l = 0; l < kAttachmentLanes; ++l)
                if (soft[l]) link[l]->lambda = summed[l];
        }
        const Lanes factor = numerator / denominator;

        // Eq. 6 for the particle, Eqs. 7-8 for the body (receiving −p); lanes that did not move
        // keep their bits.
        const Lanes step = w * factor, bodyStep = bodyInverseMass * factor;
        particle.x = moved ? particle.x + step * delta.x : particle.x;
        particle.y = moved ? particle.y + step * delta.y : particle.y;
        particle.z = moved ? particle.z + step * delta.z : particle.z;
        position.x = moved ? position.x - bodyStep * delta.x : position.x;
        position.y = moved ? position.y - bodyStep * delta.y : position.y;
        position.z = moved ? position.z - bodyStep * delta.z : position.z;
        turned.x = moved ? turned.x - factor * spin.x : turned.x;
        turned.y = moved ? turned.y - factor * spin.y : turned.y;
        turned.z = moved ? turned.z - factor * spin.z : turned.z;
        for (int l = 0; l < kAttachmentLanes; ++l) *point[l] = Vec3(particle.x[l], particle.y[l], particle.z[l]);
    }
    // Back to the runs (a copy's lane holds what its run's lane holds).
    double px[kAttachmentLanes], py[kAttachmentLanes], pz[kAttachmentLanes];
    double tx[kAttachmentLanes], ty[kAttachmentLanes], tz[kAttachmentLanes];
    std::memcpy(px, &position.x, sizeof px), std::memcpy(py, &position.y, sizeof py);
    std::memcpy(pz, &position.z, sizeof pz), std::memcpy(tx, &turned.x, sizeof tx);
    std::memcpy(ty, &turned.y, sizeof ty), std::memcpy(tz, &turned.z, sizeof tz);
    for (int l = 0; l < kAttachmentLanes; ++l) {
        if (l > 0 && runs[l] == runs[0]) continue;
        runs[l]->next += links;
        runs[l]->position = Vec3(px[l], py[l], pz[l]);
        runs[l]->turned = Vec3(tx[l], ty[l], tz[l]);
    }
}

/// solveAttachmentRuns in lanes: while two runs or more have links left, their common length in
/// lanes (the lanes no run takes copy the first run's: the same arithmetic on the same inputs,
/// the same bits stored twice), then the runs that ended drop out; the last run's rest one by
/// one.
[[gnu::always_inline]] inline void runInLanes(std::span<AttachmentRun> runs, Attachment* attachments, Vec3* x,
                                              const double* invMass, double invH2) {
    AttachmentRun* live[kAttachmentLanes];
    for (;;) {
        int count = 0;
        for (AttachmentRun& run : runs)
            if (run.next < run.end) live[count++] = &run;
        if (count < 2) break;
        size_t shortest = live[0]->end - live[0]->next;
        for (int l = 1; l < count; ++l) shortest = std::min(shortest, live[l]->end - live[l]->next);
        for (int l = count; l < kAttachmentLanes; ++l) live[l] = live[0];
        stepInLanes(live, shortest, attachments, x, invMass, invH2);
    }
    solveAttachmentRuns(runs, attachments, x, invMass, invH2, AttachmentLanes::OneByOne);
}

}  // namespace
}  // namespace substep

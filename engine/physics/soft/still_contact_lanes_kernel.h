#pragma once
/// The kernel of still contacts in vector lanes (still_contacts.h): a group of L contacts on
/// distinct particles (or fewer, the last repeated in the spare lanes), one per lane, each doing
/// still_contacts.cpp's operations in its order, so the same bits: Eigen's dot products and squared
/// norms of 3-vectors sum as (p0 + p1) + p2, std::min(a, b) is b < a ? b : a and std::max(a, b) a <
/// b ? b : a (their NaN and ±0 cases alike), and each early return is a lane mask, the lane's state
/// kept where it is clear. The files that include it (still_contact_lanes.cpp for AVX2, *_wide.cpp
/// for x86-64-v4) are compiled without fusing a multiply and an add (-ffp-contract=off,
/// engine/physics/CMakeLists.txt), and include it under their target pragma (GCC lowers the
/// vector compares and selects of a function for the target it is defined under).

#include "physics/soft/still_contacts.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>

// Every function below that takes or returns lanes is inlined into the entry points: no call
// passes vectors, so the ABI the compilers warn about (with or without AVX) never applies.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace substep {
namespace {

/// Four and eight doubles (GCC takes no vector size that depends on a template parameter), and
/// two (one SSE2 register: a particle's x and y).
typedef double FourLanes __attribute__((vector_size(4 * sizeof(double))));
typedef double EightLanes __attribute__((vector_size(8 * sizeof(double))));
typedef double TwoDoubles __attribute__((vector_size(2 * sizeof(double))));
template <int L>
struct LaneType;
template <>
struct LaneType<4> {
    using D = FourLanes;
};
template <>
struct LaneType<8> {
    using D = EightLanes;
};

// Four doubles at a byte offset in each contact, their rows as columns: a 4 x 4 transpose per
// four contacts (each half of eight lanes alike), its own inverse. Lanes are built from loads
// and shuffles in registers: filled element by element, GCC wrote them to the stack and read
// them back whole, which store forwarding cannot serve.
static_assert(offsetof(ParticleContact, radius) ==
              offsetof(ParticleContact, normal) + 3 * sizeof(double));
static_assert(offsetof(ParticleContact, staticFriction) ==
              offsetof(ParticleContact, normal) + 4 * sizeof(double));
static_assert(offsetof(ParticleContact, lambdaNormal) ==
              offsetof(ParticleContact, staticFriction) + 3 * sizeof(double));
static_assert(offsetof(ParticleContact, frictionImpulse) ==
              offsetof(ParticleContact, lambdaTangent) + sizeof(double));
static_assert(offsetof(ParticleContact, lambdaTangent) ==
              offsetof(ParticleContact, staticFriction) + 4 * sizeof(double));
static_assert(offsetof(ParticleContact, anchor) + 3 * sizeof(double) == sizeof(ParticleContact));

[[gnu::always_inline]] inline void load(FourLanes& v, const void* p) {
    std::memcpy(&v, p, sizeof v);
}
[[gnu::always_inline]] inline void store(void* p, const FourLanes& v) {
    std::memcpy(p, &v, sizeof v);
}

[[gnu::always_inline]] inline void transpose(FourLanes (&r)[4]) {
    const FourLanes t0 = __builtin_shufflevector(r[0], r[1], 0, 4, 2, 6),
                    t1 = __builtin_shufflevector(r[0], r[1], 1, 5, 3, 7);
    const FourLanes t2 = __builtin_shufflevector(r[2], r[3], 0, 4, 2, 6),
                    t3 = __builtin_shufflevector(r[2], r[3], 1, 5, 3, 7);
    r[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5),
    r[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    r[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7),
    r[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}
[[gnu::always_inline]] inline void transpose(EightLanes (&r)[4]) {
    const EightLanes t0 = __builtin_shufflevector(r[0], r[1], 0, 8, 2, 10, 4, 12, 6, 14);
    const EightLanes t1 = __builtin_shufflevector(r[0], r[1], 1, 9, 3, 11, 5, 13, 7, 15);
    const EightLanes t2 = __builtin_shufflevector(r[2], r[3], 0, 8, 2, 10, 4, 12, 6, 14);
    const EightLanes t3 = __builtin_shufflevector(r[2], r[3], 1, 9, 3, 11, 5, 13, 7, 15);
    r[0] = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
    r[1] = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
    r[2] = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
    r[3] = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
}

/// The four doubles at byte `offset` of lane l's contact as four lanes each.
template <class C>
[[gnu::always_inline]] inline void loadColumns(C* const (&lane)[4], size_t offset,
                                               FourLanes (&out)[4]) {
    for (int l = 0; l < 4; ++l)
        load(out[l], reinterpret_cast<const char*>(lane[l]) + offset);
    transpose(out);
}
/// ... of eight lanes: contact l's and l + 4's rows side by side, transposed by halves.
template <class C>
[[gnu::always_inline]] inline void loadColumns(C* const (&lane)[8], size_t offset,
                                               EightLanes (&out)[4]) {
    for (int l = 0; l < 4; ++l) {
        FourLanes low, high;
        load(low, reinterpret_cast<const char*>(lane[l]) + offset);
        load(high, reinterpret_cast<const char*>(lane[l + 4]) + offset);
        out[l] = __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
    }
    transpose(out);
}
/// The inverse of loadColumns.
[[gnu::always_inline]] inline void storeColumns(ParticleContact* const (&lane)[4], size_t offset,
                                                FourLanes (&in)[4]) {
    transpose(in);
    for (int l = 0; l < 4; ++l)
        store(reinterpret_cast<char*>(lane[l]) + offset, in[l]);
}
[[gnu::always_inline]] inline void storeColumns(ParticleContact* const (&lane)[8], size_t offset,
                                                EightLanes (&in)[4]) {
    transpose(in);
    for (int l = 0; l < 4; ++l) {
        store(reinterpret_cast<char*>(lane[l]) + offset,
              __builtin_shufflevector(in[l], in[l], 0, 1, 2, 3));
        store(reinterpret_cast<char*>(lane[l + 4]) + offset,
              __builtin_shufflevector(in[l], in[l], 4, 5, 6, 7));
    }
}

/// Lane l's contact: contacts[l], the last of `count` (1 to L) in the lanes past it, and its
/// particle. A lane that repeats a contact reads what the other one reads and writes what it
/// writes: the group solves each contact once.
template <int L, class C>
[[gnu::always_inline]] inline void laneContacts(C* contacts, int count, C* (&lane)[L], uint32_t (&particle)[L]) {
    for (int l = 0; l < L; ++l) {
        lane[l] = contacts + (l < count ? l : count - 1);
        particle[l] = lane[l]->particle;
    }
}

/// L doubles, the comparisons' lanes (all ones where true), and three coordinates by lanes.
template <int L>
struct StillLanes {
    using D = typename LaneType<L>::D;
    using M = decltype(D{} < D{});
    struct V {
        D x, y, z;
    };

    /// s in every lane (bit for bit: adding it to zeros would turn −0 into +0).
    [[gnu::always_inline]] static D all(double s) {
        D out;
        for (int l = 0; l < L; ++l)
            out[l] = s;
        return out;
    }
    /// f(l) in lane l, built in registers.
    template <class F, size_t... l>
    [[gnu::always_inline]] static D lanesOf(F&& f, std::index_sequence<l...>) {
        return D{f(l)...};
    }
    template <class F>
    [[gnu::always_inline]] static D lanesOf(F&& f) {
        return lanesOf(f, std::make_index_sequence<L>());
    }
    /// values[index[l]] in lane l.
    [[gnu::always_inline]] static D gather(const double* values, const uint32_t (&index)[L]) {
        return lanesOf([&](size_t l) { return values[index[l]]; });
    }
    /// points[index[l]] in lane l: x and y by pairs (one 16-byte load each) and shuffles, z by
    /// elements (a 32-byte load would read past the last particle).
    [[gnu::always_inline]] static V gather(const Vec3* points, const uint32_t (&index)[L]) {
        TwoDoubles xy[L];
        for (int l = 0; l < L; ++l)
            std::memcpy(&xy[l], points[index[l]].data(), sizeof xy[l]);
        D pairs0, pairs1;  // x0 y0 x1 y1 ..., the first and second half of the lanes
        if constexpr (L == 4) {
            pairs0 = __builtin_shufflevector(xy[0], xy[1], 0, 1, 2, 3);
            pairs1 = __builtin_shufflevector(xy[2], xy[3], 0, 1, 2, 3);
        } else {
            const FourLanes q0 = __builtin_shufflevector(xy[0], xy[1], 0, 1, 2, 3);
            const FourLanes q1 = __builtin_shufflevector(xy[2], xy[3], 0, 1, 2, 3);
            const FourLanes q2 = __builtin_shufflevector(xy[4], xy[5], 0, 1, 2, 3);
            const FourLanes q3 = __builtin_shufflevector(xy[6], xy[7], 0, 1, 2, 3);
            pairs0 = __builtin_shufflevector(q0, q1, 0, 1, 2, 3, 4, 5, 6, 7);
            pairs1 = __builtin_shufflevector(q2, q3, 0, 1, 2, 3, 4, 5, 6, 7);
        }
        V out;
        if constexpr (L == 4) {
            out.x = __builtin_shufflevector(pairs0, pairs1, 0, 2, 4, 6);
            out.y = __builtin_shufflevector(pairs0, pairs1, 1, 3, 5, 7);
        } else {
            out.x = __builtin_shufflevector(pairs0, pairs1, 0, 2, 4, 6, 8, 10, 12, 14);
            out.y = __builtin_shufflevector(pairs0, pairs1, 1, 3, 5, 7, 9, 11, 13, 15);
        }
        out.z = lanesOf([&](size_t l) { return points[index[l]].z(); });
        return out;
    }
    [[gnu::always_inline]] static D dot(const V& a, const V& b) {
        return (a.x * b.x + a.y * b.y) + a.z * b.z;
    }
    [[gnu::always_inline]] static D sqrt(D a) {
        for (int l = 0; l < L; ++l)
            a[l] = std::sqrt(a[l]);
        return a;
    }
    /// |a| (the sign bit cleared, as std::abs).
    [[gnu::always_inline]] static D abs(const D& a) { return (D)((M)a & (M{} + INT64_MAX)); }
    [[gnu::always_inline]] static D select(const M& m, const D& a, const D& b) { return m ? a : b; }
    [[gnu::always_inline]] static V select(const M& m, const V& a, const V& b) {
        return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
    }
    /// a − s b and a + s b, coordinate by coordinate (Eigen's a -= s * b).
    [[gnu::always_inline]] static V minusScaled(const V& a, const D& s, const V& b) {
        return {a.x - s * b.x, a.y - s * b.y, a.z - s * b.z};
    }
    [[gnu::always_inline]] static V plusScaled(const V& a, const D& s, const V& b) {
        return {a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
    }
    [[gnu::always_inline]] static V divided(const V& a, const D& s) {
        return {a.x / s, a.y / s, a.z / s};
    }
    [[gnu::always_inline]] static Vec3 get(const V& in, int l) {
        return Vec3(in.x[l], in.y[l], in.z[l]);
    }
};

/// solveStillContactPosition of contacts[0, count) in lanes, count ≤ L.
template <int L>
[[gnu::always_inline]] inline void stillPositionsInLanes(ParticleContact* contacts, int count,
                                                         const ContactParticles& particles,
                                                         const ContactStep& step) {
    using S = StillLanes<L>;
    using D = typename S::D;
    using M = typename S::M;
    using V = typename S::V;
    uint32_t index[L];
    decltype(contacts) lane[L];
    laneContacts<L>(contacts, count, lane, index);
    D normal[4], coefficients[4], tangent[4], anchored[4];
    loadColumns(lane, offsetof(ParticleContact, normal), normal);                // n, radius
    loadColumns(lane, offsetof(ParticleContact, staticFriction), coefficients);  // μ_s, μ_d, e, λ_n
    loadColumns(lane, offsetof(ParticleContact, lambdaTangent), tangent);  // λ_t, friction impulse
    // (still), anchor
    loadColumns(lane, offsetof(ParticleContact, anchor) - sizeof(double), anchored);
    const V n = {normal[0], normal[1], normal[2]}, anchor = {anchored[1], anchored[2], anchored[3]};
    const D radius = normal[3], mu = coefficients[0];
    D lambdaNormal = coefficients[3], lambdaTangent = tangent[0];
    V friction = {tangent[1], tangent[2], tangent[3]};
    V x = S::gather(particles.x, index), v = S::gather(particles.v, index);
    const V xPrev = S::gather(particles.xPrev, index);
    const D w = S::gather(particles.invMass, index);
    D held = S::gather(particles.heldImpulse, index);
    const D zero = S::all(0.0);
    v = {v.x + S::all(step.gravityStep.x()), v.y + S::all(step.gravityStep.y()),
         v.z + S::all(step.gravityStep.z())};

    // The held impulse goes to λ_n and leaves the particle.
    const M take = held > zero;
    lambdaNormal = S::select(take, lambdaNormal + held, lambdaNormal);
    held = S::select(take, zero, held);

    // Eq. 26, its depth capped by the approach.
    const V surface = S::minusScaled(x, radius, n);
    D depth = S::dot(V{anchor.x - surface.x, anchor.y - surface.y, anchor.z - surface.z}, n);
    if (step.capPushOut) {
        const D approach = -S::dot(v, n);
        const D slowest = S::all(contact_detail::kPushOutSpeed);
        const D allowed = S::all(step.h) * S::select(approach < slowest, slowest, approach);
        depth = S::select(depth > zero, S::select(allowed < depth, allowed, depth), depth);
    }
    const M pushes = depth > zero;
    const D deltaLambda = depth / w;
    x = S::select(pushes, S::plusScaled(x, w * deltaLambda, n), x);
    const D pushed = S::select(pushes, deltaLambda, zero);
    const M pushedSome = pushed > zero;
    lambdaNormal = S::select(pushedSome, lambdaNormal + pushed, lambdaNormal);
    M holds = (pushedSome | take) & (mu > zero);

    // Eqs. 27-28: the particle's own tangential motion undone while λ_t ≤ μ_s λ_n.
    const V motion = {x.x - xPrev.x, x.y - xPrev.y, x.z - xPrev.z};
    const V slip = S::minusScaled(motion, S::dot(motion, n), n);
    const D length = S::sqrt(S::dot(slip, slip));
    holds &= length > S::all(kDirectionEpsilon);
    const V t = S::divided(slip, length);
    const D deltaTangent = length / w;
    holds &= ~(lambdaTangent + deltaTangent > mu * lambdaNormal);
    lambdaTangent = S::select(holds, lambdaTangent + deltaTangent, lambdaTangent);
    friction = S::select(holds, S::minusScaled(friction, deltaTangent, t), friction);
    x = S::select(holds, S::minusScaled(x, w * deltaTangent, t), x);

    coefficients[3] = lambdaNormal;
    tangent[0] = lambdaTangent, tangent[1] = friction.x, tangent[2] = friction.y,
    tangent[3] = friction.z;
    storeColumns(lane, offsetof(ParticleContact, staticFriction), coefficients);
    storeColumns(lane, offsetof(ParticleContact, lambdaTangent), tangent);
    for (int l = 0; l < L; ++l) {
        particles.x[index[l]] = S::get(x, l);
        particles.heldImpulse[index[l]] = held[l];
    }
}

/// solveStillContactVelocity (not slid) of contacts[0, count) in lanes, count ≤ L.
template <int L>
[[gnu::always_inline]] inline void stillVelocitiesInLanes(const ParticleContact* contacts,
                                                          int count,
                                                          const ContactParticles& particles,
                                                          const ContactStep& step) {
    using S = StillLanes<L>;
    using D = typename S::D;
    using M = typename S::M;
    using V = typename S::V;
    uint32_t index[L];
    decltype(contacts) lane[L];
    laneContacts<L>(contacts, count, lane, index);
    D normal[4], coefficients[4];
    loadColumns(lane, offsetof(ParticleContact, normal), normal);                // n, radius
    loadColumns(lane, offsetof(ParticleContact, staticFriction), coefficients);  // μ_s, μ_d, e, λ_n
    const V n = {normal[0], normal[1], normal[2]};
    const D mu = coefficients[1], restitution = coefficients[2], lambdaNormal = coefficients[3];
    V v = S::gather(particles.v, index);
    const V vPrev = S::gather(particles.vPrev, index);
    const D w = S::gather(particles.invMass, index);
    const D zero = S::all(0.0);
    const D epsilon = S::all(kDirectionEpsilon), resting = S::all(contact_detail::kRestingSpeed);
    const M pressed = lambdaNormal > zero;

    // Eq. 34: the normal velocity becomes −e v̄_n (no bounce below 2|g|h), the particle taking
    // the whole change (Eq. 33).
    const D vn = S::dot(v, n);
    const D vnBefore = S::dot(vPrev, n);
    const D e = S::select(S::abs(vnBefore) <= S::all(step.restingSpeed), zero, restitution);
    const D bounce = -e * vnBefore;
    const D change = S::select(bounce < zero, zero, bounce) - vn;
    const V normalChange = {change * n.x, change * n.y, change * n.z};
    const M bounces = pressed & (S::abs(change) > resting) &
                      (S::sqrt(S::dot(normalChange, normalChange)) > epsilon);
    const V normalPulse = S::divided(normalChange, w);
    v = S::select(bounces, S::plusScaled(v, w, normalPulse), v);

    // Eq. 30: slip removed by at most μ_d λ_n / h.
    M slides = pressed & (mu > zero);
    const V slip = S::minusScaled(v, S::dot(v, n), n);
    const D slipSpeed = S::sqrt(S::dot(slip, slip));
    slides &= slipSpeed > resting;
    const V t = S::divided(slip, slipSpeed);
    const D maxChange = mu * lambdaNormal / S::all(step.h) * w;
    const D amount = -S::select(slipSpeed < maxChange, slipSpeed, maxChange);
    const V frictionChange = {amount * t.x, amount * t.y, amount * t.z};
    slides &= S::sqrt(S::dot(frictionChange, frictionChange)) > epsilon;
    const V frictionPulse = S::divided(frictionChange, w);
    v = S::select(slides, S::plusScaled(v, w, frictionPulse), v);

    for (int l = 0; l < L; ++l)
        particles.v[index[l]] = S::get(v, l);
}

}  // namespace
}  // namespace substep

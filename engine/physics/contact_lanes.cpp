#include "physics/contact_lanes.h"

#include "physics/contact_kinematics.h"
#include "physics/soft/lanes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

// Every function below that takes or returns lanes is inlined into the two entry points: no
// call passes vectors, so the ABI GCC warns about (with or without AVX) never applies.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace substep::contact_detail {
namespace {

using simd::Lanes;
using Mask = decltype(Lanes{} < Lanes{});
static_assert(simd::kLanes == kContactLanes, "one pair per lane");

[[gnu::always_inline]] inline bool anyLane(const Mask& m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }

[[gnu::always_inline]] inline void takeSquareRoot(Lanes& v) {
#pragma GCC unroll 4
    for (int l = 0; l < kContactLanes; ++l) v[l] = std::sqrt(v[l]);
}

/// A 3-vector per lane, with Eigen's operations in Eigen's order (as contact_patch.cpp's Triple):
/// a dot product (x x' + y y') + z z', a cross product row by row.
struct LaneVec {
    Lanes x, y, z;
};

[[gnu::always_inline]] inline LaneVec operator+(const LaneVec& a, const LaneVec& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
[[gnu::always_inline]] inline LaneVec operator-(const LaneVec& a, const LaneVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
[[gnu::always_inline]] inline LaneVec operator-(const LaneVec& a) { return {-a.x, -a.y, -a.z}; }
[[gnu::always_inline]] inline LaneVec operator*(const Lanes& s, const LaneVec& a) { return {s * a.x, s * a.y, s * a.z}; }
[[gnu::always_inline]] inline Lanes dot(const LaneVec& a, const LaneVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
[[gnu::always_inline]] inline LaneVec cross(const LaneVec& a, const LaneVec& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
[[gnu::always_inline]] inline LaneVec select(const Mask& m, const LaneVec& a, const LaneVec& b) {
    return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
}

/// A unit quaternion per lane.
struct LaneQuat {
    Lanes x, y, z, w;
};

/// Eigen's q * v: u = 2 q⃗ × v, then v + w u + q⃗ × u.
[[gnu::always_inline]] inline LaneVec rotate(const LaneQuat& q, const LaneVec& v) {
    const LaneVec axis{q.x, q.y, q.z};
    LaneVec u = cross(axis, v);
    u = u + u;
    return v + q.w * u + cross(axis, u);
}

/// addRotation: q + 1/2 [θ, 0] q, renormalised. The product is Eigen's SSE2 quaternion product
/// term by term (its zero w included), the norm Eigen's two-lane sum (x² + z²) + (y² + w²).
[[gnu::always_inline]] inline LaneQuat addRotation(const LaneQuat& q, const LaneVec& r) {
    const Lanes zero{};
    const Lanes px = (zero * q.x + r.y * q.z) - (r.z * q.y - r.x * q.w);
    const Lanes py = (zero * q.y + r.y * q.w) + (r.z * q.x - r.x * q.z);
    const Lanes pz = (zero * q.z - r.y * q.x) + (r.z * q.w + r.x * q.y);
    const Lanes pw = (zero * q.w - r.y * q.y) - (r.z * q.z + r.x * q.x);
    const LaneQuat sum{q.x + 0.5 * px, q.y + 0.5 * py, q.z + 0.5 * pz, q.w + 0.5 * pw};
    Lanes norm = (sum.x * sum.x + sum.z * sum.z) + (sum.y * sum.y + sum.w * sum.w);
    takeSquareRoot(norm);
    const Lanes scale = 1.0 / norm;
    return {sum.x * scale, sum.y * scale, sum.z * scale, sum.w * scale};
}

/// integrateRotation lane by lane, for the lanes set in `lanes`: q and the rotation as columns
/// (x, y, z, w of every lane). Out of line and through memory, so that the rare case leaves the
/// lanes of the common one in registers.
[[gnu::noinline, gnu::cold]] void integrateRotationsOneByOne(double (&q)[4][kContactLanes],
                                                          const double (&rotation)[3][kContactLanes],
                                                          unsigned lanes) {
    for (int l = 0; l < kContactLanes; ++l) {
        if (!(lanes >> l & 1u)) continue;
        Quat one(q[3][l], q[0][l], q[1][l], q[2][l]);
        substep::integrateRotation(one, Vec3(rotation[0][l], rotation[1][l], rotation[2][l]));
        q[0][l] = one.x(), q[1][l] = one.y(), q[2][l] = one.z(), q[3][l] = one.w();
    }
}

/// integrateRotation on the lanes in `turn`: its series for turns up to 0.2 rad, the function
/// itself lane by lane beyond (or for a turn that is not finite).
[[gnu::always_inline]] inline void integrateRotation(LaneQuat& q, const LaneVec& rotation, const Mask& turn) {
    const Lanes half2 = 0.25 * dot(rotation, rotation);
    const Lanes scale = 1.0 + half2 * (1.0 / 3.0 + half2 * (2.0 / 15.0 + half2 * (17.0 / 315.0)));
    const LaneQuat turned = addRotation(q, scale * rotation);
    const Mask rare = turn & ~(half2 < 0.01);
    LaneQuat result{turn ? turned.x : q.x, turn ? turned.y : q.y, turn ? turned.z : q.z, turn ? turned.w : q.w};
    if (anyLane(rare)) [[unlikely]] {
        double columns[4][kContactLanes];
        double rotations[3][kContactLanes];
        std::memcpy(columns[0], &q.x, sizeof q.x), std::memcpy(columns[1], &q.y, sizeof q.y);
        std::memcpy(columns[2], &q.z, sizeof q.z), std::memcpy(columns[3], &q.w, sizeof q.w);
        std::memcpy(rotations[0], &rotation.x, sizeof rotation.x);
        std::memcpy(rotations[1], &rotation.y, sizeof rotation.y);
        std::memcpy(rotations[2], &rotation.z, sizeof rotation.z);
        const unsigned lanes = (rare[0] ? 1u : 0u) | (rare[1] ? 2u : 0u) | (rare[2] ? 4u : 0u) | (rare[3] ? 8u : 0u);
        integrateRotationsOneByOne(columns, rotations, lanes);
        Lanes x, y, z, w;
        std::memcpy(&x, columns[0], sizeof x), std::memcpy(&y, columns[1], sizeof y);
        std::memcpy(&z, columns[2], sizeof z), std::memcpy(&w, columns[3], sizeof w);
        result = {rare ? x : result.x, rare ? y : result.y, rare ? z : result.z, rare ? w : result.w};
    }
    q = result;
}

/// The transpose of four rows of four doubles (a record's fields each) into four columns (a
/// lane per record), and back: it is its own inverse.
[[gnu::always_inline]] inline void transpose(Lanes& a, Lanes& b, Lanes& c, Lanes& d) {
    const Lanes ab02 = __builtin_shufflevector(a, b, 0, 4, 2, 6);  // a0 b0 a2 b2
    const Lanes ab13 = __builtin_shufflevector(a, b, 1, 5, 3, 7);  // a1 b1 a3 b3
    const Lanes cd02 = __builtin_shufflevector(c, d, 0, 4, 2, 6);
    const Lanes cd13 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
    a = __builtin_shufflevector(ab02, cd02, 0, 1, 4, 5);
    b = __builtin_shufflevector(ab13, cd13, 0, 1, 4, 5);
    c = __builtin_shufflevector(ab02, cd02, 2, 3, 6, 7);
    d = __builtin_shufflevector(ab13, cd13, 2, 3, 6, 7);
}

/// The four doubles at byte `offset` of each lane's record, as four columns: a load and a share
/// of a transpose per lane, where field by field took a load and an insert per double (and a
/// vector built through the stack).
template <class Record>
[[gnu::always_inline]] inline void loadColumns(Record* const (&record)[kContactLanes], size_t offset, Lanes& a,
                                               Lanes& b, Lanes& c, Lanes& d) {
    const auto row = [&](int l) { return reinterpret_cast<const char*>(record[l]) + offset; };
    std::memcpy(&a, row(0), sizeof a), std::memcpy(&b, row(1), sizeof b);
    std::memcpy(&c, row(2), sizeof c), std::memcpy(&d, row(3), sizeof d);
    transpose(a, b, c, d);
}

/// The inverse of loadColumns, for the first `count` lanes of `store`.
template <class Record>
[[gnu::always_inline]] inline void storeColumns(Record* const (&record)[kContactLanes], size_t offset, Lanes a,
                                                Lanes b, Lanes c, Lanes d, const Mask& store, int count) {
    transpose(a, b, c, d);
    const auto row = [&](int l) { return reinterpret_cast<char*>(record[l]) + offset; };
    // Lane by lane with constant indices, so that the rows stay in registers.
    if (store[0]) std::memcpy(row(0), &a, sizeof a);
    if (count > 1 && store[1]) std::memcpy(row(1), &b, sizeof b);
    if (count > 2 && store[2]) std::memcpy(row(2), &c, sizeof c);
    if (count > 3 && store[3]) std::memcpy(row(3), &d, sizeof d);
}

// A body's fields read four doubles at a time, each with what follows it: x (and the padding
// after it), q, v (and ω.x), ω (and xPrev.x), xPrev (and padding), qPrev, v̄ (and ω̄.x),
// ω̄ (and 1/m), and 1/m with the three inverse moments.
static_assert(offsetof(Body, q) == offsetof(Body, x) + 4 * sizeof(double));
static_assert(offsetof(Body, omega) == offsetof(Body, v) + 3 * sizeof(double));
static_assert(offsetof(Body, xPrev) == offsetof(Body, omega) + 3 * sizeof(double));
static_assert(offsetof(Body, qPrev) == offsetof(Body, xPrev) + 4 * sizeof(double));
static_assert(offsetof(Body, omegaPrev) == offsetof(Body, vPrev) + 3 * sizeof(double));
static_assert(offsetof(Body, invMass) == offsetof(Body, omegaPrev) + 3 * sizeof(double));
static_assert(offsetof(Body, invInertia) == offsetof(Body, invMass) + sizeof(double));

/// One side of the lanes' pairs: a body per lane and the state the solve reads and writes. The
/// unused lanes repeat lane 0's body and are never stored.
struct LaneBodies {
    Body* body[kContactLanes];
    LaneVec x;
    Lanes afterX;  ///< the padding after x, written back as it was read
    LaneQuat q;
    Lanes invMass;
    LaneVec invInertia;
    Mask moving;   ///< invMass ≠ 0: corrections move it
    Mask turning;  ///< moving and rotating: corrections turn it
    Mask isotropic;
    bool anyAnisotropic = false;

    LaneBodies(Body* bodies, const uint32_t (&index)[kContactLanes]) {
#pragma GCC unroll 4
        for (int l = 0; l < kContactLanes; ++l) {
            const Body& b = *(body[l] = &bodies[index[l]]);
            turning[l] = b.rotates() ? -1 : 0;
            isotropic[l] = b.isotropic ? -1 : 0;
        }
        loadColumns(body, offsetof(Body, x), x.x, x.y, x.z, afterX);
        loadColumns(body, offsetof(Body, q), q.x, q.y, q.z, q.w);
        loadColumns(body, offsetof(Body, invMass), invMass, invInertia.x, invInertia.y, invInertia.z);
        moving = invMass != 0.0;
        turning &= moving;
        anyAnisotropic = anyLane(turning & ~isotropic);
    }

    /// The 3-vector at byte `offset`, and the double after it.
    [[gnu::always_inline]] LaneVec gather(size_t offset, Lanes& after) const {
        LaneVec v;
        loadColumns(body, offset, v.x, v.y, v.z, after);
        return v;
    }

    [[gnu::always_inline]] LaneVec gather(size_t offset) const {
        Lanes after;
        return gather(offset, after);
    }

    [[gnu::always_inline]] LaneQuat gatherQuat(size_t offset) const {
        LaneQuat v;
        loadColumns(body, offset, v.x, v.y, v.z, v.w);
        return v;
    }

    /// Writes back the pose of every moving body among the first `count` lanes.
    [[gnu::always_inline]] void storePose(int count) const {
        storeColumns(body, offsetof(Body, x), x.x, x.y, x.z, afterX, moving, count);
        storeColumns(body, offsetof(Body, q), q.x, q.y, q.z, q.w, turning, count);
    }

    /// Writes back the velocities of every moving body among the first `count` lanes (and the
    /// xPrev.x read after ω, as it was).
    [[gnu::always_inline]] void storeVelocities(const LaneVec& v, const LaneVec& omega, const Lanes& afterOmega,
                                                int count) const {
        storeColumns(body, offsetof(Body, v), v.x, v.y, v.z, omega.x, moving, count);
        storeColumns(body, offsetof(Body, omega), omega.x, omega.y, omega.z, afterOmega, moving, count);
    }
};

/// pointResponse on the lanes: w and the turn per unit multiplier of a correction along unit n
/// at offset r (Eq. 2 or Eq. 3, with Eq. 8 or Eq. 9); nothing for a body that does not move.
struct LaneResponse {
    Lanes w;
    LaneVec turn;
};

[[gnu::always_inline]] inline LaneResponse respond(const LaneBodies& b, const LaneVec& r, const LaneVec& n) {
    const LaneVec rn = cross(r, n);
    LaneResponse s{b.invMass + b.invInertia.x * dot(rn, rn), b.invInertia.x * rn};
    if (b.anyAnisotropic) {
        // Into the rest frame and back (paper 3.3.2): q⁻¹ is q with its axis negated.
        const LaneQuat inverse{-b.q.x, -b.q.y, -b.q.z, b.q.w};
        const LaneVec rnBody = rotate(inverse, rn);
        const LaneVec scaled{b.invInertia.x * rnBody.x, b.invInertia.y * rnBody.y, b.invInertia.z * rnBody.z};
        const Lanes w = b.invMass + dot(rnBody, scaled);
        s.w = b.isotropic ? s.w : w;
        s.turn = select(b.isotropic, s.turn, rotate(b.q, scaled));
    }
    const Lanes zero{};
    s.w = b.turning ? s.w : (b.moving ? b.invMass : zero);
    s.turn = select(b.turning, s.turn, LaneVec{zero, zero, zero});
    return s;
}

/// movePoint on the lanes in `apply`: moved by p / m and turned by Δλ I⁻¹ (r × n) (Eq. 6 to Eq. 9).
[[gnu::always_inline]] inline void movePoint(LaneBodies& b, const LaneResponse& s, const LaneVec& p,
                                             const Lanes& deltaLambda, const Mask& apply) {
    b.x = select(apply & b.moving, b.x + b.invMass * p, b.x);
    integrateRotation(b.q, deltaLambda * s.turn, apply & b.turning);
}

/// pointVelocity on the lanes: v + ω × r.
[[gnu::always_inline]] inline LaneVec pointVelocity(const LaneVec& v, const LaneVec& omega, const LaneVec& r) {
    return v + cross(omega, r);
}

// A point's fields read four at a time: local0 (and local1.x), local1 (and n.x), n (and λ_n);
// a pair's μ_s, μ_d, e (and what follows).
static_assert(offsetof(Contact, local1) == offsetof(Contact, local0) + 3 * sizeof(double));
static_assert(offsetof(Contact, normal) == offsetof(Contact, local1) + 3 * sizeof(double));
static_assert(offsetof(Contact, lambdaNormal) == offsetof(Contact, normal) + 3 * sizeof(double));
static_assert(offsetof(ContactPair, dynamicFriction) == offsetof(ContactPair, staticFriction) + sizeof(double));
static_assert(offsetof(ContactPair, restitution) == offsetof(ContactPair, dynamicFriction) + sizeof(double));
static_assert(offsetof(ContactPair, restitution) + 2 * sizeof(double) <= sizeof(ContactPair));

/// The lanes' pairs and their points: a lane per pair, the unused lanes repeating lane 0.
template <class Pair, class Point>
struct LanePoints {
    Pair* pair[kContactLanes];
    Point* point[kContactLanes];
    uint32_t body0[kContactLanes];
    uint32_t body1[kContactLanes];
    LaneVec local0, local1, normal;
    Lanes lambdaNormal;
    Lanes staticFriction, dynamicFriction, restitution;

    LanePoints(Pair* const* pairs, int count, std::span<Point> contacts) {
#pragma GCC unroll 4
        for (int l = 0; l < kContactLanes; ++l) {
            Pair& p = *(pair[l] = pairs[l < count ? l : 0]);
            point[l] = &contacts[p.first];
            body0[l] = p.body0, body1[l] = p.body1;
        }
        Lanes repeated, unused;
        loadColumns(point, offsetof(Contact, local0), local0.x, local0.y, local0.z, repeated);
        loadColumns(point, offsetof(Contact, local1), local1.x, local1.y, local1.z, repeated);
        loadColumns(point, offsetof(Contact, normal), normal.x, normal.y, normal.z, lambdaNormal);
        loadColumns(pair, offsetof(ContactPair, staticFriction), staticFriction, dynamicFriction, restitution, unused);
    }
};

/// changePointVelocity on the lanes in `apply` (Eq. 33 along unit n).
[[gnu::always_inline]] inline void changePointVelocity(const LaneBodies& b0, const LaneBodies& b1, LaneVec& v0,
                                                       LaneVec& omega0, LaneVec& v1, LaneVec& omega1,
                                                       const LaneResponse& s0, const LaneResponse& s1,
                                                       const LaneVec& n, const Lanes& change, Mask apply) {
    const Lanes w = s0.w + s1.w;
    apply &= w > 0.0;
    const Lanes impulse = change / w;
    v0 = select(apply & b0.moving, v0 + (impulse * b0.invMass) * n, v0);
    omega0 = select(apply & b0.turning, omega0 + impulse * s0.turn, omega0);
    v1 = select(apply & b1.moving, v1 - (impulse * b1.invMass) * n, v1);
    omega1 = select(apply & b1.turning, omega1 - impulse * s1.turn, omega1);
}

[[gnu::always_inline]] inline void solvePositions(ContactPair* const* pairs, int count, std::span<Contact> contacts,
                                                 SolverContext& ctx) {
    const LanePoints<ContactPair, Contact> points(pairs, count, contacts);
    LaneBodies b0(ctx.bodies, points.body0);
    LaneBodies b1(ctx.bodies, points.body1);
    const LaneVec& n = points.normal;
    const Lanes zero{};

    // Eq. 26: the depth along n on the current poses, its push-out capped (pushOut).
    LaneVec r0 = rotate(b0.q, points.local0);
    LaneVec r1 = rotate(b1.q, points.local1);
    Lanes depth = dot((b1.x + r1) - (b0.x + r0), n);
    const Lanes h = zero + ctx.h;
    const Mask capped = ctx.capPushOut ? depth > h : Mask{};
    if (anyLane(capped)) {
        const LaneVec relative = pointVelocity(b0.gather(offsetof(Body, v)), b0.gather(offsetof(Body, omega)), r0) -
                                 pointVelocity(b1.gather(offsetof(Body, v)), b1.gather(offsetof(Body, omega)), r1);
        const Lanes approach = -dot(relative, n);
        const Lanes limit = h * (approach < 1.0 ? zero + 1.0 : approach);  // h max(approach, kPushOutSpeed)
        depth = capped ? (limit < depth ? limit : depth) : depth;
    }

    // The push, Eq. 2 to Eq. 9 with α = 0, where the points overlap and some body moves.
    const LaneResponse s0 = respond(b0, r0, n);
    const LaneResponse s1 = respond(b1, r1, n);
    const Lanes w = s0.w + s1.w;
    const Mask pushed = (depth > kDirectionEpsilon) & (w > 0.0);
    const Lanes deltaLambda = depth / w;                                                          // Eq. 4
    const Lanes lambdaNormal = pushed ? points.lambdaNormal + deltaLambda : points.lambdaNormal;  // Eq. 5
    const LaneVec p = deltaLambda * n;
    movePoint(b0, s0, p, deltaLambda, pushed);    // Eq. 6, Eq. 8
    movePoint(b1, s1, -p, -deltaLambda, pushed);  // Eq. 7, Eq. 9

    // Static friction (Eq. 27, Eq. 28): the slip is the contact's motion during the substep
    // across n, on the lever arms of the pushed poses; held while λ_t stays within μ_s λ_n.
    const Mask holds = pushed & (points.staticFriction > 0.0);
    Lanes lambdaTangent;
#pragma GCC unroll 4
    for (int l = 0; l < kContactLanes; ++l) {
        const ContactPair& pair = *points.pair[l];
        lambdaTangent[l] = pair.lambdaTangent2 == 0.0 ? std::abs(pair.lambdaTangent1) : pair.lambdaTangent();
    }
    if (anyLane(holds)) {
        r0 = select(b0.turning, rotate(b0.q, points.local0), r0);
        r1 = select(b1.turning, rotate(b1.q, points.local1), r1);
        const LaneVec previous0 = b0.gather(offsetof(Body, xPrev)) + rotate(b0.gatherQuat(offsetof(Body, qPrev)), points.local0);
        const LaneVec previous1 = b1.gather(offsetof(Body, xPrev)) + rotate(b1.gatherQuat(offsetof(Body, qPrev)), points.local1);
        const LaneVec motion = ((b0.x + r0) - previous0) - ((b1.x + r1) - previous1);  // Eq. 27
        const LaneVec slip = motion - dot(motion, n) * n;                                // Eq. 28
        const Lanes limit = points.staticFriction * lambdaNormal;
        Lanes slipLength = dot(slip, slip);
        takeSquareRoot(slipLength);
        const LaneVec t{slip.x / -slipLength, slip.y / -slipLength, slip.z / -slipLength};  // −Δp_t / |Δp_t|
        const LaneResponse t0 = respond(b0, r0, t);
        const LaneResponse t1 = respond(b1, r1, t);
        const Lanes wt = t0.w + t1.w;
        const Lanes step = slipLength / wt;
        const Mask sticks = holds & (slipLength > kDirectionEpsilon) & (wt > 0.0) & (lambdaTangent + step <= limit);
        lambdaTangent = sticks ? lambdaTangent + step : lambdaTangent;
        const LaneVec pt = step * t;
        movePoint(b0, t0, pt, step, sticks);
        movePoint(b1, t1, -pt, -step, sticks);
    }

#pragma GCC unroll 4
    for (int l = 0; l < kContactLanes; ++l) {
        if (l >= count) break;
        ContactPair& pair = *points.pair[l];
        points.point[l]->lambdaNormal = lambdaNormal[l];
        pair.lambdaNormal = lambdaNormal[l];
        if (pushed[l]) pair.anchored = false;
        if (holds[l]) {
            pair.lambdaTangent1 = lambdaTangent[l];  // one point: the magnitude is all the readout needs
            pair.lambdaTangent2 = 0.0;
        }
    }
    b0.storePose(count);
    b1.storePose(count);
}

[[gnu::always_inline]] inline void solveVelocities(const ContactPair* const* pairs, int count,
                                                  std::span<const Contact> contacts, Body* bodies, double h,
                                                  double gravity) {
    const LanePoints<const ContactPair, const Contact> points(pairs, count, contacts);
    const LaneBodies b0(bodies, points.body0);
    const LaneBodies b1(bodies, points.body1);
    const LaneVec& n = points.normal;
    const Lanes zero{};
    const Mask touching = points.lambdaNormal > 0.0;
    Lanes afterOmega0, afterOmega1;
    LaneVec v0 = b0.gather(offsetof(Body, v)), omega0 = b0.gather(offsetof(Body, omega), afterOmega0);
    LaneVec v1 = b1.gather(offsetof(Body, v)), omega1 = b1.gather(offsetof(Body, omega), afterOmega1);

    // Eq. 34 (with Eq. 29 and Eq. 33): restitution e v̄_n replaces the normal velocity, e = 0
    // below 2 |g| h; v̄_n is Eq. 29 on the velocities before this substep's derivation.
    const LaneVec r0 = rotate(b0.q, points.local0);
    const LaneVec r1 = rotate(b1.q, points.local1);
    const Lanes vn = dot(pointVelocity(v0, omega0, r0) - pointVelocity(v1, omega1, r1), n);
    const Lanes vnBefore =
        dot(pointVelocity(b0.gather(offsetof(Body, vPrev)), b0.gather(offsetof(Body, omegaPrev)), r0) -
                pointVelocity(b1.gather(offsetof(Body, vPrev)), b1.gather(offsetof(Body, omegaPrev)), r1),
            n);
    const Lanes e = (vnBefore < 0.0 ? -vnBefore : vnBefore) <= 2.0 * gravity * h ? zero : points.restitution;
    const Lanes bounce = -e * vnBefore;
    const Lanes change = (bounce < 0.0 ? zero : bounce) - vn;
    const Mask changes = touching & ((change < 0.0 ? -change : change) > kRestingSpeed);
    if (anyLane(changes))
        changePointVelocity(b0, b1, v0, omega0, v1, omega1, respond(b0, r0, n), respond(b1, r1, n), n, change,
                            changes);

    // Dynamic friction (Eq. 29, Eq. 30, Eq. 33): an impulse of at most h μ_d f_n, f_n = λ_n / h²
    // (ERRATA item 2), against the slip left after the normal step.
    Mask slides = touching & (points.dynamicFriction > 0.0);
    if (anyLane(slides)) {
        const LaneVec after = pointVelocity(v0, omega0, r0) - pointVelocity(v1, omega1, r1);
        const LaneVec slip = after - dot(after, n) * n;  // Eq. 29: v_t
        Lanes slipSpeed = dot(slip, slip);
        takeSquareRoot(slipSpeed);
        slides &= slipSpeed > kRestingSpeed;
        if (anyLane(slides)) {
            const LaneVec t{slip.x / slipSpeed, slip.y / slipSpeed, slip.z / slipSpeed};
            const LaneResponse s0 = respond(b0, r0, t);
            const LaneResponse s1 = respond(b1, r1, t);
            const Lanes maxChange = points.dynamicFriction * points.lambdaNormal / h * (s0.w + s1.w);  // Eq. 30
            const Lanes slowing = -(slipSpeed < maxChange ? slipSpeed : maxChange);
            changePointVelocity(b0, b1, v0, omega0, v1, omega1, s0, s1, t, slowing, slides);
        }
    }
    b0.storeVelocities(v0, omega0, afterOmega0, count);
    b1.storeVelocities(v1, omega1, afterOmega1, count);
}

// The kernels compiled for two instruction sets. The file is compiled with -ffp-contract=off:
// a fused multiply-add would round differently from the scalar path. On the base ISA
// (sixteen SSE registers of two doubles) the four-lane kernel spilled and ran at half the speed
// of the scalar path, which it therefore takes, pair by pair.
[[gnu::target("arch=x86-64-v4")]] void solvePositionsAvx512(ContactPair* const* pairs, int count,
                                                            std::span<Contact> contacts, SolverContext& ctx) {
    solvePositions(pairs, count, contacts, ctx);
}
[[gnu::target("avx2")]] void solvePositionsAvx2(ContactPair* const* pairs, int count, std::span<Contact> contacts,
                                                SolverContext& ctx) {
    solvePositions(pairs, count, contacts, ctx);
}
[[gnu::target("arch=x86-64-v4")]] void solveVelocitiesAvx512(const ContactPair* const* pairs, int count,
                                                             std::span<const Contact> contacts, Body* bodies,
                                                             double h, double gravity) {
    solveVelocities(pairs, count, contacts, bodies, h, gravity);
}
[[gnu::target("avx2")]] void solveVelocitiesAvx2(const ContactPair* const* pairs, int count,
                                                 std::span<const Contact> contacts, Body* bodies, double h,
                                                 double gravity) {
    solveVelocities(pairs, count, contacts, bodies, h, gravity);
}

LaneIsa chosenIsa = widestLaneIsa();

}  // namespace

LaneIsa widestLaneIsa() {
    // x86-64-v4's AVX-512 subsets (a CPU with them has the rest of x86-64-v4 and AVX2).
    static const LaneIsa widest =
        __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw")
            ? LaneIsa::Avx512
            : (__builtin_cpu_supports("avx2") ? LaneIsa::Avx2 : LaneIsa::Base);
    return widest;
}

LaneIsa useLaneIsa(LaneIsa isa) {
    const LaneIsa previous = chosenIsa;
    chosenIsa = std::min(isa, widestLaneIsa());
    return previous;
}

void solveOnePointPositionsInLanes(ContactPair* const* pairs, int count, std::span<Contact> contacts,
                                   SolverContext& ctx) {
    switch (chosenIsa) {
        case LaneIsa::Avx512: return solvePositionsAvx512(pairs, count, contacts, ctx);
        case LaneIsa::Avx2: return solvePositionsAvx2(pairs, count, contacts, ctx);
        case LaneIsa::Base: break;
    }
    for (int i = 0; i < count; ++i) solveContactPositions(*pairs[i], contacts.subspan(pairs[i]->first, 1), ctx);
}

void solveOnePointVelocitiesInLanes(const ContactPair* const* pairs, int count, std::span<const Contact> contacts,
                                    Body* bodies, double h, double gravity) {
    switch (chosenIsa) {
        case LaneIsa::Avx512: return solveVelocitiesAvx512(pairs, count, contacts, bodies, h, gravity);
        case LaneIsa::Avx2: return solveVelocitiesAvx2(pairs, count, contacts, bodies, h, gravity);
        case LaneIsa::Base: break;
    }
    for (int i = 0; i < count; ++i)
        solveContactVelocities(*pairs[i], contacts.subspan(pairs[i]->first, 1), bodies, h, gravity);
}

}  // namespace substep::contact_detail

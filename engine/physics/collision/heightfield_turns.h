#pragma once
/// A heightfield contact's turns between the field's frame and the world (Pose::apply,
/// Pose::applyInverse and the normal's `rotation * n`), the same bits in fewer instructions: the
/// sphere–heightfield narrowphase turns the centre in and a point's two surface points and normal
/// out, four turns in a call of a few hundred instructions, which Eigen's 3-vectors made 50 to 60
/// each. Eigen's quaternion turn (Quaternion::_transformVector, Eigen 3.4) is
///   uv = q.vec × v,  uv += uv,  q v = (v + w uv) + q.vec × uv,
/// each cross product's components a·b − c·d in Eigen's order; the turns here do those operations
/// in that order per coordinate, scalar or two vectors side by side in a pair of SSE2 lanes
/// (IEEE operations lane by lane, no contraction in the base ISA), so the bits are Eigen's.
/// A field in the world's axes (the identity with +0 vector part, rc_car's ground) needs no turn
/// at all: for finite vectors Eigen's gives v + 0, which the overloads taking `plain` return.

#include "physics/collision/contact_manifold.h"

#include <cmath>

namespace substep::heightfield_turns {

/// Two doubles: one SSE2 register.
using Pair = double __attribute__((vector_size(2 * sizeof(double))));

/// q v for v = (x, y, z), as Eigen computes it, for T = double (one vector) or Pair (two); q is
/// (qx, qy, qz, w).
template <class T>
[[gnu::always_inline]] inline void turn(double qx, double qy, double qz, double w, const T& x, const T& y, const T& z,
                                        T& tx, T& ty, T& tz) {
    T ux = qy * z - qz * y, uy = qz * x - qx * z, uz = qx * y - qy * x;
    ux += ux, uy += uy, uz += uz;
    tx = (x + w * ux) + (qy * uz - qz * uy);
    ty = (y + w * uy) + (qz * ux - qx * uz);
    tz = (z + w * uz) + (qx * uy - qy * ux);
}

/// pose.applyInverse(world): the conjugate's turn (q.vec negated) of world − position.
[[gnu::always_inline]] inline Vec3 applyInverse(const Pose& pose, const Vec3& world) {
    const Quat& q = pose.rotation;
    double x, y, z;
    turn<double>(-q.x(), -q.y(), -q.z(), q.w(), world.x() - pose.position.x(), world.y() - pose.position.y(),
                 world.z() - pose.position.z(), x, y, z);
    return {x, y, z};
}

/// pose.apply(a), pose.apply(b) and pose.rotation * n into `p`'s point0, point1 and normal.
[[gnu::always_inline]] inline void turnContact(const Pose& pose, const Vec3& a, const Vec3& b, const Vec3& n,
                                               ContactPoint& p) {
    const Quat& q = pose.rotation;
    const Pair x = {a.x(), b.x()}, y = {a.y(), b.y()}, z = {a.z(), b.z()};
    Pair tx, ty, tz;
    turn<Pair>(q.x(), q.y(), q.z(), q.w(), x, y, z, tx, ty, tz);
    const Vec3& o = pose.position;
    p.point0 = Vec3(o.x() + tx[0], o.y() + ty[0], o.z() + tz[0]);
    p.point1 = Vec3(o.x() + tx[1], o.y() + ty[1], o.z() + tz[1]);
    double nx, ny, nz;
    turn<double>(q.x(), q.y(), q.z(), q.w(), n.x(), n.y(), n.z(), nx, ny, nz);
    p.normal = Vec3(nx, ny, nz);
}

/// Whether q is the identity with +0 for its vector part, bit for bit (a field in the world's
/// axes): Eigen's turn of a finite vector by it or by its conjugate is then `unturned`'s.
[[gnu::always_inline]] inline bool isPlainIdentity(const Quat& q) {
    return q.w() == 1.0 && q.x() == 0.0 && q.y() == 0.0 && q.z() == 0.0 && !std::signbit(q.x()) &&
           !std::signbit(q.y()) && !std::signbit(q.z());
}

/// Whether every coordinate of v is finite (x − x is +0 for those, NaN for ±∞ and NaN).
[[gnu::always_inline]] inline bool isFinite(const Vec3& v) {
    return ((v.x() - v.x()) + (v.y() - v.y()) + (v.z() - v.z())) == 0.0;
}

/// Eigen's turn of a finite v by the plain identity (q.vec +0, w 1) or by its conjugate (q.vec −0):
/// each product of a vector-part zero is a zero, so uv and q.vec × uv are zeros, a non-zero
/// coordinate of v comes out as it went in, and a zero one as +0 (the signs of the zeros added
/// never make a −0 from a −0; the test tries every pattern): v + 0. Not for ±∞ or NaN (0 ∞ is NaN).
[[gnu::always_inline]] inline Vec3 unturned(const Vec3& v) { return {v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}; }

/// turnContact(pose, a, b, n, p) where `plain` says pose.rotation is the plain identity: for
/// finite a, b and n only shifted by the position, with the same bits.
[[gnu::always_inline]] inline void turnContact(const Pose& pose, bool plain, const Vec3& a, const Vec3& b,
                                               const Vec3& n, ContactPoint& p) {
    if (!plain || !(isFinite(a) && isFinite(b) && isFinite(n))) return turnContact(pose, a, b, n, p);
    const Vec3& o = pose.position;
    p.point0 = Vec3(o.x() + (a.x() + 0.0), o.y() + (a.y() + 0.0), o.z() + (a.z() + 0.0));
    p.point1 = Vec3(o.x() + (b.x() + 0.0), o.y() + (b.y() + 0.0), o.z() + (b.z() + 0.0));
    p.normal = unturned(n);
}

/// applyInverse(pose, world) where `plain` says pose.rotation is the plain identity: for a
/// finite world − position, only that difference, with the same bits.
[[gnu::always_inline]] inline Vec3 applyInverse(const Pose& pose, bool plain, const Vec3& world) {
    const Vec3 d(world.x() - pose.position.x(), world.y() - pose.position.y(), world.z() - pose.position.z());
    if (!plain || !isFinite(d)) return applyInverse(pose, world);
    return unturned(d);
}

}  // namespace substep::heightfield_turns

#pragma once
/// Vector and quaternion helpers shared by the physics core (Eigen, double precision).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace substep {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// Below this length a direction is treated as undefined (degenerate geometry guard).
inline constexpr double kDirectionEpsilon = 1e-12;

/// Turns q by the small world-space rotation vector `rotation` with the linearised update of
/// Algorithm 2 and Eqs. 8-9: q <- q + 1/2 [rotation, 0] q, then renormalises.
inline void addRotation(Quat& q, const Vec3& rotation) {
    const Quat dq(0.0, rotation.x(), rotation.y(), rotation.z());
    const Quat product = dq * q;
    q.coeffs() += 0.5 * product.coeffs();
    q.normalize();
}

/// Rotation vector (axis times angle, angle in [0, pi]) of the unit quaternion q.
inline Vec3 rotationVector(const Quat& q) {
    const double sign = q.w() < 0.0 ? -1.0 : 1.0;  // the shorter way round
    const Vec3 v = sign * q.vec();
    const double s = v.norm();
    if (s < kDirectionEpsilon) return 2.0 * v;  // small angle: 2 sin(θ/2) ≈ θ
    const double angle = 2.0 * std::atan2(s, sign * q.w());
    return v * (angle / s);
}

/// Any unit vector perpendicular to the unit vector n.
inline Vec3 anyPerpendicular(const Vec3& n) {
    const Vec3 helper = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
    return n.cross(helper).normalized();
}

/// Rotation vector turning unit vector `from` onto unit vector `to` by the shortest arc, with the
/// true angle as its length (Eq. 20 uses from x to, whose length sin θ understates large errors).
/// Anti-parallel vectors have no unique axis: any perpendicular one is taken.
inline Vec3 rotationBetween(const Vec3& from, const Vec3& to) {
    const Vec3 axis = from.cross(to);
    const double s = axis.norm();
    const double c = from.dot(to);
    if (s < kDirectionEpsilon) {
        if (c > 0.0) return Vec3::Zero();
        return anyPerpendicular(from) * M_PI;
    }
    return axis * (std::atan2(s, c) / s);
}

/// Signed angle from unit vector n1 to unit vector n2 about unit axis n, in (-pi, pi].
/// Algorithm 3's arcsin with its fold beyond ±90° (ERRATA item 3: φ <- π - φ), written as atan2.
inline double signedAngle(const Vec3& n, const Vec3& n1, const Vec3& n2) {
    return std::atan2(n1.cross(n2).dot(n), n1.dot(n2));
}

/// Wraps an angle into (-pi, pi].
inline double wrapAngle(double angle) {
    angle = std::remainder(angle, 2.0 * M_PI);
    return angle <= -M_PI ? angle + 2.0 * M_PI : angle;
}

inline bool isFinite(const Vec3& v) { return v.allFinite(); }
inline bool isFinite(const Quat& q) { return q.coeffs().allFinite(); }

}  // namespace substep

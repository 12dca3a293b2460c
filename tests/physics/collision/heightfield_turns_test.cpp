// Tests engine/physics/collision/heightfield_turns.h: the heightfield contacts' turns against
// Eigen's (Pose::apply, Pose::applyInverse, Quaternion * vector), bit for bit, over random
// rotations (the identity, quarter turns and any) and vectors (zeros of either sign, any scale);
// and the plain identity's turns as shifts, against Eigen's, over every pattern of zeros, signs,
// infinities and NaNs.

#include "physics/collision/heightfield_turns.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace substep {
namespace {

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

/// A coordinate of either sign from 1e-8 to 1e4, or a zero of either sign.
double someCoordinate(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
    if (unit(rng) < 0.15) return sign * 0.0;
    return sign * std::pow(10.0, -8.0 + 12.0 * unit(rng));
}

Vec3 someVector(std::mt19937& rng) { return {someCoordinate(rng), someCoordinate(rng), someCoordinate(rng)}; }

/// The identity (its zeros of either sign), a quarter or half turn about an axis, or any turn.
Quat someRotation(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<int> kind(0, 3), axis(0, 2);
    switch (kind(rng)) {
        case 0: {
            Quat q(1.0, 0.0, 0.0, 0.0);
            for (int k = 0; k < 3; ++k) q.coeffs()[k] = unit(rng) < 0.5 ? -0.0 : 0.0;
            return q;
        }
        case 1: return Quat(Eigen::AngleAxisd(unit(rng) < 0.5 ? 0.5 * M_PI : M_PI, Vec3::Unit(axis(rng))));
        default: return Quat(Eigen::AngleAxisd(7.0 * unit(rng), someVector(rng).normalized()));
    }
}

TEST(HeightfieldTurns, GiveEigensBits) {
    std::mt19937 rng(5);
    int turned = 0;
    for (int k = 0; k < 200000; ++k) {
        const Pose pose{someVector(rng), someRotation(rng)};
        const Vec3 a = someVector(rng), b = someVector(rng), n = someVector(rng);
        if (!n.allFinite() || n.isZero(0.0)) continue;
        ContactPoint p;
        heightfield_turns::turnContact(pose, a, b, n.normalized(), p);
        ASSERT_TRUE(sameBits(p.point0, pose.apply(a))) << k;
        ASSERT_TRUE(sameBits(p.point1, pose.apply(b))) << k;
        ASSERT_TRUE(sameBits(p.normal, Vec3(pose.rotation * n.normalized()))) << k;
        ASSERT_TRUE(sameBits(heightfield_turns::applyInverse(pose, a), pose.applyInverse(a))) << k;
        ++turned;
    }
    EXPECT_GT(turned, 190000);
}


/// A coordinate of one of eight kinds: ±0, a positive or negative number from 1e-310 (subnormal)
/// to 1e300, ±∞, NaN.
double coordinateOfKind(int kind, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double number = std::pow(10.0, -310.0 + 610.0 * unit(rng));
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    constexpr std::array<double, 8> signs{0.0, -0.0, 1.0, -1.0, kInfinity, -kInfinity, 0.0, 0.0};
    if (kind == 6) return std::numeric_limits<double>::quiet_NaN();
    if (kind == 7) return std::nextafter(0.0, unit(rng) < 0.5 ? 1.0 : -1.0);  // the smallest subnormal
    return kind == 2 || kind == 3 ? signs[kind] * number : signs[kind];
}

TEST(HeightfieldTurns, ThePlainIdentityTurnsAsAShift) {
    // Every pattern of the eight kinds over a vector's three coordinates (512), many times over,
    // against Eigen's turns by the identity with +0 vector part (Quat::Identity()) and by its
    // conjugate: for a finite vector the shifts give their bits; for any other the shifted
    // overloads fall back to the turns (0 ∞ is NaN in Eigen's cross products), whose NaNs are
    // heightfield_turns' own (Eigen's are only compared where the vectors are finite).
    std::mt19937 rng(18);
    std::uniform_int_distribution<int> kindOf(0, 7);
    int finite = 0;
    for (int k = 0; k < 200000; ++k) {
        const int pattern = k % 512;
        const Vec3 v(coordinateOfKind(pattern % 8, rng), coordinateOfKind(pattern / 8 % 8, rng),
                     coordinateOfKind(pattern / 64, rng));
        const Vec3 a = someVector(rng), n = someVector(rng);
        const Pose pose{Vec3(coordinateOfKind(kindOf(rng) % 4, rng), coordinateOfKind(kindOf(rng) % 4, rng),
                             coordinateOfKind(kindOf(rng) % 4, rng)),
                        Quat::Identity()};
        ASSERT_TRUE(heightfield_turns::isPlainIdentity(pose.rotation));
        if (heightfield_turns::isFinite(v)) {
            ++finite;
            ASSERT_TRUE(sameBits(heightfield_turns::unturned(v), Vec3(Quat::Identity() * v))) << k;
            ASSERT_TRUE(sameBits(heightfield_turns::unturned(v), Vec3(Quat::Identity().conjugate() * v))) << k;
        }
        // The overloads for a pose, with v in every place, finite or not.
        const bool eigens = heightfield_turns::isFinite(v) && heightfield_turns::isFinite(a) &&
                            heightfield_turns::isFinite(n) && heightfield_turns::isFinite(pose.position);
        ASSERT_TRUE(sameBits(heightfield_turns::applyInverse(pose, true, v), heightfield_turns::applyInverse(pose, v)))
            << k;
        if (eigens && heightfield_turns::isFinite(v - pose.position)) {
            ASSERT_TRUE(sameBits(heightfield_turns::applyInverse(pose, true, v), pose.applyInverse(v))) << k;
        }
        for (int place = 0; place < 3; ++place) {
            const Vec3& p0 = place == 0 ? v : a;
            const Vec3& p1 = place == 1 ? v : a;
            const Vec3& normal = place == 2 ? v : n;
            ContactPoint shifted, turned;
            heightfield_turns::turnContact(pose, true, p0, p1, normal, shifted);
            heightfield_turns::turnContact(pose, p0, p1, normal, turned);
            ASSERT_TRUE(sameBits(shifted.point0, turned.point0)) << k << " " << place;
            ASSERT_TRUE(sameBits(shifted.point1, turned.point1)) << k << " " << place;
            ASSERT_TRUE(sameBits(shifted.normal, turned.normal)) << k << " " << place;
            if (!eigens) continue;
            ASSERT_TRUE(sameBits(shifted.point0, pose.apply(p0))) << k << " " << place;
            ASSERT_TRUE(sameBits(shifted.point1, pose.apply(p1))) << k << " " << place;
            ASSERT_TRUE(sameBits(shifted.normal, Vec3(pose.rotation * normal))) << k << " " << place;
        }
    }
    EXPECT_GT(finite, 200000 / 5);  // (5/8)³ of the draws
}

TEST(HeightfieldTurns, OnlyThePlainIdentityIsPlain) {
    // Exactly the identity with +0 for its vector part: any other keeps the turns.
    EXPECT_TRUE(heightfield_turns::isPlainIdentity(Quat::Identity()));
    EXPECT_FALSE(heightfield_turns::isPlainIdentity(Quat(1.0, -0.0, 0.0, 0.0)));
    EXPECT_FALSE(heightfield_turns::isPlainIdentity(Quat(1.0, 0.0, -0.0, 0.0)));
    EXPECT_FALSE(heightfield_turns::isPlainIdentity(Quat(1.0, 0.0, 0.0, -0.0)));
    EXPECT_FALSE(heightfield_turns::isPlainIdentity(Quat(-1.0, 0.0, 0.0, 0.0)));
    EXPECT_FALSE(heightfield_turns::isPlainIdentity(Quat(std::nextafter(1.0, 2.0), 0.0, 0.0, 0.0)));
    EXPECT_FALSE(heightfield_turns::isPlainIdentity(Quat(1.0, 1e-300, 0.0, 0.0)));
}

}  // namespace
}  // namespace substep

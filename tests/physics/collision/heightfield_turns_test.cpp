// Tests engine/physics/collision/heightfield_turns.h: the heightfield contacts' turns against
// Eigen's (Pose::apply, Pose::applyInverse, Quaternion * vector), bit for bit, over random
// rotations (the identity, quarter turns and any) and vectors (zeros of either sign, any scale).

#include "physics/collision/heightfield_turns.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
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

}  // namespace
}  // namespace substep

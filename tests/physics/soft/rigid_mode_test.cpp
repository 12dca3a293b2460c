// Tests engine/physics/soft/rigid_mode.h and rigid_mode.cpp: a particle set's moments against the
// closed forms of point masses, the momentum-keeping spin against its defining equation
// Rot(h ω) I ω = L, and the passes in vector lanes against their formulas particle by particle,
// for every count of particles left over after the blocks of four, and the elements' warm starts
// turned with their body against the quaternion product.
#include "physics/soft/rigid_mode.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace substep {
namespace {

TEST(RigidMode, MomentsOfABoxsCornersFarFromTheOrigin) {
    // Eight particles of mass m at (±a, ±b, ±c) from a centre 1 km away, moving rigidly:
    // I = 8 m diag(b² + c², a² + c², a² + b²), L = I ω, momentum 8 m v.
    const double m = 0.7, a = 0.1, b = 0.2, c = 0.3;
    const Vec3 centre(1000.0, -400.0, 250.0), velocity(1, -2, 0.5), omega(0.3, -4.0, 2.0);
    std::vector<Vec3> x, v;
    std::vector<double> masses(8, m);
    for (int n = 0; n < 8; ++n) {
        const Vec3 r((n & 1 ? a : -a), (n & 2 ? b : -b), (n & 4 ? c : -c));
        x.push_back(centre + r);
        v.push_back(velocity + omega.cross(r));
    }
    const RigidModeMoments moments = rigidModeMoments(x.data(), v.data(), masses.data(), 8);
    const Mat3 inertia =
        8 * m * Vec3(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal().toDenseMatrix();
    EXPECT_NEAR(moments.mass, 8 * m, 1e-15);
    EXPECT_LT((moments.centre - centre).norm(), 1e-12);
    EXPECT_LT((moments.velocity - velocity).norm(), 1e-14);
    EXPECT_LT((moments.inertia - inertia).norm(), 1e-9 * inertia.norm());  // summed 1 km out
    EXPECT_LT((moments.angularMomentum - inertia * omega).norm(), 1e-9 * (inertia * omega).norm());
}

TEST(RigidMode, TheSpinKeepsTheAngularMomentumThroughTheTurn) {
    // An anisotropic inertia at a general orientation: after turning by h ω the inertia is
    // Rot I Rotᵀ and the angular momentum Rot I ω, which must still be L.
    const Mat3 turn = Quat(Eigen::AngleAxisd(0.8, Vec3(1, 2, -1).normalized())).toRotationMatrix();
    const Mat3 inertia = turn * Vec3(0.5, 2.0, 3.5).asDiagonal() * turn.transpose();
    const Vec3 angularMomentum(3.0, -1.0, 7.0);
    for (const double h : {1e-4, 1e-3, 1e-2}) {
        const Vec3 omega = momentumKeepingSpin(inertia, angularMomentum, h);
        Quat rotation = Quat::Identity();
        integrateRotation(rotation, h * omega);
        const Vec3 after = rotation * Vec3(inertia * omega);
        EXPECT_LT((after - angularMomentum).norm(), 1e-12 * angularMomentum.norm()) << h;
        // The explicit spin I⁻¹ L would turn L with the body (a first-order error): the test
        // tells them apart.
        const Vec3 explicitSpin = inertia.inverse() * angularMomentum;
        Quat explicitTurn = Quat::Identity();
        integrateRotation(explicitTurn, h * explicitSpin);
        const Vec3 explicitAfter = explicitTurn * Vec3(inertia * explicitSpin);
        EXPECT_GT((explicitAfter - angularMomentum).norm(), 1e-5 * angularMomentum.norm()) << h;
    }
}

TEST(RigidMode, NoSpinForParticlesOnALine) {
    // Inertia of masses on the x axis: zero about x, so no inverse and no turn, never a NaN.
    const Mat3 line = Vec3(0.0, 2.0, 2.0).asDiagonal();
    EXPECT_EQ(momentumKeepingSpin(line, Vec3(1, 1, 1), 1e-3), Vec3::Zero());
    EXPECT_EQ(momentumKeepingSpin(Mat3::Zero(), Vec3(1, 1, 1), 1e-3), Vec3::Zero());
}

/// Particles of uneven masses at uneven positions and velocities, 300 m from the origin.
struct Particles {
    std::vector<Vec3> x, xPrev, v;
    std::vector<double> m;
    explicit Particles(int count) {
        for (int i = 0; i < count; ++i) {
            const double k = i + 1;
            x.push_back(Vec3(300, -20, 7) + 0.1 * Vec3(std::sin(k), std::cos(2 * k), std::sin(3 * k)));
            xPrev.push_back(x.back() + 1e-3 * Vec3(std::cos(5 * k), std::sin(7 * k), 0.5));
            v.push_back(Vec3(std::sin(11 * k), 2 * std::cos(13 * k), -1.0));
            m.push_back(0.5 + 0.25 * (i % 3));
        }
    }
};

double distance(const Mat3& a, const Mat3& b) { return (a - b).norm(); }

TEST(RigidMode, PassesInLanesMatchTheirFormulasForEveryRemainder) {
    const Mat3 arc = 1e-3 * Quat(Eigen::AngleAxisd(0.7, Vec3(1, -2, 3).normalized())).toRotationMatrix();
    const Mat3 spin = crossMatrix(Vec3(0.3, -4.0, 2.0));
    const Mat3 turnBack = 2.0 * arc;
    const Vec3 gravityStep(0, -0.01, 0), centre(300, -20, 7.01), centrePrev(300.001, -20, 7);
    const double h = 1e-3;
    for (int count = 1; count <= 9; ++count) {
        // Moments and turn sums: the sums written out (each up to rounding, 1e-12 relative).
        const Particles p(count);
        const RigidModeMoments moments = rigidModeMoments(p.x.data(), p.v.data(), p.m.data(), count);
        double mass = 0.0;
        Vec3 first = Vec3::Zero(), momentum = Vec3::Zero();
        for (int i = 0; i < count; ++i)
            mass += p.m[i], first += p.m[i] * p.x[i], momentum += p.m[i] * p.v[i];
        const Vec3 c = first / mass;
        Vec3 angular = Vec3::Zero();
        Mat3 inertia = Mat3::Zero();
        for (int i = 0; i < count; ++i) {
            const Vec3 r = p.x[i] - c;
            angular += p.m[i] * r.cross(p.v[i]);
            inertia += p.m[i] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
        }
        EXPECT_NEAR(moments.mass, mass, 1e-14) << count;
        EXPECT_LT((moments.centre - c).norm(), 1e-12) << count;
        EXPECT_LT((moments.velocity - momentum / mass).norm(), 1e-14) << count;
        EXPECT_LT((moments.angularMomentum - angular).norm(), 1e-11 * (1 + angular.norm())) << count;
        EXPECT_LT(distance(moments.inertia, inertia), 1e-11 * (1e-6 + inertia.norm())) << count;

        const Vec3 origin = p.xPrev[0];
        const TurnSums sums = turnSums(p.x.data(), p.xPrev.data(), p.m.data(), count, origin);
        TurnSums expected;
        for (int i = 0; i < count; ++i) {
            const Vec3 a = p.x[i] - origin, b = p.xPrev[i] - origin;
            expected.mass += p.m[i];
            expected.first += p.m[i] * a;
            expected.firstPrev += p.m[i] * b;
            expected.cross += p.m[i] * a * b.transpose();
            expected.spread += p.m[i] * b.squaredNorm();
        }
        EXPECT_NEAR(sums.mass, expected.mass, 1e-14) << count;
        EXPECT_LT((sums.first - expected.first).norm(), 1e-14) << count;
        EXPECT_LT((sums.firstPrev - expected.firstPrev).norm(), 1e-14) << count;
        EXPECT_LT(distance(sums.cross, expected.cross), 1e-14) << count;
        EXPECT_NEAR(sums.spread, expected.spread, 1e-14) << count;

        // Prediction and velocities: each particle's formula, to rounding (1e-15 m at 300 m
        // from the origin is below its last bit); particles past `count` are never written, and
        // the prediction does not store v + gravityStep. It predicts from x_prev into x.
        Particles lanes(count + 1), scalar(count + 1);
        lanes.xPrev = lanes.x;
        predictOnArc(lanes.x.data(), lanes.xPrev.data(), lanes.v.data(), count, gravityStep, h, arc, centre);
        for (int i = 0; i < count; ++i) {
            scalar.xPrev[i] = scalar.x[i];
            scalar.x[i] += h * Vec3(scalar.v[i] + gravityStep) + arc * (scalar.xPrev[i] - centre);
        }
        scalar.xPrev[count] = scalar.x[count];
        for (int i = 0; i <= count; ++i) {
            EXPECT_LT((lanes.x[i] - scalar.x[i]).norm(), 1e-12) << count << " " << i;
            EXPECT_EQ(lanes.v[i], scalar.v[i]) << count << " " << i;
            EXPECT_EQ(lanes.xPrev[i], scalar.xPrev[i]) << count << " " << i;
        }
        const double invH = 1.0 / h;
        const RigidModeMoments derived = deriveOnArc(lanes.x.data(), lanes.xPrev.data(), lanes.v.data(), count,
                                                     invH, spin, centre, turnBack, centrePrev, lanes.m.data());
        for (int i = 0; i < count; ++i) {
            scalar.v[i] = (scalar.x[i] - scalar.xPrev[i]) * invH + spin * (scalar.x[i] - centre) -
                          turnBack * (scalar.xPrev[i] - centrePrev);
        }
        for (int i = 0; i <= count; ++i) {
            EXPECT_LT((lanes.v[i] - scalar.v[i]).norm(), 1e-9) << count << " " << i;  // x/h: 1e-12 m / 1e-3 s
        }
        EXPECT_EQ(lanes.x[count], Particles(count + 1).x[count]);  // untouched
        // The moments it returns are those of x and the new v, as rigidModeMoments sums them.
        const RigidModeMoments after = rigidModeMoments(lanes.x.data(), lanes.v.data(), lanes.m.data(), count);
        EXPECT_NEAR(derived.mass, after.mass, 1e-14 * after.mass) << count;
        EXPECT_LT((derived.centre - after.centre).norm(), 1e-12) << count;
        EXPECT_LT((derived.velocity - after.velocity).norm(), 1e-12 * (1 + after.velocity.norm())) << count;
        EXPECT_LT((derived.angularMomentum - after.angularMomentum).norm(), 1e-11 * (1 + after.angularMomentum.norm())) << count;
        EXPECT_LT(distance(derived.inertia, after.inertia), 1e-11 * (1e-6 + after.inertia.norm())) << count;
    }
}

TEST(RigidMode, ThePredictionReadsOnlyThePreviousPositions) {
    // SoftSystem::integrate swaps x and x_prev and predicts into the array that held the last
    // x_prev: the prediction must give the same bits whatever that array holds (here NaNs or
    // a copy of x_prev), and leave x_prev as it was. Random particles, arcs and counts.
    std::mt19937_64 random(20261125);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const auto vec = [&] { return Vec3(unit(random), unit(random), unit(random)); };
    for (int trial = 0; trial < 40; ++trial) {
        const auto count = static_cast<uint32_t>(1 + random() % 41);
        Mat3 arc;
        for (int k = 0; k < 9; ++k) arc(k / 3, k % 3) = 1e-2 * unit(random);
        const Vec3 gravityStep = 1e-2 * vec(), centre = 100.0 * vec();
        const double h = 1e-3 * (1.0 + unit(random));
        std::vector<Vec3> xPrev, v;
        for (uint32_t i = 0; i < count; ++i)
            xPrev.push_back(centre + vec()), v.push_back(10.0 * vec());
        const std::vector<Vec3> kept = xPrev;
        std::vector<Vec3> fromCopy = xPrev;
        std::vector<Vec3> fromNaN(count + 1, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
        predictOnArc(fromCopy.data(), xPrev.data(), v.data(), count, gravityStep, h, arc, centre);
        predictOnArc(fromNaN.data(), xPrev.data(), v.data(), count, gravityStep, h, arc, centre);
        for (uint32_t i = 0; i < count; ++i) {
            EXPECT_EQ(std::memcmp(fromCopy[i].data(), fromNaN[i].data(), sizeof(Vec3)), 0) << trial << " " << i;
            EXPECT_EQ(std::memcmp(xPrev[i].data(), kept[i].data(), sizeof(Vec3)), 0) << trial << " " << i;
            EXPECT_NE(fromNaN[i], xPrev[i]) << trial << " " << i;  // it moved
        }
        EXPECT_TRUE(std::isnan(fromNaN[count].x())) << trial;  // past the end: not written
    }
}

/// Random particles for the passes' bit-for-bit tests: positions near `centre`, velocities,
/// masses, and positions moved a little from them.
struct RandomParticles {
    std::vector<Vec3> x, xPrev, v;
    std::vector<double> m;
    RandomParticles(std::mt19937_64& random, uint32_t count, const Vec3& centre) {
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        const auto vec = [&] { return Vec3(unit(random), unit(random), unit(random)); };
        for (uint32_t i = 0; i < count; ++i) {
            xPrev.push_back(centre + 0.2 * vec());
            x.push_back(xPrev.back() + 1e-3 * vec());
            v.push_back(5.0 * vec());
            m.push_back(1e-3 * (1.5 + unit(random)));
        }
    }
};

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(Vec3)) == 0; }

// On AVX-512 the passes run eight particles at a time (PassLanes::Widest) and their last
// particles, and PassLanes::Four all of them, four at a time: the same operations per lane, so
// the same bits, which these tests check on random inputs (elsewhere Widest is Four).

TEST(RigidMode, ThePredictionOnEightLanesGivesTheBitsOfFour) {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 80; ++trial) {
        // Odd trials near the origin with a large arc and step, where every term of the sum
        // reaches x's last bits (far from the origin the arc's rounding is below them).
        const double far = trial % 2 == 0 ? 1.0 : 0.0, large = trial % 2 == 0 ? 1.0 : 100.0;
        const auto count = static_cast<uint32_t>(1 + random() % 70);
        const Vec3 centre = far * Vec3(300.0 * unit(random), 10.0 * unit(random), -50.0 * unit(random));
        const RandomParticles p(random, count, centre);
        Mat3 arc;
        for (int k = 0; k < 9; ++k) arc(k / 3, k % 3) = large * 1e-2 * unit(random);
        const Vec3 gravityStep(0.0, -9.81e-3 * (1.0 + unit(random)), 0.0);
        const double h = large * 1e-3 * (1.0 + 0.5 * unit(random));
        std::vector<Vec3> widest(count), four(count);
        predictOnArc(widest.data(), p.xPrev.data(), p.v.data(), count, gravityStep, h, arc, centre);
        predictOnArc(four.data(), p.xPrev.data(), p.v.data(), count, gravityStep, h, arc, centre, PassLanes::Four);
        for (uint32_t i = 0; i < count; ++i)
            EXPECT_TRUE(sameBits(widest[i], four[i])) << trial << " " << i;
    }
}

TEST(RigidMode, TheTurnSumsOnEightLanesGiveTheBitsOfFour) {
    std::mt19937_64 random(13);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 40; ++trial) {
        const auto count = static_cast<uint32_t>(1 + random() % 70);
        const RandomParticles p(random, count, Vec3(-40.0 * unit(random), 2.0, 700.0 * unit(random)));
        const TurnSums widest = turnSums(p.x.data(), p.xPrev.data(), p.m.data(), count, p.xPrev[0]);
        const TurnSums four = turnSums(p.x.data(), p.xPrev.data(), p.m.data(), count, p.xPrev[0], PassLanes::Four);
        EXPECT_EQ(std::memcmp(&widest.mass, &four.mass, sizeof(double)), 0) << trial;
        EXPECT_TRUE(sameBits(widest.first, four.first)) << trial;
        EXPECT_TRUE(sameBits(widest.firstPrev, four.firstPrev)) << trial;
        EXPECT_EQ(std::memcmp(widest.cross.data(), four.cross.data(), sizeof(Mat3)), 0) << trial;
        EXPECT_EQ(std::memcmp(&widest.spread, &four.spread, sizeof(double)), 0) << trial;
    }
}

TEST(RigidMode, TheDerivationOnEightLanesGivesTheBitsOfFour) {
    std::mt19937_64 random(17);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const auto matrix = [&](double scale) {
        Mat3 a;
        for (int k = 0; k < 9; ++k) a(k / 3, k % 3) = scale * unit(random);
        return a;
    };
    for (int trial = 0; trial < 40; ++trial) {
        const auto count = static_cast<uint32_t>(1 + random() % 70);
        const Vec3 centre(100.0 * unit(random), 5.0 * unit(random), -80.0 * unit(random));
        RandomParticles widest(random, count, centre);
        RandomParticles four = widest;
        const Vec3 centrePrev = centre + 1e-3 * Vec3(unit(random), unit(random), unit(random));
        const Mat3 spin = crossMatrix(20.0 * Vec3(unit(random), unit(random), unit(random)));
        const Mat3 turnBack = matrix(10.0);
        const double invH = 1e3 * (1.0 + 0.5 * unit(random));
        const RigidModeMoments a = deriveOnArc(widest.x.data(), widest.xPrev.data(), widest.v.data(), count, invH,
                                               spin, centre, turnBack, centrePrev, widest.m.data());
        const RigidModeMoments b = deriveOnArc(four.x.data(), four.xPrev.data(), four.v.data(), count, invH, spin,
                                               centre, turnBack, centrePrev, four.m.data(), PassLanes::Four);
        for (uint32_t i = 0; i < count; ++i)
            EXPECT_TRUE(sameBits(widest.v[i], four.v[i])) << trial << " " << i;
        EXPECT_EQ(std::memcmp(&a.mass, &b.mass, sizeof(double)), 0) << trial;
        EXPECT_TRUE(sameBits(a.centre, b.centre)) << trial;
        EXPECT_TRUE(sameBits(a.velocity, b.velocity)) << trial;
        EXPECT_TRUE(sameBits(a.angularMomentum, b.angularMomentum)) << trial;
        EXPECT_EQ(std::memcmp(a.inertia.data(), b.inertia.data(), sizeof(Mat3)), 0) << trial;
    }
}

TEST(RigidMode, TurnRotationsOnEightLanesGivesTheBitsOfFour) {
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 40; ++trial) {
        const auto count = static_cast<uint32_t>(1 + random() % 50);
        const Quat turn = Quat(Eigen::AngleAxisd(0.1 * unit(random), Vec3(unit(random), unit(random), 1.0).normalized()));
        std::vector<Quat> widest, four;
        for (uint32_t i = 0; i < count; ++i)
            widest.push_back(Quat(Eigen::AngleAxisd(3.0 * unit(random), Vec3(unit(random), 1.0, unit(random)).normalized())));
        four = widest;
        turnRotations(widest.data(), count, turn);
        turnRotations(four.data(), count, turn, PassLanes::Four);
        for (uint32_t i = 0; i < count; ++i)
            EXPECT_EQ(std::memcmp(widest[i].coeffs().data(), four[i].coeffs().data(), sizeof(Quat)), 0) << trial << " " << i;
    }
}

TEST(RigidMode, TurnRotationsIsTheQuaternionProduct) {
    // The elements' warm starts turned by their body's turn: turn q for each, whatever the
    // count, against Eigen's product.
    const Quat turn = Quat(Eigen::AngleAxisd(0.013, Vec3(1, -2, 0.5).normalized()));
    for (const uint32_t count : {0u, 1u, 5u, 37u}) {
        std::vector<Quat> rotations, expected;
        for (uint32_t i = 0; i <= count; ++i) {  // one past the end stays as it was
            rotations.push_back(Quat(Eigen::AngleAxisd(0.3 * i, Vec3(std::sin(i), 1.0, std::cos(2.0 * i)).normalized())));
            expected.push_back(i < count ? Quat(turn * rotations.back()) : rotations.back());
        }
        turnRotations(rotations.data(), count, turn);
        for (uint32_t i = 0; i <= count; ++i)
            EXPECT_LT((rotations[i].coeffs() - expected[i].coeffs()).norm(), 1e-15) << count << " " << i;
    }
}

}  // namespace
}  // namespace substep

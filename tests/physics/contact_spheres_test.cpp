// Tests engine/physics/contact_spheres.h: the sphere pile's fast path gives the depth and normal
// of the closed forms (r0 + r1 − |c0 − c1| along the line of centres; r − height above a plane
// or a box's face), and, over random poses, radii, planes, boxes and both orders of the bodies,
// exactly the contacts the
// general narrowphase (collide() and World::findPairContacts' change of frame) gives, bit for
// bit, so that a pile's results do not depend on which path found its points.

#include "physics/contact_spheres.h"

#include "physics/collision/narrowphase.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace substep {
namespace {

constexpr double kMargin = 0.005;

Body makeSphere(double radius, const Vec3& x, const Quat& q) {
    Body body =
        makeBody({.shape = sphereShape(radius), .mass = 1.0, .position = x, .orientation = q});
    return body;
}

Body makePlane(const Vec3& normal, double offset) {
    return makeBody({.shape = planeShape(normal, offset), .type = BodyType::Static});
}

Pose poseOf(const Body& b) {
    return {b.userPosition(), b.userOrientation()};
}

/// The general path as World::findPairContacts takes it.
std::vector<Contact> generalContacts(const Body& b0, const Body& b1) {
    ContactManifold manifold;
    collide(b0.shape, poseOf(b0), b1.shape, poseOf(b1), kMargin, manifold);
    std::vector<Contact> out;
    const Quat q0Inverse = b0.q.conjugate();
    const Quat q1Inverse = b1.q.conjugate();
    for (int i = 0; i < manifold.count; ++i) {
        const ContactPoint& point = manifold.points[i];
        out.push_back({.local0 = q0Inverse * (point.point0 - b0.x),
                       .local1 = q1Inverse * (point.point1 - b1.x),
                       .normal = point.normal,
                       .feature = point.feature});
    }
    return out;
}

std::vector<Contact> fastContacts(const Body& b0, const Body& b1) {
    std::vector<Contact> out;
    const int count = appendSpherePairContacts(b0, poseOf(b0), b1, poseOf(b1), kMargin, out);
    EXPECT_EQ(count, static_cast<int>(out.size()));
    return out;
}

void expectSameBits(const Vec3& a, const Vec3& b) {
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(a[k], b[k]) << "component " << k;
}

void expectSameContacts(const Body& b0, const Body& b1) {
    const std::vector<Contact> general = generalContacts(b0, b1);
    const std::vector<Contact> fast = fastContacts(b0, b1);
    ASSERT_EQ(general.size(), fast.size());
    for (size_t i = 0; i < fast.size(); ++i) {
        expectSameBits(fast[i].local0, general[i].local0);
        expectSameBits(fast[i].local1, general[i].local1);
        expectSameBits(fast[i].normal, general[i].normal);
        EXPECT_EQ(fast[i].feature, general[i].feature);
    }
}

Quat randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    return Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

/// Depth of a stored contact on the bodies' poses (as the solve measures it).
double depthOf(const Contact& c, const Body& b0, const Body& b1) {
    return ((b1.x + b1.q * c.local1) - (b0.x + b0.q * c.local0)).dot(c.normal);
}

TEST(ContactSpheres, SphereSphereDepthAndNormalAreTheClosedForms) {
    const Body b0 = makeSphere(0.1, Vec3(0.3, 1.0, -0.2),
                               Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())));
    const Body b1 = makeSphere(0.25, Vec3(0.3 + 0.2, 1.0 + 0.1, -0.2), Quat::Identity());
    const double distance = std::sqrt(0.2 * 0.2 + 0.1 * 0.1);
    const std::vector<Contact> contacts = fastContacts(b0, b1);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(depthOf(contacts[0], b0, b1), 0.35 - distance, 1e-14);
    const Vec3 expectedNormal = Vec3(-0.2, -0.1, 0.0) / distance;  // from body 1 towards body 0
    EXPECT_NEAR((contacts[0].normal - expectedNormal).norm(), 0.0, 1e-15);
}

TEST(ContactSpheres, SpherePlaneDepthIsRadiusMinusHeightInEitherOrder) {
    // Plane 2 y = 1 (not unit), i.e. y = 0.5; sphere of radius 0.2 at height 0.62 above it.
    const Body plane = makePlane(Vec3(0, 2, 0), 1.0);
    const Body sphere =
        makeSphere(0.2, Vec3(0.4, 0.5 + 0.18, 0.1), Quat(Eigen::AngleAxisd(1.1, Vec3::UnitZ())));
    for (const bool sphereFirst : {true, false}) {
        const Body& b0 = sphereFirst ? sphere : plane;
        const Body& b1 = sphereFirst ? plane : sphere;
        const std::vector<Contact> contacts = fastContacts(b0, b1);
        ASSERT_EQ(contacts.size(), 1u);
        EXPECT_NEAR(depthOf(contacts[0], b0, b1), 0.02, 1e-14);
        EXPECT_NEAR(contacts[0].normal.y(), sphereFirst ? 1.0 : -1.0, 1e-15);
    }
}

TEST(ContactSpheres, SphereBoxDepthIsRadiusMinusHeightAboveTheFaceInEitherOrder) {
    // A turned 1 x 1 x 1 box; a sphere of radius 0.2 whose centre is 0.15 above its +y face.
    const Quat turn(Eigen::AngleAxisd(0.4, Vec3(1, 0, 1).normalized()));
    const Body box = makeBody({.shape = boxShape(Vec3::Ones()),
                               .type = BodyType::Static,
                               .position = Vec3(0.3, 0.5, -0.1),
                               .orientation = turn});
    const Body sphere = makeSphere(0.2, box.x + turn * Vec3(0.1, 0.5 + 0.15, -0.2),
                                   Quat(Eigen::AngleAxisd(1.1, Vec3::UnitZ())));
    for (const bool sphereFirst : {true, false}) {
        const Body& b0 = sphereFirst ? sphere : box;
        const Body& b1 = sphereFirst ? box : sphere;
        const std::vector<Contact> contacts = fastContacts(b0, b1);
        ASSERT_EQ(contacts.size(), 1u);
        EXPECT_NEAR(depthOf(contacts[0], b0, b1), 0.05, 1e-14);
        const Vec3 up = turn * Vec3::UnitY();  // from the box towards the sphere
        EXPECT_NEAR((contacts[0].normal - (sphereFirst ? up : Vec3(-up))).norm(), 0.0, 1e-15);
    }
}

TEST(ContactSpheres, GapsBeyondTheMarginGiveNoPoint) {
    const Body b0 = makeSphere(0.1, Vec3(0, 0, 0), Quat::Identity());
    const Body near = makeSphere(0.1, Vec3(0.2 + 0.9 * kMargin, 0, 0), Quat::Identity());
    const Body far = makeSphere(0.1, Vec3(0.2 + 1.1 * kMargin, 0, 0), Quat::Identity());
    EXPECT_EQ(fastContacts(b0, near).size(), 1u);
    EXPECT_EQ(fastContacts(b0, far).size(), 0u);
    const Body plane = makePlane(Vec3::UnitY(), 0.0);
    EXPECT_EQ(
        fastContacts(makeSphere(0.1, Vec3(0, 0.1 + 0.9 * kMargin, 0), Quat::Identity()), plane)
            .size(),
        1u);
    EXPECT_EQ(
        fastContacts(makeSphere(0.1, Vec3(0, 0.1 + 1.1 * kMargin, 0), Quat::Identity()), plane)
            .size(),
        0u);
}

TEST(ContactSpheres, OtherPairsAreLeftToTheGeneralNarrowphase) {
    const Body sphere = makeSphere(0.1, Vec3::Zero(), Quat::Identity());
    const Body capsule = makeBody({.shape = capsuleShape(0.1, 0.4), .mass = 1.0});
    std::vector<Contact> out;
    EXPECT_EQ(
        appendSpherePairContacts(sphere, poseOf(sphere), capsule, poseOf(capsule), kMargin, out),
        -1);
    EXPECT_EQ(
        appendSpherePairContacts(capsule, poseOf(capsule), sphere, poseOf(sphere), kMargin, out),
        -1);
    EXPECT_TRUE(out.empty());
}

TEST(ContactSpheres, BodyFramesAreEigensConjugateRotationBitForBit) {
    // The frame change both paths store (appendContactInBodyFrames, two lanes side by side)
    // against Eigen's q⁻¹ (p − x) one point at a time, for any bodies, points and feature ids.
    std::mt19937_64 rng(35);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 2000; ++trial) {
        Body b0 = makeSphere(0.1, Vec3(unit(rng), unit(rng), unit(rng)) * 50, randomRotation(rng));
        Body b1 = makeBody({.shape = boxShape(Vec3(0.3, 0.2, 0.1)),
                            .mass = 2.0,
                            .position = Vec3(unit(rng), unit(rng), unit(rng)) * 50,
                            .orientation = randomRotation(rng)});
        const Vec3 point0 = b0.x + Vec3(unit(rng), unit(rng), unit(rng));
        const Vec3 point1 = b1.x + Vec3(unit(rng), unit(rng), unit(rng)) * 1e-3;
        const Vec3 normal = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
        std::vector<Contact> out;
        appendContactInBodyFrames(b0, b1, point0, point1, normal, out,
                                  static_cast<uint32_t>(trial));
        ASSERT_EQ(out.size(), 1u);
        expectSameBits(out[0].local0, b0.q.conjugate() * (point0 - b0.x));
        expectSameBits(out[0].local1, b1.q.conjugate() * (point1 - b1.x));
        expectSameBits(out[0].normal, normal);
        EXPECT_EQ(out[0].feature, static_cast<uint32_t>(trial));
    }
}

TEST(ContactSpheres, RandomPairsMatchTheGeneralPathBitForBit) {
    std::mt19937_64 rng(18);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> radius(0.01, 2.0);
    int touching = 0;
    int boxTouching = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const double r0 = radius(rng);
        const double r1 = radius(rng);
        const Vec3 c0(unit(rng) * 10, unit(rng) * 10, unit(rng) * 10);
        // Centres from overlapping deeply to just beyond the margin.
        const Vec3 direction = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
        const double distance =
            (r0 + r1) * (0.2 + 0.81 * std::abs(unit(rng))) + kMargin * unit(rng);
        const Body b0 = makeSphere(r0, c0, randomRotation(rng));
        const Body b1 = makeSphere(r1, c0 + distance * direction, randomRotation(rng));
        expectSameContacts(b0, b1);
        expectSameContacts(b1, b0);
        // Planes of any tilt, scaled normals, both orders.
        const Vec3 normal = Vec3(unit(rng), unit(rng), unit(rng)) * (0.5 + std::abs(unit(rng)));
        const double offset =
            normal.norm() * (normal.normalized().dot(c0) - r0 * (0.5 + unit(rng)));
        const Body plane = makePlane(normal, offset);
        expectSameContacts(b0, plane);
        expectSameContacts(plane, b0);
        // Boxes of any pose and size (a pile's walls), the centre outside, on the surface or
        // inside, both orders.
        const Vec3 size(0.1 + 3 * std::abs(unit(rng)), 0.1 + 3 * std::abs(unit(rng)),
                        0.1 + 3 * std::abs(unit(rng)));
        const Quat boxRotation = randomRotation(rng);
        const Vec3 local =
            size.cwiseProduct(Vec3(unit(rng), unit(rng), unit(rng))) * 0.5 *
            (trial % 3 == 0 ? 0.9 : 1.0 + r0 / size.minCoeff() * std::abs(unit(rng)));
        const Body box = makeBody({.shape = boxShape(size),
                                   .type = BodyType::Static,
                                   .position = c0 - boxRotation * local,
                                   .orientation = boxRotation});
        expectSameContacts(b0, box);
        expectSameContacts(box, b0);
        touching += static_cast<int>(fastContacts(b0, b1).size() + fastContacts(b0, plane).size());
        boxTouching += static_cast<int>(fastContacts(b0, box).size());
    }
    EXPECT_GT(boxTouching, 500);
    EXPECT_GT(touching, 1000);  // the trials reach both sides of the margin
    // Degenerate cases: coincident centres (+y), a zero plane normal (+y).
    const Body a = makeSphere(0.3, Vec3(1, 2, 3), Quat::Identity());
    const Body b = makeSphere(0.2, Vec3(1, 2, 3), randomRotation(rng));
    expectSameContacts(a, b);
    const Body flat = makePlane(Vec3::Zero(), 1.5);
    expectSameContacts(a, flat);
    expectSameContacts(flat, a);
    // A box centred on the sphere's centre (ties between faces: the first axis), and on a face.
    const Body cube = makeBody({.shape = boxShape(Vec3::Constant(1.0)),
                                .type = BodyType::Static,
                                .position = Vec3(1, 2, 3)});
    expectSameContacts(a, cube);
    expectSameContacts(cube, a);
    const Body onFace = makeBody({.shape = boxShape(Vec3::Constant(1.0)),
                                  .type = BodyType::Static,
                                  .position = Vec3(1, 2.5, 3)});
    expectSameContacts(a, onFace);
    expectSameContacts(onFace, a);
}

}  // namespace
}  // namespace substep

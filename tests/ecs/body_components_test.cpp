// Tests engine/ecs/body_components.cpp: a BodyDef split into Transform, RigidBody and Collider
// and put back together is the same definition, field for field.

#include "ecs/body_components.h"
#include "ecs/registry.h"

#include <gtest/gtest.h>

namespace substep::ecs {
namespace {

BodyDef everyFieldSet() {
    return {
        .shape = capsuleShape(0.1, 0.5),
        .type = BodyType::Dynamic,
        .mass = 2.5,
        .density = 700.0,
        .position = Vec3(1, 2, 3),
        .orientation = Quat(0.5, 0.5, -0.5, 0.5),
        .velocity = Vec3(-1, 0.25, 4),
        .angularVelocity = Vec3(0.1, 0.2, 0.3),
        .staticFriction = 0.9,
        .dynamicFriction = 0.6,
        .restitution = 0.4,
        .collide = false,
    };
}

void expectSameDef(const BodyDef& a, const BodyDef& b) {
    EXPECT_EQ(a.shape.type, b.shape.type);
    EXPECT_EQ(a.shape.radius, b.shape.radius);
    EXPECT_EQ(a.shape.length, b.shape.length);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.mass, b.mass);
    EXPECT_EQ(a.density, b.density);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
    EXPECT_EQ(a.velocity, b.velocity);
    EXPECT_EQ(a.angularVelocity, b.angularVelocity);
    EXPECT_EQ(a.staticFriction, b.staticFriction);
    EXPECT_EQ(a.dynamicFriction, b.dynamicFriction);
    EXPECT_EQ(a.restitution, b.restitution);
    EXPECT_EQ(a.collide, b.collide);
}

TEST(BodyComponents, RoundTripKeepsEveryField) {
    const BodyDef def = everyFieldSet();
    const BodyComponents c = toBodyComponents(def);
    EXPECT_TRUE(c.rigidBody.id.isNull());
    expectSameDef(toBodyDef(c.transform, c.rigidBody, &c.collider), def);
}

TEST(BodyComponents, EmplaceBodyGivesTheEntityTheThreeComponents) {
    Registry registry;
    const Entity e = registry.create();
    const BodyDef def = everyFieldSet();
    emplaceBody(registry, e, def);
    expectSameDef(toBodyDef(registry.get<Transform>(e), registry.get<RigidBody>(e),
                            registry.tryGet<Collider>(e)),
                  def);
}

TEST(BodyComponents, WithoutAColliderTheBodyHasNoShapeAndCollidesWithNothing) {
    const BodyDef def = toBodyDef({.position = Vec3(0, 1, 0)}, {.mass = 1.0}, nullptr);
    EXPECT_EQ(def.shape.type, ShapeType::None);
    EXPECT_FALSE(def.collide);
    EXPECT_EQ(def.mass, 1.0);
    EXPECT_EQ(def.position, Vec3(0, 1, 0));
}

}  // namespace
}  // namespace substep::ecs

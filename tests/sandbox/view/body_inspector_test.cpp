// sandbox/view/body_inspector.cpp (through view_session.cpp's select): a click's ray selects the
// body it meets first, and the inspector reads it from the components: hinge_bar's 1 kg, 0.4 m
// bar held level by its hinge shows its mass and the hinge's torque m g L / 2 = 2 N m; a ray
// through nothing clears the selection; a restart forgets it.

#include "scene_source.h"
#include "view/body_inspector.h"
#include "view/view_session.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

namespace substep::view {
namespace {

/// The ray from the scene's start camera through `point`.
Ray rayTo(const ViewSession& session, const Vec3& point) {
    const Vec3 eye = session.startCamera().position.cast<double>();
    return {eye, (point - eye).normalized()};
}

Vec3 bodyPosition(const ViewSession& session, const char* name) {
    const ecs::Registry& registry = session.instance().registry;
    for (const ecs::Entity entity : session.instance().bodyEntities) {
        const ecs::Name* entityName = registry.tryGet<ecs::Name>(entity);
        if (entityName != nullptr && entityName->value == name) return registry.get<ecs::Transform>(entity).position;
    }
    ADD_FAILURE() << "no body " << name;
    return Vec3::Zero();
}

TEST(BodyInspectorTest, AClickSelectsTheBarAndShowsItsMassAndTheHingeTorque) {
    ViewSession session(resolveScene("hinge_bar"), 16.0f / 9.0f);
    for (int frame = 0; frame < 60; ++frame) session.stepOnce();  // 1 s: held level
    EXPECT_FALSE(session.inspection());
    ASSERT_TRUE(session.select(rayTo(session, bodyPosition(session, "bar"))));
    const std::optional<BodyInspection> bar = session.inspection();
    ASSERT_TRUE(bar);
    EXPECT_EQ(bar->name, "bar");
    EXPECT_FALSE(bar->isStatic);
    EXPECT_NEAR(bar->mass, 1.0, 1e-9);
    EXPECT_LT(bar->velocity.norm(), 1e-3);  // at rest, held
    ASSERT_EQ(bar->joints.size(), 1u);
    EXPECT_EQ(bar->joints[0].name, "hinge");
    EXPECT_NEAR(bar->joints[0].torque, 1.0 * 10.0 * 0.4 / 2.0, 0.02);  // m g L / 2
    EXPECT_NEAR(bar->joints[0].force, 1.0 * 10.0, 0.1);                // carries the weight

    // The outline: the twelve edges of the bar's box, around its position.
    const render::RenderScene drawn = session.draw(session.startCamera());
    std::size_t yellow = 0;
    for (const render::DebugLine& line : drawn.lines)
        if (line.colour.isApprox(render::Colour(1.0f, 0.85f, 0.1f))) ++yellow;
    EXPECT_EQ(yellow, 12u);

    // The static mount selects as static; a ray into the sky clears the selection.
    ASSERT_TRUE(session.select(rayTo(session, bodyPosition(session, "mount"))));
    EXPECT_EQ(session.inspection()->name, "mount");
    EXPECT_TRUE(session.inspection()->isStatic);
    const Vec3 eye = session.startCamera().position.cast<double>();
    EXPECT_FALSE(session.select({eye, Vec3(0.0, 1.0, 0.0)}));
    EXPECT_FALSE(session.inspection());

    ASSERT_TRUE(session.select(rayTo(session, bodyPosition(session, "bar"))));
    session.restart();
    EXPECT_FALSE(session.inspection());
}

TEST(BodyInspectorTest, TheNearestBodyAlongTheRayIsPicked) {
    // cradle: three marbles in a row along x; a ray along the row from its far end meets the
    // nearest first.
    ViewSession session(resolveScene("cradle"), 16.0f / 9.0f);
    ecs::Registry& registry = const_cast<ecs::Registry&>(session.instance().registry);
    std::vector<std::pair<double, ecs::Entity>> marbles;
    for (const ecs::Entity entity : session.instance().bodyEntities) {
        const ecs::RigidBody& body = registry.get<ecs::RigidBody>(entity);
        if (body.simulatedMass > 0.0) marbles.emplace_back(registry.get<ecs::Transform>(entity).position.x(), entity);
    }
    ASSERT_GE(marbles.size(), 3u);
    std::sort(marbles.begin(), marbles.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const Vec3 first = registry.get<ecs::Transform>(marbles.front().second).position;
    const std::optional<BodyHit> fromLeft = pickBody(registry, {first - Vec3(5.0, 0.0, 0.0), Vec3::UnitX()});
    ASSERT_TRUE(fromLeft);
    EXPECT_EQ(fromLeft->entity, marbles.front().second);
    const std::optional<BodyHit> fromRight = pickBody(registry, {first + Vec3(50.0, 0.0, 0.0), -Vec3::UnitX()});
    ASSERT_TRUE(fromRight);
    EXPECT_EQ(fromRight->entity, marbles.back().second);
}

}  // namespace
}  // namespace substep::view

// sandbox/view/joint_inspector.cpp (through view_session.cpp's select and jointInspection): a
// mass hanging at rest from a ceiling shows its joint's force m g (Eq. 10) within 1 % for every
// joint type that can hold it and masses from 0.2 to 40 kg, no torque, no error; a hinge's angle
// sits 0.4 of the way through limits [-1, 1.5] rad; a click near the joint's anchor selects it
// (and one far from every anchor selects no joint), the view highlights it; a drive's target and
// reach are read from the world.

#include "view/joint_inspector.h"
#include "scene_source.h"
#include "scenes/scenes.h"
#include "view/view_session.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

#include <tuple>

namespace substep::view {
namespace {

constexpr double kGravity = 10.0;

/// A box of `mass` hanging 1 m under a static ceiling by a joint of `type` named "holder".
SceneSource hangingMass(JointType type, double mass) {
    SceneDescription scene{
        .name = "hanging", .gravity = Vec3(0.0, -kGravity, 0.0), .substeps = 20, .iterations = 1};
    scenes::addStaticBox(scene, "ceiling", Vec3(0.4, 0.1, 0.4), Vec3(0.0, 2.0, 0.0));
    scenes::addBox(scene, "weight", Vec3(0.2, 0.2, 0.2), mass, Vec3(0.0, 0.9, 0.0));
    // The ceiling's anchor is at y = 1.95: the weight's is there too (a massless arm 1.05 m
    // long), or for the rope on its top face, 0.95 m below.
    JointDef def{.type = type, .anchor0 = Vec3(0.0, -0.05, 0.0), .anchor1 = Vec3(0.0, 1.05, 0.0)};
    if (type == JointType::Hinge) {
        def.axis0 = def.axis1 = Vec3::UnitZ();
        def.limits = Range{-1.0, 1.5};
    }
    if (type == JointType::Distance) {
        def.anchor1 = Vec3(0.0, 0.1, 0.0);
        def.maxDistance = 1.95 - 1.0;  // a rope, taut
    }
    scenes::addJoint(scene, "holder", "ceiling", "weight", def);
    scene.camera = SceneCamera{.position = Vec3(0.0, 1.5, 3.0), .target = Vec3(0.0, 1.5, 0.0)};
    return SceneSource{.description = std::move(scene), .label = "hanging"};
}

Ray rayTo(const ViewSession& session, const Vec3& point) {
    const Vec3 eye = session.startCamera().position.cast<double>();
    return {eye, (point - eye).normalized()};
}

class HangingMass : public testing::TestWithParam<std::tuple<JointType, double>> {};

TEST_P(HangingMass, TheJointShowsTheWeightItCarries) {
    const auto [type, mass] = GetParam();
    ViewSession session(hangingMass(type, mass), 16.0f / 9.0f);
    for (int frame = 0; frame < 60; ++frame)
        session.stepOnce();
    EXPECT_FALSE(session.jointInspection());
    // A click 5 pixels beside the ceiling's anchor (0, 1.95, 0), the view 800 pixels high.
    const double radiansPerPixel = session.startCamera().fovY / 800.0;
    const Vec3 eye = session.startCamera().position.cast<double>();
    const Vec3 anchor(0.0, 1.95, 0.0);
    const Vec3 beside = anchor + 5.0 * radiansPerPixel * (anchor - eye).norm() * Vec3::UnitX();
    ASSERT_TRUE(session.select(rayTo(session, beside), radiansPerPixel));
    const std::optional<JointDetails> joint = session.jointInspection();
    ASSERT_TRUE(joint);
    EXPECT_FALSE(session.inspection()) << "a joint selected, no body";
    EXPECT_EQ(joint->name, "holder");
    EXPECT_EQ(joint->body0, "ceiling");
    EXPECT_EQ(joint->body1, "weight");
    EXPECT_NEAR(joint->force, mass * kGravity, 0.01 * mass * kGravity);  // Eq. 10 at rest: m g
    EXPECT_LT(joint->torque, 1e-3 * mass * kGravity);                    // straight under: no lever
    EXPECT_LT(joint->error, 1e-4);
    EXPECT_LT(joint->angleError, 1e-4);
    EXPECT_NEAR(joint->anchor0.y(), 1.95, 1e-12);
    if (type == JointType::Hinge) {
        EXPECT_EQ(joint->type, "hinge");
        ASSERT_TRUE(joint->limits);
        ASSERT_TRUE(joint->withinLimits());
        EXPECT_NEAR(*joint->withinLimits(), (0.0 - -1.0) / (1.5 - -1.0), 1e-3);
        EXPECT_FALSE(joint->hasDrive);
    }

    // The highlight: a cross at each anchor and a line from each body's centre to its anchor.
    const render::RenderScene drawn = session.draw(session.startCamera());
    std::size_t yellow = 0;
    for (const render::DebugLine& line : drawn.lines)
        if (line.colour.isApprox(render::Colour(1.0f, 0.85f, 0.1f))) ++yellow;
    EXPECT_EQ(yellow, 8u);

    // Far from every anchor (the middle of the weight's face), a click selects the body.
    ASSERT_TRUE(session.select(rayTo(session, Vec3(0.0, 0.9, 0.1)), radiansPerPixel));
    EXPECT_FALSE(session.jointInspection());
    ASSERT_TRUE(session.inspection());
    EXPECT_EQ(session.inspection()->name, "weight");
}

INSTANTIATE_TEST_SUITE_P(TypesAndMasses, HangingMass,
                         testing::Combine(testing::Values(JointType::Spherical, JointType::Hinge,
                                                          JointType::Distance, JointType::Fixed),
                                          testing::Values(0.2, 3.0, 40.0)));

TEST(JointInspectorTest, ADriveShowsItsTargetAndHowFarTheJointIsFromIt) {
    // hinge_bar: a hard drive to 0 holds the 1 kg, 0.4 m bar level against m g L / 2 = 2 N m.
    ViewSession session(resolveScene("hinge_bar"), 16.0f / 9.0f);
    for (int frame = 0; frame < 60; ++frame)
        session.stepOnce();
    ASSERT_EQ(session.instance().jointEntities.size(), 1u);
    session.selectJoint(session.instance().jointEntities[0]);
    const std::optional<JointDetails> hinge = session.jointInspection();
    ASSERT_TRUE(hinge);
    EXPECT_EQ(hinge->body0, "the world");
    EXPECT_EQ(hinge->body1, "bar");
    EXPECT_TRUE(hinge->hasDrive);
    EXPECT_EQ(hinge->target, 0.0);
    EXPECT_LT(std::abs(hinge->reach), 1e-3);
    EXPECT_NEAR(hinge->torque, 1.0 * 10.0 * 0.4 / 2.0, 0.02);
    EXPECT_NEAR(hinge->force, 10.0, 0.1);
    EXPECT_FALSE(hinge->limits);
    session.restart();
    EXPECT_FALSE(session.jointInspection()) << "a restart forgets the selection";
}

}  // namespace
}  // namespace substep::view

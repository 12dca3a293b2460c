// Tests sandbox/scenes/scene_script.{h,cpp} and live_scene.{h,cpp}: knobs clamp and apply, the
// frame hook sees the right times, a restart keeps the knobs and starts the new world from them.

#include "scenes/live_scene.h"
#include "scenes/scenes.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace substep {
namespace {

/// A box on a spring whose compliance is a knob; records what the LiveScene calls.
class ProbeScript : public SceneScript {
  public:
    ProbeScript() {
        compliance_ = addKnob({.name = "compliance", .label = "spring compliance", .min = 0.0, .max = 0.1});
        pass_ = addKnob({.name = "velocity_pass", .label = "velocity pass", .kind = SceneKnob::Kind::Toggle, .value = 1.0});
        split_ = addKnob({.name = "split", .label = "solver", .kind = SceneKnob::Kind::Choice,
                          .choices = {"20 x 1", "1 x 20"}});
    }
    void start(SceneInstance& scene) override {
        ++starts;
        setCompliance(scene);
    }
    void setCompliance(SceneInstance& scene) const {
        scene.registry.patch<ecs::Joint>(scene.jointEntities.front(),
                                         [&](ecs::Joint& spring) { spring.def.compliance = knob(compliance_); });
    }
    void beforeFrame(SceneInstance&, double time, double dt) override {
        times.push_back(time);
        lastDt = dt;
    }
    void knobChanged(SceneInstance& scene, std::size_t index) override {
        changed.push_back(index);
        WorldSettings settings = scene.world().settings();
        if (index == compliance_) setCompliance(scene);
        if (index == pass_) settings.velocityPass = toggled(pass_);
        if (index == split_) {
            settings.substeps = knob(split_) == 0.0 ? 20 : 1;
            settings.iterations = knob(split_) == 0.0 ? 1 : 20;
        }
        scene.physics().setSettings(settings);
    }

    int starts = 0;
    std::vector<double> times;
    double lastDt = 0.0;
    std::vector<std::size_t> changed;

  private:
    std::size_t compliance_ = 0, pass_ = 0, split_ = 0;
};

ProbeScript* gLastProbe = nullptr;

SceneEntry probeEntry() {
    return {.name = "probe",
            .description = "a box on a spring",
            .build = [] {
                SceneDescription scene{.name = "probe", .gravity = scenes::kPaperGravity};
                scenes::addBox(scene, "box", Vec3::Constant(0.2), 1.0, Vec3(0.0, 1.0, 0.0));
                scenes::addJoint(scene, "spring", "", "box",
                                 JointDef{.type = JointType::Distance, .anchor0 = Vec3(0.0, 2.0, 0.0),
                                          .anchor1 = Vec3(0.0, 0.1, 0.0)});
                return scene;
            },
            .makeScript = []() -> std::unique_ptr<SceneScript> {
                auto script = std::make_unique<ProbeScript>();
                gLastProbe = script.get();
                return script;
            }};
}

TEST(SceneScript, SetKnobClampsToTheKindAndApplies) {
    const SceneEntry entry = probeEntry();
    LiveScene scene(entry.build(), &entry);
    SceneScript& script = *scene.script();
    const JointId spring = scene.instance().namedJointIds().front().second;

    EXPECT_TRUE(scene.setKnob("compliance", 5.0));  // above its range
    EXPECT_DOUBLE_EQ(script.findKnob("compliance")->value, 0.1);
    EXPECT_DOUBLE_EQ(scene.world().joint(spring).compliance, 0.1);

    EXPECT_TRUE(script.setKnob(scene.instance(), "velocity_pass", 0.3));  // any non-zero is on
    EXPECT_DOUBLE_EQ(script.findKnob("velocity_pass")->value, 1.0);
    EXPECT_TRUE(script.setKnob(scene.instance(), "velocity_pass", 0.0));
    EXPECT_FALSE(scene.world().settings().velocityPass);

    EXPECT_TRUE(script.setKnob(scene.instance(), "split", 7.0));  // the last choice
    EXPECT_DOUBLE_EQ(script.findKnob("split")->value, 1.0);
    EXPECT_EQ(scene.world().settings().substeps, 1);
    EXPECT_EQ(scene.world().settings().iterations, 20);

    EXPECT_FALSE(script.setKnob(scene.instance(), "no_such_knob", 1.0));
    EXPECT_FALSE(scene.setKnob("compliance", std::nan("")));
    EXPECT_EQ(gLastProbe->changed.size(), 4u);  // the refused ones applied nothing
}

TEST(LiveScene, StepsCallTheFrameHookWithFrameTimes) {
    const SceneEntry entry = probeEntry();
    LiveScene scene(entry.build(), &entry);
    const double dt = scene.description().dt;
    for (int frame = 0; frame < 3; ++frame) scene.step();
    ASSERT_EQ(gLastProbe->times.size(), 3u);
    EXPECT_EQ(gLastProbe->times[0], 0.0);
    EXPECT_EQ(gLastProbe->times[2], 2.0 * dt);
    EXPECT_EQ(gLastProbe->lastDt, dt);
    EXPECT_EQ(scene.frame(), 3);
    EXPECT_EQ(scene.time(), 3.0 * dt);
}

TEST(LiveScene, RestartKeepsTheKnobsAndStartsTheNewWorldFromThem) {
    const SceneEntry entry = probeEntry();
    LiveScene scene(entry.build(), &entry);
    ProbeScript* probe = gLastProbe;
    scene.setKnob("compliance", 0.01);
    for (int frame = 0; frame < 10; ++frame) scene.step();
    scene.restart();
    EXPECT_EQ(scene.frame(), 0);
    EXPECT_EQ(probe->starts, 2);
    EXPECT_EQ(gLastProbe, probe) << "a restart keeps the script";
    const JointId spring = scene.instance().namedJointIds().front().second;
    EXPECT_DOUBLE_EQ(scene.world().joint(spring).compliance, 0.01);
}

TEST(LiveScene, SceneWithoutScriptStepsPlainly) {
    SceneEntry entry = probeEntry();
    entry.makeScript = nullptr;
    LiveScene scene(entry.build(), &entry);
    EXPECT_EQ(scene.script(), nullptr);
    scene.step();
    EXPECT_EQ(scene.frame(), 1);
    LiveScene file(entry.build(), nullptr);  // a scene file has no entry
    EXPECT_EQ(file.script(), nullptr);
}

}  // namespace
}  // namespace substep

// sandbox/view (`substep view`): the program run end to end. Without a display it must say so
// and exit 2; under Xvfb (xvfb-run) its scripted form opens the real window, runs frames and
// saves the window as a PNG, which is decoded and checked for the window's size and for a drawn
// scene and panel, and in compare mode for two runs side by side. The window-free parts (orbit
// camera, sessions, compare session, body dragger) run in process.

#include "command_test_support.h"

#include "render/png_codec.h"
#include "scene_source.h"
#include "scenes/scenes.h"
#include "view/compare_session.h"
#include "view/orbit_camera.h"
#include "view/scene_file_watch.h"
#include "view/view_session.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <set>

namespace substep::command_test {
namespace {

constexpr const char* kNoDisplay =
    "substep: no display ($DISPLAY is unset); use `substep render SCENE --frames LIST --out DIR` to render "
    "PNGs headless";

bool haveXvfbRun() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

using ViewCommandTest = CommandTest;

TEST_F(ViewCommandTest, WithoutDisplaySaysSoAndExits2) {
    const Result result = substep("view boxes3", "env -u DISPLAY");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find(kNoDisplay), std::string::npos) << result.err;
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(ViewCommandTest, NoCommandMeansTheViewer) {
    const Result result = substep("", "env -u DISPLAY");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find(kNoDisplay), std::string::npos) << result.err;
}

TEST_F(ViewCommandTest, BadInputIsReportedBeforeAnyWindow) {
    Result result = substep("view no_such_scene", "env -u DISPLAY");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("no_such_scene"), std::string::npos) << result.err;

    result = substep("view boxes3 --screenshot out.png", "env -u DISPLAY");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("--screenshot"), std::string::npos) << result.err;

    result = substep("view boxes3 --frames 0", "env -u DISPLAY");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(ViewCommandTest, ScriptedRunUnderXvfbSavesTheWindow) {
    if (!haveXvfbRun()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    const Result result = substep("view boxes3 --frames 30 --size 800x600 --screenshot shot.png", "xvfb-run -a");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("saved shot.png after 30 frames of boxes3"), std::string::npos) << result.out;
    EXPECT_EQ(workEntries(), std::vector<std::string>{"shot.png"});  // no imgui.ini, no temporaries

    const render::Image image = render::decodePng(readFile(work() / "shot.png"));
    ASSERT_EQ(image.width, 800);
    ASSERT_EQ(image.height, 600);

    // A drawn scene has shading, sky and grid: many colours, not one clear colour.
    std::set<uint32_t> colours;
    for (int y = 0; y < image.height; y += 3) {
        for (int x = 0; x < image.width; x += 3) {
            const uint8_t* p = image.pixel(x, y);
            colours.insert(uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]);
        }
    }
    EXPECT_GT(colours.size(), 200u);

    // The panel is docked at the left beside the scene: ImGui's dark window is darker there than
    // the sky at the top right.
    auto meanBrightness = [&](int x0, int y0, int x1, int y1) {
        double sum = 0.0;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const uint8_t* p = image.pixel(x, y);
                sum += (p[0] + p[1] + p[2]) / 3.0;
            }
        }
        return sum / ((x1 - x0) * (y1 - y0));
    };
    EXPECT_LT(meanBrightness(20, 40, 300, 120), 0.6 * meanBrightness(500, 5, 790, 60));
}

TEST(OrbitCameraTest, StartsAtTheGivenCameraAndKeepsItsTarget) {
    render::Camera start;
    start.position = render::Vec3f(3.0f, 2.0f, 5.0f);
    start.target = render::Vec3f(0.5f, 1.0f, -1.0f);
    view::OrbitCamera camera(start);
    EXPECT_LT((camera.camera().position - start.position).norm(), 1e-4f);
    EXPECT_LT((camera.camera().target - start.target).norm(), 1e-6f);

    const float distance = (start.position - start.target).norm();
    camera.orbit(120.0f, -40.0f);
    EXPECT_LT((camera.camera().target - start.target).norm(), 1e-6f);
    EXPECT_NEAR((camera.camera().position - camera.camera().target).norm(), distance, 1e-4f);

    camera.zoom(2.0f);  // in: closer by 0.9 a step
    EXPECT_NEAR((camera.camera().position - camera.camera().target).norm(), distance * 0.81f, 1e-4f);

    camera.pan(100.0f, 0.0f, 720.0f);  // sideways only: the target stays at its height
    EXPECT_GT((camera.camera().target - start.target).norm(), 1e-3f);
    EXPECT_NEAR(camera.camera().target.y(), start.target.y(), 1e-5f);
}

TEST(OrbitCameraTest, PitchStopsShortOfStraightDown) {
    view::OrbitCamera camera(render::Camera{});
    camera.orbit(0.0f, 1e6f);
    const render::Camera view = camera.camera();
    const render::Vec3f direction = (view.target - view.position).normalized();
    EXPECT_LT(std::abs(direction.y()), 0.9999f);
    EXPECT_TRUE(view.position.allFinite());
}

TEST(ViewSessionTest, StepsRestartsAndAppliesControls) {
    view::ViewSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    EXPECT_EQ(session.controls().substeps, session.source().description.substeps);
    EXPECT_EQ(session.energyHistory().count(), 1u);  // the initial state
    EXPECT_EQ(session.chainElongationHistory(), nullptr);  // pendulum3 has no chain measure
    session.stepOnce();
    EXPECT_EQ(session.frame(), 1);
    EXPECT_EQ(session.energyHistory().count(), 2u);

    session.controls().substeps = 7;
    session.controls().iterations = 3;
    session.controls().gravityY = -2.0f;
    session.applyControls();
    EXPECT_EQ(session.world().settings().substeps, 7);
    EXPECT_EQ(session.world().settings().iterations, 3);
    EXPECT_DOUBLE_EQ(session.world().settings().gravity.y(), -2.0);

    session.restart();  // the initial state again, with the edited controls kept
    EXPECT_EQ(session.frame(), 0);
    EXPECT_EQ(session.energyHistory().count(), 1u);
    EXPECT_EQ(session.world().settings().substeps, 7);

    session.controls().drawing.contacts = true;
    session.applyDrawingOptions();
    EXPECT_FALSE(session.draw(session.startCamera()).instances.empty());

    session.load(resolveScene("boxes3"));  // a new scene brings its own solver settings
    EXPECT_EQ(session.source().label, "boxes3");
    EXPECT_EQ(session.controls().substeps, session.source().description.substeps);
}

TEST(BodyDraggerTest, PullsTheBodyUnderTheCursorAndLetsGo) {
    view::ViewSession session(resolveScene("boxes3"), 16.0f / 9.0f);
    const World& world = session.world();
    // The lowest dynamic body, aimed at from the side.
    std::size_t target = 0;
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
        const Body& body = world.bodies()[i];
        if (body.alive && body.isDynamic() && (target == 0 || body.x.y() < world.bodies()[target].x.y())) target = i;
    }
    ASSERT_NE(target, 0u);
    const Vec3 start = world.bodies()[target].x;
    const Vec3 eye = start + Vec3(0.0, 0.0, 5.0);

    EXPECT_FALSE(session.grab({eye, Vec3(0.0, 1.0, 0.0)}));  // aimed at nothing
    ASSERT_TRUE(session.grab({eye, Vec3(0.0, 0.0, -1.0)}));
    EXPECT_TRUE(session.dragging());
    const std::size_t joints = world.joints().size();

    // The cursor moves 0.3 m to the right: the body follows on its spring.
    session.drag({eye, (start + Vec3(0.3, 0.0, 0.0) - eye).normalized()});
    for (int frame = 0; frame < 120; ++frame) session.stepOnce();
    EXPECT_GT(world.bodies()[target].x.x() - start.x(), 0.1);
    EXPECT_TRUE(world.isFinite());
    EXPECT_EQ(session.draw(session.startCamera()).lines.empty(), false);

    session.release();
    EXPECT_FALSE(session.dragging());
    EXPECT_EQ(world.joints().size(), joints);  // the slot stays, the joint is gone
    session.restart();                          // a restart while held would forget it too
    EXPECT_FALSE(session.dragging());
}

// The panel's compliance sliders reach the world's joints, and a restart restores the scene's.
TEST(ViewSessionTest, JointComplianceIsEditableLive) {
    view::ViewSession session(resolveScene("boxes3"), 16.0f / 9.0f);
    ASSERT_FALSE(session.namedJoints().empty());
    const ecs::Entity id = session.namedJoints().front().second;
    const JointId worldId = session.instance().registry.get<ecs::Joint>(id).id;
    const double original = session.world().joint(worldId).compliance;
    session.setJointCompliance(id, 0.05);
    EXPECT_EQ(session.world().joint(session.instance().registry.get<ecs::Joint>(id).id).compliance, 0.05);
    session.setJointCompliance(id, -1.0);  // refused: a compliance is never negative
    EXPECT_EQ(session.world().joint(session.instance().registry.get<ecs::Joint>(id).id).compliance, 0.05);
    session.restart();
    EXPECT_EQ(session.world().joint(session.instance().registry.get<ecs::Joint>(session.namedJoints().front().second).id).compliance, original);
}

// A saved scene file is noticed once, a built-in scene (no path) never, and a file that is
// briefly missing (saved by rename) is not taken for a change.
TEST(SceneFileWatchTest, NoticesEachSaveOnce) {
    namespace fs = std::filesystem;
    const fs::path file = fs::temp_directory_path() / "substep_watch_test.json";
    { std::ofstream(file) << "{}"; }
    const auto now = std::chrono::steady_clock::now();
    const auto later = [&](int steps) { return now + steps * view::SceneFileWatch::interval; };
    view::SceneFileWatch watch;
    watch.watch(file.string());
    EXPECT_FALSE(watch.changed(later(1)));
    fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(5));
    EXPECT_FALSE(watch.changed(later(1)));  // asked again within the interval: not looked at
    EXPECT_TRUE(watch.changed(later(2)));
    EXPECT_FALSE(watch.changed(later(3)));  // the same save is reported once
    fs::remove(file);
    EXPECT_FALSE(watch.changed(later(4)));
    { std::ofstream(file) << "{ }"; }
    fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(10));
    EXPECT_TRUE(watch.changed(later(5)));
    fs::remove(file);

    view::SceneFileWatch builtin;
    builtin.watch("");
    EXPECT_FALSE(builtin.changed(later(10)));
}

// Real-time pacing: paused time is not stepped, a fraction of dt is carried, and a frame far
// behind steps a few frames, not all it owes.
TEST(CompareSessionTest, PacesTheRunsInRealTime) {
    view::CompareSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    ASSERT_EQ(session.runCount(), 1u);
    const double dt = session.source().description.dt;
    session.playback().playing = false;
    session.advance(1.0);  // paused: real time passes, the world does not
    EXPECT_EQ(session.first().frame(), 0);
    session.stepOnce();
    EXPECT_EQ(session.first().frame(), 1);

    session.playback().playing = true;
    session.advance(dt * 2.5);
    EXPECT_EQ(session.first().frame(), 3);
    session.advance(dt * 0.6);  // with the 0.5 dt carried: one more
    EXPECT_EQ(session.first().frame(), 4);
    session.advance(10.0);  // far behind: a few frames, not 600
    EXPECT_LE(session.first().frame(), 4 + 4);
    session.playback().timeScale = 0.5f;
    const long long before = session.first().frame();
    session.advance(dt * 1.9);  // half speed: 0.95 dt of scene time, not a frame yet
    EXPECT_EQ(session.first().frame(), before);
}

TEST(CompareSessionTest, ReadsSplits) {
    const std::optional<view::CompareSplits> paper = view::parseCompareSplits("20x1,1x20");
    ASSERT_TRUE(paper.has_value());
    EXPECT_EQ(*paper, view::kPaperCompareSplits);
    const std::optional<view::CompareSplits> other = view::parseCompareSplits("5x4,2x10");
    ASSERT_TRUE(other.has_value());
    EXPECT_EQ((*other)[0], (view::SolverSplit{5, 4}));
    EXPECT_EQ((*other)[1], (view::SolverSplit{2, 10}));
    for (const char* bad : {"", "20x1", "20x1,", "0x1,1x1", "1x0,1x1", "ax1,1x1", "20x1,1x20,3x3", "20x1,1x",
                            "1001x1,1x1", " 20x1,1x20", "20X1,1x20", "-1x1,1x1", "20x1;1x20",
                            "20x1:,1x20", "20x1:Start,1x20", "20x1:start:paper,1x20", ":start,1x20"}) {
        EXPECT_FALSE(view::parseCompareSplits(bad).has_value()) << bad;
    }
}

// "20x1:paper,20x1:start": the paper's joint projection against the start-direction one, side by
// side (issue 17); the projection reaches each run's world.
TEST(CompareSessionTest, ComparesJointProjections) {
    const std::optional<view::CompareSplits> splits = view::parseCompareSplits("20x1:paper,20x1:start");
    ASSERT_TRUE(splits.has_value());
    EXPECT_EQ((*splits)[0], (view::SolverSplit{20, 1, JointProjection::Paper}));
    EXPECT_EQ((*splits)[1], (view::SolverSplit{20, 1, JointProjection::Start}));
    view::CompareSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    session.compare(*splits);
    EXPECT_EQ(session.run(0).world().settings().jointProjection, JointProjection::Paper);
    EXPECT_EQ(session.run(1).world().settings().jointProjection, JointProjection::Start);
}

// The paper's Fig. 10 comparison on its chain (Fig. 11, PEERS chain100): both runs step in
// lockstep from one source with their own split, and the 20 x 1 run keeps the chain's length far
// better than the 1 x 20 run, as the paper reports.
TEST(CompareSessionTest, RunsTwoSplitsOfOneSceneInLockstep) {
    view::CompareSession session(resolveScene("chain100"), 16.0f / 9.0f);
    session.compare(view::kPaperCompareSplits);
    ASSERT_TRUE(session.comparing());
    ASSERT_EQ(session.runCount(), 2u);
    EXPECT_EQ(session.run(0).world().settings().substeps, 20);
    EXPECT_EQ(session.run(0).world().settings().iterations, 1);
    EXPECT_EQ(session.run(1).world().settings().substeps, 1);
    EXPECT_EQ(session.run(1).world().settings().iterations, 20);

    const double dt = session.source().description.dt;
    for (int frame = 0; frame < 30; ++frame) session.advance(dt);
    EXPECT_GT(session.run(0).frame(), 20);
    EXPECT_EQ(session.run(0).frame(), session.run(1).frame());
    ASSERT_NE(session.run(0).chainElongationHistory(), nullptr);
    ASSERT_NE(session.run(1).chainElongationHistory(), nullptr);
    const double left = session.run(0).chainElongationHistory()->latest();
    const double right = session.run(1).chainElongationHistory()->latest();
    EXPECT_GT(left, 0.0);  // a hanging chain stretches under its weight, a little
    EXPECT_GT(right, 10.0 * left) << "20x1 " << left << ", 1x20 " << right;
    EXPECT_GT(session.run(1).jointErrorHistory().latest(), session.run(0).jointErrorHistory().latest());

    // Each run's split is its own; gravity is shared.
    session.run(1).controls().substeps = 4;
    session.first().controls().gravityY = -3.0f;
    session.applyControls();
    EXPECT_EQ(session.run(1).world().settings().substeps, 4);
    EXPECT_EQ(session.run(0).world().settings().substeps, 20);
    EXPECT_DOUBLE_EQ(session.run(1).world().settings().gravity.y(), -3.0);
    EXPECT_EQ(session.splits()[1], (view::SolverSplit{4, 20}));

    // Joint edits reach both runs; a restart brings both back to the start, keeping the splits.
    const ecs::Entity joint = session.first().namedJoints().front().second;
    session.setJointCompliance(joint, 1e-3);
    EXPECT_EQ(session.run(1).world().joint(session.run(1).instance().registry.get<ecs::Joint>(joint).id).compliance, 1e-3);
    session.restart();
    EXPECT_EQ(session.run(0).frame(), 0);
    EXPECT_EQ(session.run(1).frame(), 0);
    EXPECT_EQ(session.run(1).world().settings().substeps, 4);

    // A new scene keeps the comparison's splits (and brings its own gravity); compare mode off
    // brings back the scene's own splits, keeping an edited gravity.
    session.load(resolveScene("pendulum3"));
    EXPECT_EQ(session.run(0).world().settings().substeps, 20);
    EXPECT_EQ(session.run(1).world().settings().iterations, 20);
    EXPECT_DOUBLE_EQ(session.run(1).world().settings().gravity.y(), -10.0);
    session.first().controls().gravityY = -3.0f;
    session.applyControls();
    session.compare(std::nullopt);
    ASSERT_EQ(session.runCount(), 1u);
    EXPECT_EQ(session.first().world().settings().substeps, session.source().description.substeps);
    EXPECT_DOUBLE_EQ(session.first().world().settings().gravity.y(), -3.0);  // kept
}

// A knob that switches the solver (the bunny chain's 20 x 1 against 1 x 20) is set in both runs,
// but in compare mode each run keeps the split it is there to show.
TEST(CompareSessionTest, KnobsReachBothRunsAndLeaveTheSplits) {
    view::CompareSession session(resolveScene("bunny_chain"), 16.0f / 9.0f);
    session.compare(view::CompareSplits{{{10, 2}, {2, 10}}});
    SceneScript* script = session.first().script();
    ASSERT_NE(script, nullptr);
    const std::span<SceneKnob> knobs = script->knobs();
    const auto solver = std::find_if(knobs.begin(), knobs.end(), [](const SceneKnob& knob) { return knob.name == "solver"; });
    if (solver == knobs.end()) GTEST_SKIP() << "bunny_chain has no solver knob";
    const auto index = static_cast<std::size_t>(solver - knobs.begin());
    // Its last choice is 1 x 20: left alone, both runs would switch to it.
    const double value = static_cast<double>(solver->choices.size() - 1);
    session.setKnob(index, value);
    EXPECT_EQ(session.run(0).script()->knobs()[index].value, value);
    EXPECT_EQ(session.run(1).script()->knobs()[index].value, value);
    EXPECT_EQ(session.run(0).world().settings().substeps, 10);
    EXPECT_EQ(session.run(1).world().settings().substeps, 2);
    EXPECT_EQ(session.run(1).world().settings().iterations, 10);
}

TEST(CompareSessionTest, SplitsTheViewBesideThePanelIntoHalves) {
    view::CompareSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    // The view: a 1661 x 720 window less a 380-wide panel at its left.
    const view::ViewArea area{.left = 380.0f, .top = 0.0f, .width = 1281.0f, .height = 720.0f};
    const render::RenderTarget view{.framebuffer = 0, .size = {1281, 720}, .originX = 380, .originY = 0};
    render::RenderTarget whole = session.target(0, view);
    EXPECT_EQ(whole.originX, 380);
    EXPECT_EQ(whole.size, (render::PixelSize{1281, 720}));
    EXPECT_EQ(session.runAt(1500.0f, area), 0u);

    session.compare(view::kPaperCompareSplits);
    const render::RenderTarget left = session.target(0, view);
    const render::RenderTarget right = session.target(1, view);
    EXPECT_EQ(left.originX, 380);
    EXPECT_EQ(right.originX, 380 + left.size.width);
    EXPECT_EQ(left.size.width + right.size.width, 1281);  // every column of the view drawn once
    EXPECT_EQ(right.size.height, 720);
    EXPECT_EQ(session.runAt(400.0f, area), 0u);
    EXPECT_EQ(session.runAt(1100.0f, area), 1u);
    EXPECT_EQ(session.runAt(5000.0f, area), 1u);  // off the window: the nearest run
    EXPECT_EQ(session.runAt(10.0f, area), 0u);
    EXPECT_FLOAT_EQ(session.part(1, area).left, 380.0f + 640.5f);
    EXPECT_FLOAT_EQ(session.part(1, area).width, 640.5f);
}

// A static body that does not collide is moved by the cursor itself, and a body hanging from it
// follows; a static body that collides is not grabbed.
TEST(BodyDraggerTest, MovesAStaticNonCollidingBodyAndTheJointsFollow) {
    SceneDescription description{.name = "hanging", .gravity = scenes::kPaperGravity};
    scenes::addStaticBox(description, "ceiling", Vec3(1.0, 0.1, 0.4), Vec3(0.0, 2.05, 0.0));
    scenes::addBox(description, "weight", Vec3(0.2, 0.2, 0.2), 1.0, Vec3(0.0, 1.0, 0.0));
    // The weight's top centre pinned 0.9 m under the ceiling's bottom: a pendulum of 1 m to the
    // weight's centre, damped so it comes to rest.
    scenes::addJoint(description, "rod", "ceiling", "weight",
                     JointDef{.type = JointType::Distance, .anchor0 = Vec3(0.0, -0.05, 0.0),
                              .anchor1 = Vec3(0.0, 0.1, 0.0), .maxDistance = 0.9, .linearDamping = 5.0});
    description.bodies.push_back({"block", BodyDef{.shape = boxShape(Vec3(0.5, 0.5, 0.5)), .type = BodyType::Static,
                                                    .position = Vec3(3.0, 0.25, 0.0)}});  // collides
    view::ViewSession session(SceneSource{description, "hanging", false, nullptr}, 16.0f / 9.0f);
    for (int frame = 0; frame < 60; ++frame) session.stepOnce();  // the rope pulls taut

    const World& world = session.world();
    const auto bodyNamed = [&](const std::string& name) {
        for (const auto& [bodyName, id] : session.instance().namedBodyIds()) {
            if (bodyName == name) return id;
        }
        throw std::runtime_error("no body " + name);
    };
    const BodyId ceiling = bodyNamed("ceiling");
    const BodyId weight = bodyNamed("weight");
    const Vec3 ceilingStart = world.body(ceiling).x;
    EXPECT_NEAR(world.body(weight).x.x(), 0.0, 1e-6);

    // The colliding block stays where it is: no grab.
    EXPECT_FALSE(session.grab({Vec3(3.0, 0.25, 5.0), Vec3(0.0, 0.0, -1.0)}));

    // Grab the ceiling from the front at its centre, drag the cursor 0.5 m to the right in the
    // plane facing the camera.
    const Vec3 eye(0.0, 2.05, 5.0);
    ASSERT_TRUE(session.grab({eye, Vec3(0.0, 0.0, -1.0)}));
    EXPECT_TRUE(session.dragging());
    const std::size_t joints = world.joints().size();
    const Vec3 grabPoint(0.0, 2.05, 0.2);  // where the ray enters the ceiling's front face
    session.drag({eye, (grabPoint + Vec3(0.5, 0.0, 0.0) - eye).normalized()});
    const Body& moved = world.body(ceiling);
    EXPECT_NEAR(moved.x.x() - ceilingStart.x(), 0.5, 1e-9);
    EXPECT_NEAR(moved.x.y(), ceilingStart.y(), 1e-9);
    EXPECT_NEAR(moved.x.z(), ceilingStart.z(), 1e-9);
    EXPECT_EQ(moved.xPrev, moved.x);  // put there, not thrown
    EXPECT_EQ(world.joints().size(), joints);  // no spring for a static body

    // The weight swings over and, damped, comes to rest under the ceiling's new place, 1 m down.
    for (int frame = 0; frame < 600; ++frame) session.stepOnce();
    EXPECT_NEAR(world.body(weight).x.x(), 0.5, 1e-3);
    EXPECT_NEAR(world.body(weight).x.y(), 2.0 - 1.0, 1e-3);
    EXPECT_EQ(world.body(ceiling).x, moved.x);  // gravity and the rope leave a static body alone
    EXPECT_TRUE(world.isFinite());

    session.release();
    EXPECT_FALSE(session.dragging());
    EXPECT_NEAR(world.body(ceiling).x.x(), 0.5, 1e-9);  // left where it was put
}

TEST_F(ViewCommandTest, CompareTakesTwoSplitsOrNone) {
    for (const char* bad : {"20x1", "20x1,0x20", "fast,slow"}) {
        const Result result = substep(std::string("view pendulum3 --compare ") + bad, "env -u DISPLAY");
        EXPECT_EQ(result.exitCode, 2) << bad;
        EXPECT_NE(result.err.find("--compare: expected SUBSTEPSxITERATIONS,SUBSTEPSxITERATIONS"), std::string::npos)
            << result.err;
    }
    // Good values get as far as the display check.
    for (const char* good : {"view pendulum3 --compare", "view pendulum3 --compare 5x2,1x10"}) {
        const Result result = substep(good, "env -u DISPLAY");
        EXPECT_EQ(result.exitCode, 2) << good;
        EXPECT_NE(result.err.find(kNoDisplay), std::string::npos) << result.err;
    }
}

// Compare mode's scripted window: the two runs in the two halves, each a drawn scene (not the
// clear colour), the same picture for the same split, and different pictures once a triple
// pendulum has swung for a second and a half under 20 x 1 and under 1 x 20.
TEST_F(ViewCommandTest, CompareModeUnderXvfbShowsTwoRunsSideBySide) {
    if (!haveXvfbRun()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    const auto shoot = [&](const std::string& splits, const std::string& file) {
        const Result result =
            substep("view pendulum3 --compare " + splits + " --frames 90 --size 2460x700 --screenshot " + file,
                    "xvfb-run -a -s '-screen 0 2560x800x24'");
        EXPECT_EQ(result.exitCode, 0) << result.err;
        return render::decodePng(readFile(work() / file));
    };
    const render::Image different = shoot("20x1,1x20", "compare.png");
    const render::Image same = shoot("20x1,20x1", "same.png");
    ASSERT_EQ(different.width, 2460);
    ASSERT_EQ(same.height, 700);

    // A band of each half of the view (beside the 380 px panel docked at the left: halves of
    // 1040 px from x = 380) clear of the run's measures (bottom right of each half, at most half
    // its height), above the horizon: sky, bodies and joint markers. Each half is wide enough
    // that the pendulum's swing, 3 m either side of its pivot, stays in the band. The halves
    // start at the same phase of the sky's 4 x 4 dither, at full and at half resolution (the
    // light quality), so the same split gives the same pixels.
    constexpr int kHalf = 1040;
    constexpr int kBandLeft = 390;
    constexpr int kBandRight = 1380;
    constexpr int kBandTop = 10;
    constexpr int kBandBottom = 300;
    const auto meanDifference = [&](const render::Image& image) {
        double sum = 0.0;
        for (int y = kBandTop; y < kBandBottom; ++y) {
            for (int x = kBandLeft; x < kBandRight; ++x) {
                for (int c = 0; c < 3; ++c) sum += std::abs(image.pixel(x, y)[c] - image.pixel(x + kHalf, y)[c]);
            }
        }
        return sum / ((kBandBottom - kBandTop) * (kBandRight - kBandLeft) * 3.0);
    };
    // The sky behind is the same colour along a row; pixels far from their row's median colour
    // are the scene drawn over it.
    const auto sceneOverSky = [&](const render::Image& image, int offset) {
        std::size_t drawn = 0;
        for (int y = kBandTop; y < kBandBottom; ++y) {
            std::array<std::vector<int>, 3> channels;
            for (int x = kBandLeft; x < kBandRight; ++x) {
                for (int c = 0; c < 3; ++c) channels[c].push_back(image.pixel(x + offset, y)[c]);
            }
            std::array<int, 3> median{};
            for (int c = 0; c < 3; ++c) {
                std::nth_element(channels[c].begin(), channels[c].begin() + channels[c].size() / 2, channels[c].end());
                median[c] = channels[c][channels[c].size() / 2];
            }
            for (int x = kBandLeft; x < kBandRight; ++x) {
                const uint8_t* p = image.pixel(x + offset, y);
                const int distance = std::abs(p[0] - median[0]) + std::abs(p[1] - median[1]) + std::abs(p[2] - median[2]);
                if (distance > 60) ++drawn;
            }
            EXPECT_GT(median[0] + median[1] + median[2], 150) << "the clear colour at row " << y << ", offset " << offset;
        }
        return drawn;
    };
    // Both halves show the pendulum over the sky.
    EXPECT_GT(sceneOverSky(different, 0), 500u);
    EXPECT_GT(sceneOverSky(different, kHalf), 500u);
    // The same split draws the same picture in both halves (same camera, same size, same state),
    // so what differs below is the solver's doing.
    EXPECT_LT(meanDifference(same), 0.01);
    EXPECT_GT(meanDifference(different), 0.5);  // measured 1.6 (same split: 0)
}

}  // namespace
}  // namespace substep::command_test

// sandbox/view (`substep view`): the program run end to end. Without a display it must say so
// and exit 2; under Xvfb (xvfb-run) its scripted form opens the real window, runs frames and
// saves the window as a PNG, which is decoded and checked for the window's size and for a drawn
// scene and panel. The window-free parts (orbit camera, session, body dragger) run in process.

#include "command_test_support.h"

#include "render/png_codec.h"
#include "scene_source.h"
#include "view/orbit_camera.h"
#include "view/scene_file_watch.h"
#include "view/view_session.h"

#include <gtest/gtest.h>

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

    // The panel sits at the top left over the scene: ImGui's dark window is darker there than
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

    session.controls().playing = false;
    session.advance(1.0);  // paused: real time passes, the world does not
    EXPECT_EQ(session.frame(), 0);
    session.stepOnce();
    EXPECT_EQ(session.frame(), 1);

    session.controls().playing = true;
    session.advance(session.source().description.dt * 2.5);
    EXPECT_EQ(session.frame(), 3);
    session.advance(10.0);  // far behind: a few frames, not 600
    EXPECT_LE(session.frame(), 3 + 4);

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
    const JointId id = session.namedJoints().front().second;
    const double original = session.world().joint(id).compliance;
    session.setJointCompliance(id, 0.05);
    EXPECT_EQ(session.world().joint(id).compliance, 0.05);
    session.setJointCompliance(id, -1.0);  // refused: a compliance is never negative
    EXPECT_EQ(session.world().joint(id).compliance, 0.05);
    session.restart();
    EXPECT_EQ(session.world().joint(session.namedJoints().front().second).compliance, original);
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

}  // namespace
}  // namespace substep::command_test

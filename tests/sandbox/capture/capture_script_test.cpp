// Tests sandbox/capture/capture_script.cpp: capture scripts read whole, every error naming the
// script and the JSON path (DESIGN.md "Capture scripts").

#include "capture/capture_script.h"

#include "capture/json_input.h"

#include <gtest/gtest.h>

namespace substep::capture {
namespace {

std::string errorOf(const std::string& text) {
    try {
        parseCaptureScriptText(text, "dir/s.json");
    } catch (const InputError& error) {
        return error.what();
    }
    return "(no error)";
}

/// A valid script with one capture whose body is `capture` (without braces).
std::string script(const std::string& capture) {
    return R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": [0, 10], "state": {})" +
           (capture.empty() ? std::string() : ", " + capture) + "}]}";
}

TEST(CaptureScript, ReadsEveryFieldOfTheContractsExample) {
    const CaptureScript parsed = parseCaptureScriptText(
        R"({"substep_capture": 1, "captures": [
             {"name": "drop", "scene": "cradle", "set": {"velocity_pass": 0, "restitution": true},
              "substeps": 20, "iterations": 2, "dt": 0.01, "frames": [0, 20, 45],
              "state": {"abs": 1e-9, "rel": 1e-6, "bodies": {"b": {"abs": 0.5}}, "joints": {"j": {"rel": 0.25}}},
              "image": {"size": [320, 240], "pixel_tolerance": 8, "max_fraction": 0.002,
                        "camera": {"position": [0, 1, 4], "target": [0, 0, 0], "fov": 0.5}},
              "metrics": {"max_joint_error": 0.001, "energy_drift": 0.05, "penetration": 0.01}}]})",
        "dir/gallery.json");
    EXPECT_EQ(parsed.goldenFolder, "dir/gallery.golden");
    ASSERT_EQ(parsed.captures.size(), 1u);
    const CaptureSpec& spec = parsed.captures[0];
    EXPECT_EQ(spec.name, "drop");
    EXPECT_EQ(spec.scenePath, "cradle");
    ASSERT_EQ(spec.knobs.size(), 2u);
    EXPECT_EQ(spec.knobs[0], (std::pair<std::string, double>("velocity_pass", 0.0)));
    EXPECT_EQ(spec.knobs[1], (std::pair<std::string, double>("restitution", 1.0)));
    EXPECT_EQ(spec.substeps, 20);
    EXPECT_EQ(spec.iterations, 2);
    EXPECT_EQ(spec.dt, 0.01);
    EXPECT_EQ(spec.frames, (std::vector<long long>{0, 20, 45}));
    ASSERT_TRUE(spec.state);
    EXPECT_EQ(spec.state->tolerance.abs, 1e-9);
    EXPECT_EQ(spec.state->tolerance.rel, 1e-6);
    EXPECT_EQ(spec.state->bodies.at("b").abs, 0.5);
    EXPECT_EQ(spec.state->bodies.at("b").rel, 0.0);
    EXPECT_EQ(spec.state->joints.at("j").rel, 0.25);
    EXPECT_FALSE(spec.state->exact());
    ASSERT_TRUE(spec.image);
    EXPECT_EQ(spec.image->width, 320);
    EXPECT_EQ(spec.image->height, 240);
    EXPECT_EQ(spec.image->pixelTolerance, 8);
    EXPECT_EQ(spec.image->maxFraction, 0.002);
    ASSERT_TRUE(spec.image->camera);
    EXPECT_EQ(spec.image->camera->fov, 0.5);
    EXPECT_EQ(spec.metrics.maxJointError, 0.001);
    EXPECT_EQ(spec.metrics.energyDrift, 0.05);
    EXPECT_EQ(spec.metrics.penetration, 0.01);
}

TEST(CaptureScript, DefaultsAreExactStateAndASmallExactImage) {
    const CaptureScript parsed = parseCaptureScriptText(script(R"("image": {})"), "s.json");
    const CaptureSpec& spec = parsed.captures[0];
    EXPECT_TRUE(spec.state->exact());
    EXPECT_EQ(spec.image->width, 160);
    EXPECT_EQ(spec.image->height, 120);
    EXPECT_EQ(spec.image->pixelTolerance, 0);
    EXPECT_EQ(spec.image->maxFraction, 0.0);
    EXPECT_FALSE(spec.metrics.any());
    EXPECT_EQ(parsed.goldenFolder, "s.golden");
}

TEST(CaptureScript, ErrorsNameTheScriptAndTheJsonPath) {
    EXPECT_EQ(errorOf(R"({"captures": []})"),
              "dir/s.json: top level: missing \"substep_capture\": 1 (is this a capture script?)");
    EXPECT_EQ(errorOf(R"({"substep_capture": 1, "captures": []})"),
              "dir/s.json: captures: must list at least one capture");
    EXPECT_EQ(errorOf(script(R"("frame": [1])")),
              "dir/s.json: captures[0].frame: unknown key (expected one of: name, scene, set, "
              "substeps, iterations, dt, "
              "frames, state, image, metrics)");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": [0, 10, 5], "state": {}}]})"),
        "dir/s.json: captures[0].frames[2]: frames must increase, got 5 after 10");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": [-1], "state": {}}]})"),
        "dir/s.json: captures[0].frames[0]: must be a whole number from 0 to 1000000, got -1");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": []}]})"),
        "dir/s.json: captures[0].frames: must list 1 to 1000 frame numbers");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": [1]}]})"),
        "dir/s.json: captures[0]: needs \"state\", \"image\" or both: there is nothing to compare");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "../x", "scene": "boxes3", "frames": [1], "state": {}}]})"),
        "dir/s.json: captures[0].name: must not start with '.' (it names a folder)");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "nowhere.json", "frames": [1], "state": {}}]})"),
        "dir/s.json: captures[0].scene: no built-in scene \"nowhere.json\" (see `substep scenes`) "
        "and no file "
        "dir/nowhere.json");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": [1], "state": {"abs": -1}}]})"),
        "dir/s.json: captures[0].state.abs: must be between 0 and 1e+300, got -1");
    EXPECT_EQ(
        errorOf(script(R"("image": {"size": [0, 10]})")),
        "dir/s.json: captures[0].image.size[0]: must be a whole number from 1 to 4096, got 0");
    EXPECT_EQ(errorOf(script(R"("image": {"max_fraction": 1.5})")),
              "dir/s.json: captures[0].image.max_fraction: must be between 0 and 1, got 1.5");
    EXPECT_EQ(errorOf(script(R"("metrics": {"energy": 1})")),
              "dir/s.json: captures[0].metrics.energy: unknown key (expected one of: "
              "max_joint_error, energy_drift, "
              "penetration)");
    EXPECT_EQ(errorOf(script(R"("substeps": 0)")),
              "dir/s.json: captures[0].substeps: must be a whole number from 1 to 10000, got 0");
    EXPECT_EQ(errorOf(script(R"("dt": 0)")), "dir/s.json: captures[0].dt: must be > 0 s");
    EXPECT_EQ(errorOf(script(R"("dt": 1e-320)")).rfind("dir/s.json: captures[0].dt: must be at least 1e-06 s", 0), 0u);
    EXPECT_EQ(errorOf(script(R"("set": {"velocity_pass": "off"})")),
              "dir/s.json: captures[0].set.velocity_pass: expected a number, got a string");
    EXPECT_EQ(
        errorOf(
            R"({"substep_capture": 1, "captures": [{"name": "a", "scene": "boxes3", "frames": [1], "state": {}},
                                                            {"name": "a", "scene": "boxes7", "frames": [1], "state": {}}]})"),
        "dir/s.json: captures[1].name: duplicate capture name \"a\"");
}

}  // namespace
}  // namespace substep::capture

// Tests sandbox/capture/capture_command.cpp: `substep capture` end to end, by running the built
// program on scripts and goldens made in a scratch folder (DESIGN.md "Capture scripts").

#include "../command_test_support.h"

#include "render/png_codec.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>

namespace substep::command_test {
namespace {

/// A ball falling freely (nothing to hit) and a box hanging from a spring; gravity 10.
constexpr const char* kDropScene = R"({
  "substep_scene": 1, "gravity": [0, -10, 0], "dt": 0.016666666666666666, "substeps": 20, "iterations": 1,
  "bodies": [
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [1, 1, 0], "collide": false},
    {"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 2, "position": [0, 1, 0], "collide": false}
  ],
  "joints": [
    {"name": "spring", "type": "distance", "body0": "world", "body1": "box",
     "anchor0": [0, 1.1, 0], "anchor1": [0, 0.1, 0], "compliance": 0.001}
  ]
})";

constexpr const char* kScript = R"({"substep_capture": 1, "captures": [
  {"name": "drop", "scene": "drop.json", "frames": [0, 30], "state": {},
   "image": {"size": [160, 120]}},
  {"name": "cradle", "scene": "cradle", "set": {"velocity_pass": 1}, "frames": [20], "state": {}}
]})";

class CaptureCommand : public CommandTest {
  protected:
    void SetUp() override {
        CommandTest::SetUp();
        write("drop.json", kDropScene);
        write("s.json", kScript);
    }

    void write(const std::string& name, const std::string& text) const {
        std::ofstream(work() / name, std::ios::binary) << text;
    }
    std::string read(const std::string& name) const { return readFile(work() / name); }

    /// Every file under `folder` (relative to work()) with its bytes.
    std::map<std::string, std::string> snapshot(const std::string& folder) const {
        std::map<std::string, std::string> files;
        for (const auto& entry : fs::recursive_directory_iterator(work() / folder)) {
            if (entry.is_regular_file())
                files[fs::relative(entry.path(), work()).string()] = readFile(entry.path());
        }
        return files;
    }

    /// Replaces the first `from` in file `name` by `to`.
    void edit(const std::string& name, const std::string& from, const std::string& to) const {
        std::string text = read(name);
        const std::size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from << " not in " << name;
        write(name, text.replace(at, from.size(), to));
    }

    void update() const {
        const Result result = substep("capture s.json --update");
        ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    }
};

TEST_F(CaptureCommand, UpdateThenCompareMatchesAndUpdateTwiceChangesNothing) {
    Result result = substep("capture s.json --update");
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    EXPECT_NE(result.out.find("added     s.golden/drop/frame_00030.json"), std::string::npos)
        << result.out;
    EXPECT_NE(result.out.find("7 added, 0 changed, 0 unchanged, 0 removed"), std::string::npos)
        << result.out;
    const std::map<std::string, std::string> first = snapshot("s.golden");
    EXPECT_EQ(first.size(), 7u);  // drop: 2 states, 2 images, digest; cradle: 1 state, digest
    EXPECT_TRUE(first.count("s.golden/drop/frame_00000.png"));
    EXPECT_TRUE(first.count("s.golden/cradle/digest.txt"));
    const auto modified = fs::last_write_time(work() / "s.golden/drop/frame_00030.png");

    result = substep("capture s.json --update");
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    EXPECT_NE(result.out.find("0 added, 0 changed, 7 unchanged, 0 removed"), std::string::npos)
        << result.out;
    EXPECT_EQ(snapshot("s.golden"), first);
    EXPECT_EQ(fs::last_write_time(work() / "s.golden/drop/frame_00030.png"), modified);

    // Compared against them: all match; nothing on stderr (no progress line off a terminal).
    result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
    EXPECT_EQ(result.out, "substep capture s.json: 2 captures match (3 frames)\n");
    EXPECT_EQ(result.err, "");
    EXPECT_EQ(snapshot("s.golden"), first);
}

TEST_F(CaptureCommand, TheCapturedStateIsTheSimulatedOne) {
    update();
    // Free fall under XPBD's integration, n substeps of h: v = −g n h, y = y0 − g h² n(n+1)/2
    // (to the rounding of 600 substeps).
    const nlohmann::json state = nlohmann::json::parse(read("s.golden/drop/frame_00030.json"));
    const double t = 0.5;
    const double h = (1.0 / 60.0) / 20.0;
    const double n = 30.0 * 20.0;
    const nlohmann::json& ball = state["bodies"][0];
    EXPECT_EQ(ball["name"], "ball");
    EXPECT_NEAR(ball["velocity"][1].get<double>(), -10.0 * n * h, 1e-9);
    EXPECT_NEAR(ball["position"][1].get<double>(), 1.0 - 10.0 * h * h * n * (n + 1.0) / 2.0, 1e-9);
    EXPECT_EQ(ball["position"][0].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(state["t"].get<double>(), t);
    // The box, released with its spring (k = 1/α = 1000 N/m) unstretched, oscillates about the
    // stretch m g / k = 0.02 m at ω = √(k/m): stretch 0.02 (1 − cos ωt), force k times that;
    // within 5 % of the equilibrium stretch (the discrete oscillator runs slightly off ω).
    const double omega = std::sqrt(1000.0 / 2.0);
    const double stretch = 0.02 * (1.0 - std::cos(omega * t));
    EXPECT_NEAR(state["bodies"][1]["position"][1].get<double>(), 1.0 - stretch, 1e-3);
    EXPECT_EQ(state["joints"][0]["name"], "spring");
    EXPECT_NEAR(state["joints"][0]["force"].get<double>(), 1000.0 * stretch, 1.0);
    EXPECT_NEAR(state["joints"][0]["error"].get<double>(), stretch, 1e-3);
}

TEST_F(CaptureCommand, SoftBodiesAreCapturedWithTheirCentresAndVolumes) {
    // A soft box falling freely: its centre falls as a particle does under the substeps'
    // integration, y = y0 − g h² n(n+1)/2, and its volume is its size's while nothing presses it.
    write("soft.json", R"({"substep_scene": 1, "gravity": [0, -10, 0], "dt": 0.016666666666666666,
      "soft_bodies": [{"name": "jelly", "type": "box", "size": [0.3, 0.2, 0.5], "cells": [3, 2, 5],
                       "position": [0.5, 2, -1], "compliance": 1e-6}]})");
    write("soft_script.json", R"({"substep_capture": 1, "captures": [
      {"name": "jelly", "scene": "soft.json", "frames": [0, 30], "state": {}}]})");
    const Result result = substep("capture soft_script.json --update");
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    const nlohmann::json state = nlohmann::json::parse(read("soft_script.golden/jelly/frame_00030.json"));
    ASSERT_EQ(state["soft_bodies"].size(), 1u);
    const nlohmann::json& jelly = state["soft_bodies"][0];
    EXPECT_EQ(jelly["name"], "jelly");
    const double h = (1.0 / 60.0) / 20.0, n = 30.0 * 20.0;
    EXPECT_NEAR(jelly["centre"][0].get<double>(), 0.5, 1e-12);
    EXPECT_NEAR(jelly["centre"][1].get<double>(), 2.0 - 10.0 * h * h * n * (n + 1.0) / 2.0, 1e-9);
    EXPECT_NEAR(jelly["centre"][2].get<double>(), -1.0, 1e-12);
    EXPECT_NEAR(jelly["volume"].get<double>(), 0.3 * 0.2 * 0.5, 1e-12);
    // And a soft body that moves differently is a mismatch.
    edit("soft.json", "\"position\": [0.5, 2, -1]", "\"position\": [0.5, 2.001, -1]");
    const Result moved = substep("capture soft_script.json");
    EXPECT_EQ(moved.exitCode, 1) << moved.out << moved.err;
    EXPECT_NE((moved.out + moved.err).find("jelly"), std::string::npos) << moved.out << moved.err;
}

TEST_F(CaptureCommand, ChangedGravityIsAMismatchNamingCaptureFrameAndBody) {
    update();
    edit("drop.json", "[0, -10, 0]", "[0, -9.81, 0]");
    const Result result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(result.out.find("drop frame 30: state: "), std::string::npos) << result.out;
    // Six values move: the ball's and the box's height and vertical speed, the spring's force and
    // stretch; the worst is the force, off by 0.19 of m g (its share of the lighter gravity).
    EXPECT_NE(result.out.find("drop frame 30: state: 6 of 30 values out of tolerance; worst "
                              "joints[0] \"spring\".force: "
                              "golden 16.7"),
              std::string::npos)
        << result.out;
    EXPECT_NE(result.out.find("drop frame 30: image: "), std::string::npos) << result.out;
    EXPECT_EQ(result.out.find("frame 0:"), std::string::npos)
        << "frame 0 is the same state: " << result.out;
    EXPECT_NE(result.out.find("substep capture s.json: 1 of 2 captures differ"), std::string::npos)
        << result.out;
}

TEST_F(CaptureCommand, ChangedKnobIsAMismatch) {
    update();
    edit("s.json", "\"velocity_pass\": 1", "\"velocity_pass\": 0");
    const Result result = substep("capture s.json --only cradle");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(result.out.find("cradle frame 20: state: "), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("1 of 1 capture differ"), std::string::npos) << result.out;
}

TEST_F(CaptureCommand, OnePixelOfAnotherColourIsAMismatchUnlessTolerated) {
    update();
    const fs::path png = work() / "s.golden/drop/frame_00000.png";
    render::Image image = render::decodePng(readFile(png));
    image.rgba[4 * (60 * 160 + 80) + 1] ^= 0x40;  // one green channel, by 64
    std::ofstream(png, std::ios::binary) << render::encodePng(image);
    Result result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(
        result.out.find(
            "drop frame 0: image: 1 of 19200 pixels (0.005208%) differ by more than 0 (allowed "
            "0%); largest channel difference 64"),
        std::string::npos)
        << result.out;
    EXPECT_EQ(result.out.find("state"), std::string::npos) << result.out;

    // Within the script's tolerance it passes: a pixel tolerance of 64, or a fraction of 1e-4.
    edit("s.json", "\"size\": [160, 120]", "\"size\": [160, 120], \"pixel_tolerance\": 64");
    EXPECT_EQ(substep("capture s.json").exitCode, 0);
    edit("s.json", "\"pixel_tolerance\": 64", "\"max_fraction\": 1e-4");
    EXPECT_EQ(substep("capture s.json").exitCode, 0);
}

TEST_F(CaptureCommand, TheReportShowsTheImagesAndTheStateDifferences) {
    update();
    edit("drop.json", "[0, -10, 0]", "[0, -9.81, 0]");
    const Result result = substep("capture s.json --report rep");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(result.out.find("report: rep/index.html"), std::string::npos) << result.out;
    const std::string html = read("rep/index.html");
    EXPECT_NE(html.find("drop frame 30: state: "), std::string::npos);
    EXPECT_NE(html.find("<td>bodies[0] &quot;ball&quot;.velocity[1]</td><td>-5.0000000000"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<td>joints[0] &quot;spring&quot;.force</td>"), std::string::npos) << html;
    for (const char* kind : {"golden", "new", "diff"}) {
        const std::string name = std::string("drop/frame_00030_") + kind + ".png";
        EXPECT_NE(html.find("<img src=\"" + name + "\""), std::string::npos) << name;
        const render::Image image = render::decodePng(read("rep/" + name));
        EXPECT_EQ(image.width, 160);
        EXPECT_EQ(image.height, 120);
    }
    EXPECT_NE(html.find("cradle</a> (cradle): <span class=ok>matches"), std::string::npos);
    // The golden image in the report is the golden's bytes decoded and encoded again: the same
    // picture.
    EXPECT_EQ(render::decodePng(read("rep/drop/frame_00030_golden.png")).rgba,
              render::decodePng(read("s.golden/drop/frame_00030.png")).rgba);
}

TEST_F(CaptureCommand, DamagedOrMissingGoldensAreBadInputThatSaysWhatToDo) {
    Result result = substep("capture s.json --report rep");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err,
              "substep capture: s.golden/drop/frame_00000.json: no such golden; run `substep "
              "capture s.json --update` to "
              "make it\n");
    EXPECT_FALSE(fs::exists(work() / "rep")) << "no report on bad input";

    update();
    const std::string state = read("s.golden/drop/frame_00030.json");
    write("s.golden/drop/frame_00030.json", state.substr(0, state.size() / 2));
    result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_TRUE(std::regex_search(
        result.err,
        std::regex(
            R"re(^substep capture: s\.golden/drop/frame_00030\.json: [\w\[\]\.]+: not valid JSON at line \d+, column \d+: .*a damaged golden\? run `substep capture s\.json --update` to make it again\)\n$)re")))
        << result.err;
    EXPECT_EQ(result.out, "");
    write("s.golden/drop/frame_00030.json", state);

    const std::string png = read("s.golden/drop/frame_00030.png");
    write("s.golden/drop/frame_00030.png", png.substr(0, 200));
    result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("s.golden/drop/frame_00030.png: cannot be decoded ("),
              std::string::npos)
        << result.err;
    write("s.golden/drop/frame_00030.png", png);

    write("s.golden/cradle/digest.txt", "fnv1a64\n");
    result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("s.golden/cradle/digest.txt: not a digest line"), std::string::npos)
        << result.err;
}

TEST_F(CaptureCommand, ADigestThatDiffersIsAMismatchEvenWhenTheListedFramesMatch) {
    update();
    std::string digest = read("s.golden/cradle/digest.txt");
    digest[8] = digest[8] == '0' ? '1' : '0';
    write("s.golden/cradle/digest.txt", digest);
    const Result result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(result.out.find("cradle: digest: the run differs between the listed frames (golden " +
                              digest.substr(0, digest.size() - 1)),
              std::string::npos)
        << result.out;
}

TEST_F(CaptureCommand, ScriptErrorsNameTheFileAndTheJsonPath) {
    edit("s.json", "\"frames\": [0, 30]", "\"frames\": [30, 0]");
    Result result = substep("capture s.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(
        result.err,
        "substep capture: s.json: captures[0].frames[1]: frames must increase, got 0 after 30\n");

    edit("s.json", "\"frames\": [30, 0]", "\"frames\": [0, 30]");
    edit("s.json", "\"velocity_pass\": 1", "\"velocity\": 1");
    result = substep("capture s.json --update");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err.rfind("substep capture: s.json: captures[1].set.velocity: cradle has no "
                               "such knob (its knobs: ",
                               0),
              0u)
        << result.err;
    EXPECT_FALSE(fs::exists(work() / "s.golden"))
        << "bad input writes no golden, not even the first capture's";

    result = substep("capture s.json --only nothing");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err,
              "substep capture: --only nothing: s.json has no capture of that name (its captures: "
              "drop, cradle)\n");
    EXPECT_EQ(substep("capture").exitCode, 2);

    fs::create_directory(work() / "folder.json");
    result = substep("capture folder.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err, "substep capture: folder.json: is a folder, not a file\n");
}

TEST_F(CaptureCommand, AReportFolderThatCannotBeMadeIsBadInputBeforeAnythingRuns) {
    write("taken", "");
    const Result result = substep("capture s.json --update --report taken");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err,
              "substep capture: --report taken: cannot create the folder (a file has that name)\n");
    EXPECT_EQ(result.out, "");
    EXPECT_FALSE(fs::exists(work() / "s.golden"));
}

TEST_F(CaptureCommand, OnlyRunsTheNamedCaptures) {
    const Result result = substep("capture s.json --update --only drop");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(fs::exists(work() / "s.golden/drop/digest.txt"));
    EXPECT_FALSE(fs::exists(work() / "s.golden/cradle"));
    EXPECT_EQ(substep("capture s.json --only drop").exitCode, 0);
    EXPECT_EQ(substep("capture s.json").exitCode, 2) << "cradle's goldens are missing";
}

TEST_F(CaptureCommand, MetricBoundsHoldWhateverTheGoldensSay) {
    // The spring stretches by m g α = 2 · 10 · 0.001 = 0.02 m as the box settles; it starts
    // unstretched.
    edit("s.json", "\"image\": {\"size\": [160, 120]}",
         "\"image\": {}, \"metrics\": {\"max_joint_error\": 0.01}");
    Result result = substep("capture s.json --update");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_TRUE(std::regex_search(
        result.out,
        std::regex(
            R"re(drop: metrics: max_joint_error 0\.0[2-4]\d* m over frames 0-30 exceeds its bound 0\.01 m)re")))
        << result.out;
    EXPECT_FALSE(fs::exists(work() / "s.golden/drop"))
        << "an unsound run's goldens are not written";
    EXPECT_TRUE(fs::exists(work() / "s.golden/cradle/digest.txt"));

    edit("s.json", "\"max_joint_error\": 0.01", "\"max_joint_error\": 0.05");
    EXPECT_EQ(substep("capture s.json --update").exitCode, 0);
    EXPECT_EQ(substep("capture s.json").exitCode, 0);
}

TEST_F(CaptureCommand, UpdateRemovesGoldensTheScriptNoLongerMakes) {
    update();
    edit("s.json", "\"frames\": [0, 30]", "\"frames\": [30]");
    const Result result = substep("capture s.json --update");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(
        result.out.find(
            "removed   s.golden/drop/frame_00000.json\nremoved   s.golden/drop/frame_00000.png\n"),
        std::string::npos)
        << result.out;
    // The digest covers frames 0 to 30 whichever are listed: unchanged.
    EXPECT_NE(result.out.find("0 added, 0 changed, 5 unchanged, 2 removed"), std::string::npos)
        << result.out;
    EXPECT_FALSE(fs::exists(work() / "s.golden/drop/frame_00000.png"));
}

// The chaotic pendula script: its per-body tolerances absorb a nudge of dt by 1e-13 of itself
// (a stand-in for another compiler's rounding), which exact tolerances do not.
TEST_F(CaptureCommand, PerBodyTolerancesAbsorbTheChaoticPendulasDivergence) {
    const fs::path assets = fs::path(SUBSTEP_SOURCE_DIR) / "assets/captures";
    fs::copy(assets / "chaotic_pendula.golden", work() / "chaotic_pendula.golden",
             fs::copy_options::recursive);
    write("chaotic_pendula.json", readFile(assets / "chaotic_pendula.json"));
    edit("chaotic_pendula.json", "\"scene\": \"pendula\",",
         "\"scene\": \"pendula\", \"dt\": 0.016666666666668332,");
    Result result = substep("capture chaotic_pendula.json");
    EXPECT_EQ(result.exitCode, 0) << result.out << result.err;

    // Without them the same nudge differs, in the chaotic bodies.
    std::string script = read("chaotic_pendula.json");
    script = std::regex_replace(script, std::regex(R"re("(abs|rel)": [0-9.e+-]+)re"), "\"$1\": 0");
    write("chaotic_pendula.json", script);
    result = substep("capture chaotic_pendula.json");
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_TRUE(std::regex_search(
        result.out,
        std::regex(
            R"re(pendula frame 600: state: \d+ of 132 values out of tolerance; worst (bodies|joints)\[\d+\] "(double|triple))re")))
        << result.out;
}

}  // namespace
}  // namespace substep::command_test

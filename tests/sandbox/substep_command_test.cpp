// Tests the `substep` program (sandbox/main.cpp, run_command.cpp, scene_source.cpp) by running
// the built binary against DESIGN.md's command contract: columns, rows, exit codes, summaries,
// and that bad input never leaves a file behind.

#include "command_test_support.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace substep {
namespace {

using command_test::CommandTest;
using command_test::lines;
using command_test::quoted;
using command_test::readFile;
using command_test::Result;
namespace fs = std::filesystem;

const fs::path kHangScene = fs::path(SUBSTEP_TEST_DATA) / "sandbox" / "hang.json";
constexpr double kHangDt = 0.016666666666666666;  // hang.json's dt

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');)
        cells.push_back(cell);
    return cells;
}

/// Each test runs the program in its own empty working folder (command_test_support.h).
class SubstepCommand : public CommandTest {};

const std::string kHang = quoted(kHangScene.string());

TEST_F(SubstepCommand, HeaderFollowsTheContract) {
    const Result result = substep("run " + kHang + " --frames 1 --csv out.csv");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::vector<std::string> rows = lines(readFile(work() / "out.csv"));
    ASSERT_FALSE(rows.empty());
    EXPECT_TRUE(rows[0].starts_with("frame,t,kinetic,potential,elastic,energy,max_error,b.x,"));
    EXPECT_EQ(rows[0],
              "frame,t,kinetic,potential,elastic,energy,max_error,"
              "b.x,b.y,b.z,b.qw,b.qx,b.qy,b.qz,b.vx,b.vy,b.vz,b.wx,b.wy,b.wz,"
              "j.force,j.torque,j.error");
}

TEST_F(SubstepCommand, RowZeroIsTheInitialStateAndTIsFrameTimesDt) {
    const Result result = substep("run " + kHang + " --frames 30 --csv out.csv");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::vector<std::string> rows = lines(readFile(work() / "out.csv"));
    ASSERT_EQ(rows.size(), 1u + 31u) << "header, row 0, and one row per frame";
    const std::vector<std::string> header = split(rows[0]);
    for (std::size_t frame = 0; frame <= 30; ++frame) {
        const std::vector<std::string> cells = split(rows[frame + 1]);
        ASSERT_EQ(cells.size(), header.size()) << "row " << frame;
        EXPECT_EQ(cells[0], std::to_string(frame));
        EXPECT_EQ(std::strtod(cells[1].c_str(), nullptr), static_cast<double>(frame) * kHangDt);
    }
    // Row 0: the pose and velocities of the file, exactly.
    const std::vector<std::string> row0 = split(rows[1]);
    auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        return row0.at(static_cast<std::size_t>(it - header.begin()));
    };
    EXPECT_EQ(column("b.x"), "0");
    EXPECT_EQ(column("b.y"), "1");
    EXPECT_EQ(column("b.qw"), "1");
    EXPECT_EQ(column("b.vy"), "0");
    EXPECT_EQ(column("kinetic"), "0");
}

TEST_F(SubstepCommand, RerunsAreByteIdentical) {
    ASSERT_EQ(substep("run " + kHang + " --frames 120 --csv a.csv").exitCode, 0);
    ASSERT_EQ(substep("run " + kHang + " --frames 120 --csv b.csv").exitCode, 0);
    const std::string a = readFile(work() / "a.csv");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, readFile(work() / "b.csv"));
}

TEST_F(SubstepCommand, ThreadsGiveTheSameBytes) {
    // A pile with enough pairs for every stage to split (spheres1000 landing: about 2000). Two
    // threads and more solve in the coloured order (README, `--threads`), the same bytes for
    // every count and from run to run; one thread is the serial order.
    ASSERT_EQ(substep("run spheres1000 --frames 80 --threads 2 --csv two.csv").exitCode, 0);
    ASSERT_EQ(substep("run spheres1000 --frames 80 --threads 2 --csv again.csv").exitCode, 0);
    ASSERT_EQ(substep("run spheres1000 --frames 80 --threads 3 --csv three.csv").exitCode, 0);
    const std::string two = readFile(work() / "two.csv");
    EXPECT_FALSE(two.empty());
    EXPECT_EQ(two, readFile(work() / "again.csv"));
    EXPECT_EQ(two, readFile(work() / "three.csv"));
    for (const char* bad : {"0", "65", "two"}) {
        const Result result = substep("run " + kHang + " --frames 1 --threads " + bad + " --csv t.csv");
        EXPECT_EQ(result.exitCode, 2) << bad;
        EXPECT_NE(result.err.find("--threads"), std::string::npos) << result.err;
        EXPECT_FALSE(fs::exists(work() / "t.csv")) << bad;
    }
}

TEST_F(SubstepCommand, SecondsBecomeRoundedFrames) {
    ASSERT_EQ(substep("run " + kHang + " --seconds 0.5 --csv out.csv").exitCode, 0);
    EXPECT_EQ(lines(readFile(work() / "out.csv")).size(), 1u + 1u + 30u);

    // Neither option: 5 s.
    ASSERT_EQ(substep("run " + kHang + " --json s.json").exitCode, 0);
    EXPECT_EQ(nlohmann::json::parse(readFile(work() / "s.json")).at("frames"), 300);

    // --dt overrides the scene's: 0.5 s at 0.01 s.
    ASSERT_EQ(substep("run " + kHang + " --seconds 0.5 --dt 0.01 --json s.json").exitCode, 0);
    EXPECT_EQ(nlohmann::json::parse(readFile(work() / "s.json")).at("frames"), 50);
}

TEST_F(SubstepCommand, JsonSummaryHasEveryField) {
    const Result result =
        substep("run " + kHang + " --frames 30 --substeps 7 --iterations 2 --json s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const nlohmann::json summary = nlohmann::json::parse(readFile(work() / "s.json"));
    EXPECT_EQ(summary.at("frames"), 30);
    EXPECT_EQ(summary.at("substeps"), 7);
    EXPECT_EQ(summary.at("iterations"), 2);
    EXPECT_TRUE(summary.at("wall_ms_per_frame").is_number());
    EXPECT_GE(summary.at("wall_ms_per_frame").get<double>(), 0.0);
    EXPECT_TRUE(summary.at("energy_initial").is_number());
    EXPECT_TRUE(summary.at("energy_final").is_number());
    EXPECT_GE(summary.at("max_error").get<double>(), 0.0);
    EXPECT_EQ(summary.at("finite"), true);
    // The scene's own settings when not overridden.
    ASSERT_EQ(substep("run " + kHang + " --frames 1 --json s.json").exitCode, 0);
    EXPECT_EQ(nlohmann::json::parse(readFile(work() / "s.json")).at("substeps"), 10);
}

TEST_F(SubstepCommand, JsonSummaryMatchesTheCsv) {
    ASSERT_EQ(substep("run " + kHang + " --frames 60 --csv out.csv --json s.json").exitCode, 0);
    const std::vector<std::string> rows = lines(readFile(work() / "out.csv"));
    const nlohmann::json summary = nlohmann::json::parse(readFile(work() / "s.json"));
    const double energyFirst = std::strtod(split(rows[1])[5].c_str(), nullptr);
    const double energyLast = std::strtod(split(rows.back())[5].c_str(), nullptr);
    double maxError = 0.0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        maxError = std::max(maxError, std::strtod(split(rows[i])[6].c_str(), nullptr));
    }
    EXPECT_EQ(summary.at("energy_initial").get<double>(), energyFirst);
    EXPECT_EQ(summary.at("energy_final").get<double>(), energyLast);
    EXPECT_EQ(summary.at("max_error").get<double>(), maxError);
}

TEST_F(SubstepCommand, BuiltinSceneRuns) {
    const auto scenes = builtinScenes();
    ASSERT_FALSE(scenes.empty());
    const std::string name(scenes.front().name);
    const Result result = substep("run " + name + " --frames 3 --csv out.csv");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(lines(readFile(work() / "out.csv")).size(), 1u + 1u + 3u);
    EXPECT_NE(result.out.find(name), std::string::npos) << result.out;
}

TEST_F(SubstepCommand, TruncatedSceneExits2NamingTheFileAndWritesNothing) {
    const std::string text = readFile(kHangScene);
    std::ofstream(work() / "broken.json") << text.substr(0, text.size() / 2);
    const Result result = substep("run broken.json --frames 5 --csv out.csv --json s.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("broken.json"), std::string::npos) << result.err;
    EXPECT_EQ(workEntries(), std::vector<std::string>{"broken.json"});
}

TEST_F(SubstepCommand, UnknownSceneExits2PointingToTheList) {
    Result result = substep("run no_such_scene --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("substep scenes"), std::string::npos) << result.err;
    result = substep("run missing/scene.json --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("missing/scene.json"), std::string::npos) << result.err;
    EXPECT_TRUE(workEntries().empty());
}

// --set turns a scene's knob before the first frame: the cradle without its velocity pass is
// plain PBD, whose hit passes on only half the striker's speed (paper Fig. 12), so its CSV differs.
TEST_F(SubstepCommand, SetTurnsASceneKnob) {
    ASSERT_EQ(substep("run cradle --frames 60 --csv pass.csv").exitCode, 0);
    const Result plain = substep("run cradle --frames 60 --set velocity_pass=0 --csv plain.csv");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    EXPECT_NE(readFile(work() / "pass.csv"), readFile(work() / "plain.csv"));
    // A knob that switches the solver shows in the summary; --substeps still wins over it.
    EXPECT_NE(substep("run bunny_chain --frames 1 --set solver=4").out.find("1 substeps x 20 iterations"),
              std::string::npos);
    EXPECT_NE(substep("run bunny_chain --frames 1 --set solver=4 --substeps 3").out.find("3 substeps x 20"),
              std::string::npos);
}

TEST_F(SubstepCommand, BadSetExits2NamingTheKnobsAndWritesNothing) {
    Result result = substep("run cradle --set no_such_knob=1 --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("velocity_pass"), std::string::npos) << "lists the scene's knobs: " << result.err;
    result = substep("run cradle --set velocity_pass --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("NAME=VALUE"), std::string::npos) << result.err;
    result = substep("run cradle --set velocity_pass=yes --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    result = substep("run " + kHang + " --set velocity_pass=0 --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("none"), std::string::npos) << "a scene file has no knobs: " << result.err;
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SubstepCommand, FramesWithSecondsIsAUsageError) {
    const Result result = substep("run " + kHang + " --frames 10 --seconds 1 --csv out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_FALSE(result.err.empty());
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SubstepCommand, OutOfRangeValuesExit2) {
    for (const char* options :
         {"--substeps 0",   "--substeps 10001",  "--substeps -3", "--substeps 99999999999999999999",
          "--iterations 0", "--iterations 1001", "--frames -1",   "--frames 10000001",
          "--frames abc",   "--frames 1.5",      "--seconds 0",   "--seconds -1",
          "--seconds nan",  "--seconds 1e999",   "--dt 0",        "--dt -0.01",
          "--dt inf",       "--dt nan",          "--dt x",        "--seconds 1e300"}) {
        const Result result = substep("run " + kHang + " " + options + " --csv out.csv");
        EXPECT_EQ(result.exitCode, 2) << options;
        EXPECT_FALSE(result.err.empty()) << options;
    }
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SubstepCommand, RangeEndsAreAccepted) {
    EXPECT_EQ(substep("run " + kHang + " --frames 0 --substeps 1 --iterations 1").exitCode, 0);
    EXPECT_EQ(substep("run " + kHang + " --frames 1 --substeps 10000 --iterations 1000").exitCode,
              0);
}

TEST_F(SubstepCommand, UnwritableOutputExits2AndLeavesNothing) {
    Result result = substep("run " + kHang + " --frames 5 --csv missing/out.csv --json s.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("missing/out.csv"), std::string::npos) << result.err;
    EXPECT_TRUE(workEntries().empty());

    fs::create_directories(work() / "folder");
    result = substep("run " + kHang + " --frames 5 --csv folder");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(workEntries(), std::vector<std::string>{"folder"});
    EXPECT_TRUE(fs::is_empty(work() / "folder"));
}

TEST_F(SubstepCommand, AFrameTooLongToStayFiniteIsRefused) {
    // A frame of 1e300 s under gravity used to overflow the velocity, then the position (exit 1
    // with the rows so far); --dt now has a file's bounds, so it is bad input and nothing is
    // written. No valid input is known to turn the state non-finite any more.
    const Result result =
        substep("run " + kHang + " --frames 10 --dt 1e300 --csv out.csv --json s.json");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("--dt must be between 1e-06 and 1, got 1e300"), std::string::npos)
        << result.err;
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SubstepCommand, ScenesListsEveryBuiltinScene) {
    const Result result = substep("scenes");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::vector<std::string> listed = lines(result.out);
    const auto scenes = builtinScenes();
    ASSERT_EQ(listed.size(), scenes.size());
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        EXPECT_TRUE(listed[i].starts_with(std::string(scenes[i].name) + " ")) << listed[i];
        EXPECT_NE(listed[i].find(scenes[i].description), std::string::npos) << listed[i];
    }
}

TEST_F(SubstepCommand, UsageErrorsExit2) {
    EXPECT_EQ(substep("run").exitCode, 2);
    EXPECT_EQ(substep("run " + kHang + " --no-such-option").exitCode, 2);
    EXPECT_EQ(substep("run " + kHang + " --frames").exitCode, 2);
    EXPECT_EQ(substep("frobnicate").exitCode, 2);
    EXPECT_EQ(substep("--help").exitCode, 0);
    EXPECT_EQ(substep("run --help").exitCode, 0);
    EXPECT_TRUE(workEntries().empty());
}

// --restitution (issue 17; an addition to DESIGN.md's command): the row of the issue, a striker
// listed first at 1 m/s into three touching spheres (no gravity, no friction, e = 1), in a file
// that asks for the paper's rule. With the sweeps the closed form of elastic collisions holds
// (the striker stops, the far sphere leaves at 1 m/s); the paper's Eq. 34 alone carries the
// push down the row in one pass and the far sphere leaves at 0.43 m/s. A bad value exits 2
// naming the option, on run, bench and sweep, and writes nothing.
TEST_F(SubstepCommand, RestitutionOptionChoosesTheRule) {
    std::string bodies;
    for (int i = 0; i < 4; ++i) {
        const double x = i == 0 ? -0.3 : 0.2 * (i - 1);
        bodies += std::string(i == 0 ? "" : ",\n") + "{\"name\": \"s" + std::to_string(i) +
                  "\", \"shape\": {\"type\": \"sphere\", \"radius\": 0.1}, \"mass\": 1, \"position\": [" +
                  std::to_string(x) + ", 0, 0], \"velocity\": [" + (i == 0 ? "1" : "0") +
                  ", 0, 0], \"friction\": {\"static\": 0, \"dynamic\": 0}, \"restitution\": 1}";
    }
    std::ofstream(work() / "row.json") << "{\"substep_scene\": 1, \"gravity\": [0, 0, 0], \"substeps\": 20, "
                                          "\"restitution\": \"paper\", \"bodies\": [" << bodies << "]}\n";
    const auto finalVx = [&](const std::string& file, const std::string& body) {
        const std::vector<std::string> rows = lines(readFile(work() / file));
        const std::vector<std::string> header = split(rows.at(0));
        const std::vector<std::string> last = split(rows.back());
        const auto it = std::find(header.begin(), header.end(), body + ".vx");
        return std::strtod(last.at(static_cast<std::size_t>(it - header.begin())).c_str(), nullptr);
    };
    const Result swept = substep("run row.json --frames 60 --restitution swept --csv swept.csv");
    ASSERT_EQ(swept.exitCode, 0) << swept.err;
    EXPECT_NEAR(finalVx("swept.csv", "s0"), 0.0, 1e-3);
    EXPECT_NEAR(finalVx("swept.csv", "s1"), 0.0, 1e-3);
    EXPECT_NEAR(finalVx("swept.csv", "s2"), 0.0, 1e-3);
    EXPECT_NEAR(finalVx("swept.csv", "s3"), 1.0, 1e-3);
    const Result paper = substep("run row.json --frames 60 --restitution paper --csv paper.csv");
    ASSERT_EQ(paper.exitCode, 0) << paper.err;
    EXPECT_LT(finalVx("paper.csv", "s3"), 0.6) << "the paper's rule, listed striker first";
    fs::remove(work() / "swept.csv");
    fs::remove(work() / "paper.csv");
    for (const std::string& command : {std::string("run row.json --frames 1 --csv bad.csv"),
                                       std::string("bench row.json --seconds 0.1 --repeats 1 --json bad.json"),
                                       std::string("sweep row.json --budget 2 --seconds 0.1 --csv bad.csv")}) {
        const Result bad = substep(command + " --restitution Swept");
        EXPECT_EQ(bad.exitCode, 2) << command;
        EXPECT_NE(bad.err.find("--restitution: expected swept or paper, got 'Swept'"), std::string::npos)
            << command << ": " << bad.err;
        const Result good = substep(command + " --restitution swept");
        EXPECT_EQ(good.exitCode, 0) << command << ": " << good.err;
        fs::remove(work() / "bad.csv");
        fs::remove(work() / "bad.json");
    }
    EXPECT_EQ(workEntries(), std::vector<std::string>{"row.json"});
}

// Without a display the viewer (also `substep` alone) says so, points to `render`, and exits 2;
// DISPLAY is unset so that the test never opens a window on a machine that has one.
TEST_F(SubstepCommand, ViewerWithoutDisplaySaysSoAndCaptureOfAMissingScriptExits2) {
    for (const char* command : {"", "view boxes3"}) {
        const Result result = substep(command, "env -u DISPLAY -u WAYLAND_DISPLAY");
        EXPECT_EQ(result.exitCode, 2) << command;
        EXPECT_NE(result.err.find("no display"), std::string::npos) << command << ": " << result.err;
        EXPECT_NE(result.err.find("substep render"), std::string::npos) << command << ": " << result.err;
    }
    // capture is built (tests/sandbox/capture/ test it); a script that is not there is bad input.
    const Result result = substep("capture script.json");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("script.json: cannot be read"), std::string::npos) << result.err;
    EXPECT_TRUE(workEntries().empty());
}

}  // namespace
}  // namespace substep

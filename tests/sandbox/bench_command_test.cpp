// Tests `substep bench` (sandbox/bench_command.cpp) by running the built binary: the table's
// columns, the JSON array, and that bad input exits 2 leaving nothing behind. No timings are
// checked (DESIGN.md: timings are benchmarks, never pass/fail tests), only that they are there.

#include "command_test_support.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace substep {
namespace {

using command_test::CommandTest;
using command_test::quoted;
using command_test::readFile;
using command_test::Result;
namespace fs = std::filesystem;

// Short and single: the tests check the output's shape, not the figures.
const std::string kQuick = " --seconds 0.1 --repeats 1";

std::vector<std::string> words(const std::string& line) {
    std::vector<std::string> result;
    std::istringstream in(line);
    for (std::string word; in >> word;)
        result.push_back(word);
    return result;
}

/// The table row of `scene`, split into cells; empty when there is none.
std::vector<std::string> rowOf(const std::string& out, const std::string& scene) {
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells = words(line);
        if (!cells.empty() && cells[0] == scene) return cells;
    }
    return {};
}

/// Bodies the solver moves: what the table's and the JSON's `bodies` count.
std::size_t movingBodies(const SceneDescription& scene) {
    return static_cast<std::size_t>(
        std::count_if(scene.bodies.begin(), scene.bodies.end(),
                      [](const SceneBody& body) { return body.def.type != BodyType::Static; }));
}

/// Each test runs the program in its own empty working folder; stdout and stderr are captured
/// outside it, so "nothing written" means the folder is still empty.
class BenchCommand : public CommandTest {
  protected:
    bool workIsEmpty() const { return fs::is_empty(work()); }
};

/// The two scenes the tests bench: one with a paper figure (boxes3), one with several
/// pendulums at 40 substeps (pendula).
const char* const kScenes[] = {"boxes3", "pendula"};

TEST_F(BenchCommand, TableListsTheScenesWithTheirSettings) {
    const Result result = substep(std::string("bench boxes3 pendula") + kQuick);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::vector<std::string> header = words(result.out.substr(0, result.out.find('\n')));
    ASSERT_GE(header.size(), 7u);
    EXPECT_EQ(header[0], "scene");
    EXPECT_EQ(header[1], "bodies");
    EXPECT_EQ(header[2], "joints");
    EXPECT_EQ(header[3], "contacts/frame");
    EXPECT_EQ(header[4], "substeps");
    EXPECT_EQ(header[5], "iterations");
    EXPECT_EQ(header[6], "ms/frame");

    for (const char* name : kScenes) {
        const SceneEntry* entry = findBuiltinScene(name);
        ASSERT_NE(entry, nullptr) << name;
        const SceneDescription scene = entry->build();
        const std::vector<std::string> row = rowOf(result.out, name);
        ASSERT_GE(row.size(), 7u) << name << " not in:\n" << result.out;
        EXPECT_EQ(row[1], std::to_string(movingBodies(scene))) << name;
        EXPECT_EQ(row[2], std::to_string(scene.joints.size())) << name;
        EXPECT_EQ(row[3], "0") << name;
        EXPECT_EQ(row[4], std::to_string(scene.substeps)) << name;
        EXPECT_EQ(row[5], std::to_string(scene.iterations)) << name;
        EXPECT_GE(std::strtod(row[6].c_str(), nullptr), 0.0) << name;
        // The paper's figure and the ratio where the paper gives one, nothing where it does not.
        EXPECT_EQ(row.size(), entry->paperMsPerFrame > 0.0 ? 9u : 7u) << name;
    }
    // Static bodies (boxes3's ceiling) are not counted, as in the paper's "3 Boxes".
    EXPECT_EQ(rowOf(result.out, "boxes3").at(1), "3");
    // Only the scenes asked for.
    EXPECT_TRUE(rowOf(result.out, "chain100").empty()) << result.out;
}

TEST_F(BenchCommand, JsonIsAnArrayWithEveryField) {
    const Result result = substep(std::string("bench boxes3 pendula --json b.json") + kQuick);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const nlohmann::json json = nlohmann::json::parse(readFile(work() / "b.json"));
    ASSERT_TRUE(json.is_array());
    ASSERT_EQ(json.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        const nlohmann::json& row = json[i];
        const SceneEntry* entry = findBuiltinScene(kScenes[i]);
        const SceneDescription scene = entry->build();
        EXPECT_EQ(row.at("scene"), kScenes[i]);
        EXPECT_EQ(row.at("bodies"), movingBodies(scene));
        EXPECT_EQ(row.at("static_bodies"), scene.bodies.size() - movingBodies(scene));
        EXPECT_EQ(row.at("joints"), scene.joints.size());
        EXPECT_EQ(row.at("contacts_per_frame"), 0);
        EXPECT_EQ(row.at("substeps"), scene.substeps);
        EXPECT_EQ(row.at("iterations"), scene.iterations);
        EXPECT_EQ(row.at("dt"), scene.dt);
        EXPECT_EQ(row.at("repeats"), 1);
        EXPECT_GE(row.at("warm_up_frames").get<long long>(), 1);
        EXPECT_GE(row.at("timed_frames").get<long long>(), 1);
        ASSERT_TRUE(row.at("repeat_ms_per_frame").is_array());
        EXPECT_EQ(row.at("repeat_ms_per_frame").size(), 1u);
        ASSERT_TRUE(row.at("median_ms_per_frame").is_number());
        EXPECT_GE(row.at("median_ms_per_frame").get<double>(), 0.0);
        EXPECT_EQ(row.at("finite"), true);
        if (entry->paperMsPerFrame > 0.0) {
            EXPECT_EQ(row.at("paper_ms_per_frame"), entry->paperMsPerFrame);
            EXPECT_TRUE(row.at("paper_ratio").is_number() || row.at("paper_ratio").is_null());
        } else {
            EXPECT_TRUE(row.at("paper_ms_per_frame").is_null());
            EXPECT_TRUE(row.at("paper_ratio").is_null());
        }
    }
}

/// --sleeping turns sleeping on and reports the sleeping bodies; --warm-up sets the untimed
/// frames: stack10's ten cubes, stacked at rest, sleep after 0.5 s, so after a 2 s warm-up all
/// ten sleep through the timed frames (without --sleeping none do, and the key is absent).
TEST_F(BenchCommand, SleepingAndWarmUp) {
    const Result result = substep("bench stack10 --sleeping --warm-up 2 --seconds 0.5 --repeats 1 --json s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("stack10: 10 of 10 moving bodies asleep"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("after a 2 s warm-up"), std::string::npos) << result.out;
    const nlohmann::json json = nlohmann::json::parse(readFile(work() / "s.json"));
    EXPECT_EQ(json.at(0).at("warm_up_frames"), 120);
    EXPECT_EQ(json.at(0).at("sleeping_bodies_per_frame"), 10.0);

    const Result awake = substep("bench stack10 --seconds 0.1 --repeats 1 --json a.json");
    ASSERT_EQ(awake.exitCode, 0) << awake.err;
    EXPECT_FALSE(nlohmann::json::parse(readFile(work() / "a.json")).at(0).contains("sleeping_bodies_per_frame"));
}

TEST_F(BenchCommand, UnknownSceneExits2AndWritesNothing) {
    const Result result = substep(std::string("bench boxes3 no_such_scene --json b.json") + kQuick);
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("no_such_scene"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << "nothing runs before every scene is known:\n" << result.out;
    EXPECT_TRUE(workIsEmpty());
}

TEST_F(BenchCommand, BadOptionsExit2AndWriteNothing) {
    for (const char* options : {"--repeats 0", "--repeats -1", "--repeats 101", "--repeats 1.5",
                                "--repeats x", "--repeats 99999999999999999999", "--seconds 0",
                                "--seconds -1", "--seconds nan", "--seconds inf", "--seconds 1e999",
                                "--seconds 3601", "--seconds x", "--warm-up -1", "--warm-up nan",
                                "--warm-up 3601", "--warm-up x", "--no-such-option"}) {
        const Result result = substep(std::string("bench boxes3 --json b.json ") + options);
        EXPECT_EQ(result.exitCode, 2) << options;
        EXPECT_FALSE(result.err.empty()) << options;
    }
    EXPECT_TRUE(workIsEmpty());
}

TEST_F(BenchCommand, UnwritableJsonExits2BeforeRunning) {
    const Result result = substep(std::string("bench boxes3 --json missing/b.json") + kQuick);
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("missing/b.json"), std::string::npos) << result.err;
    EXPECT_TRUE(workIsEmpty());
}

}  // namespace
}  // namespace substep

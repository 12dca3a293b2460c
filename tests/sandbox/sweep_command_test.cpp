// Tests sandbox/sweep_command.cpp by running the built `substep sweep` (splits, CSV contract,
// exit codes, nothing written on bad input, the plot), and sandbox/error_measures.cpp directly.
// No timing assertions: ms_per_frame is only checked to be a positive number.

#include "sweep_command.h"
#include "error_measures.h"
#include "command_test_support.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace substep {
namespace {

using command_test::CommandTest;
using command_test::lines;
using command_test::readFile;
using command_test::Result;
namespace fs = std::filesystem;

/// Cells of a CSV line, keeping empty ones (a trailing blank cell included).
std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells(1);
    for (const char c : line) {
        if (c == ',')
            cells.emplace_back();
        else
            cells.back() += c;
    }
    return cells;
}

/// A sweep CSV read back: the header's columns and one map-like row per split.
struct SweepTable {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;

    std::string cell(std::size_t row, const std::string& column) const {
        const auto it = std::find(header.begin(), header.end(), column);
        return rows.at(row).at(static_cast<std::size_t>(it - header.begin()));
    }
    double number(std::size_t row, const std::string& column) const {
        return std::strtod(cell(row, column).c_str(), nullptr);
    }
    std::string splitName(std::size_t row) const {
        return cell(row, "substeps") + "x" + cell(row, "iterations");
    }
};

SweepTable readSweep(const fs::path& path) {
    const std::vector<std::string> text = lines(readFile(path));
    SweepTable table;
    if (text.empty()) return table;
    table.header = split(text[0]);
    for (std::size_t i = 1; i < text.size(); ++i)
        table.rows.push_back(split(text[i]));
    return table;
}

bool matplotlibAvailable() {
    return std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0;
}

/// Each test runs the program in its own empty working folder (command_test_support.h).
class SweepCommand : public CommandTest {};

TEST_F(SweepCommand, EverySplitOfTheBudgetWithTheContractHeader) {
    const Result result = substep("sweep pendulum3 --budget 4 --seconds 0.2 --csv out.csv");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::vector<std::string> text = lines(readFile(work() / "out.csv"));
    ASSERT_EQ(text.size(), 4u) << "header and one row per split";
    EXPECT_EQ(text[0],
              "budget,substeps,iterations,ms_per_frame,energy_drift,energy_error_final,"
              "max_joint_error,mean_joint_error,chain_elongation,penetration");
    EXPECT_EQ(text[0], kSweepCsvHeader);

    const SweepTable table = readSweep(work() / "out.csv");
    const std::vector<std::string> expected = {"4x1", "2x2", "1x4"};
    for (std::size_t row = 0; row < expected.size(); ++row) {
        ASSERT_EQ(table.rows[row].size(), table.header.size()) << "row " << row;
        EXPECT_EQ(table.cell(row, "budget"), "4");
        EXPECT_EQ(table.splitName(row), expected[row]);
        EXPECT_GT(table.number(row, "ms_per_frame"), 0.0);
        EXPECT_GT(table.number(row, "energy_drift"), 0.0);
        EXPECT_GE(table.number(row, "energy_drift"), table.number(row, "energy_error_final"));
        EXPECT_GE(table.number(row, "max_joint_error"), table.number(row, "mean_joint_error"));
        EXPECT_EQ(table.cell(row, "chain_elongation"), "") << "pendulum3 has no chain measure";
        EXPECT_EQ(table.cell(row, "penetration"), "0") << "no contacts yet";
    }
}

// The paper's claim (Fig. 9, ERRATA item 8): at equal cost, substeps damp less than iterations.
TEST_F(SweepCommand, MoreSubstepsDriftLessThanMoreIterations) {
    const Result result = substep("sweep pendulum3 --budget 4 --seconds 0.2 --csv out.csv");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const SweepTable table = readSweep(work() / "out.csv");
    ASSERT_EQ(table.rows.size(), 3u);
    ASSERT_EQ(table.splitName(0), "4x1");
    ASSERT_EQ(table.splitName(2), "1x4");
    EXPECT_LT(table.number(0, "energy_drift"), table.number(2, "energy_drift"));
    EXPECT_LT(table.number(0, "energy_drift"), table.number(1, "energy_drift"));
}

// --joint-projection start (issue 17): the start-direction projection keeps the pendulum's
// energy, so over 2 s at 20 substeps it drifts far less than the paper's form; a bad value
// exits 2 naming the option, and nothing is written.
TEST_F(SweepCommand, JointProjectionOptionChoosesTheProjection) {
    ASSERT_EQ(substep("sweep pendulum3 --budget 20 --seconds 2 --csv paper.csv").exitCode, 0);
    const Result start =
        substep("sweep pendulum3 --budget 20 --seconds 2 --csv start.csv --joint-projection start");
    ASSERT_EQ(start.exitCode, 0) << start.err;
    const SweepTable paper = readSweep(work() / "paper.csv");
    const SweepTable kept = readSweep(work() / "start.csv");
    ASSERT_EQ(paper.splitName(0), "20x1");
    ASSERT_EQ(kept.splitName(0), "20x1");
    EXPECT_LT(10.0 * kept.number(0, "energy_error_final"), paper.number(0, "energy_error_final"));
    const Result bad = substep("sweep pendulum3 --budget 2 --csv bad.csv --joint-projection shake");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("--joint-projection: expected paper or start, got 'shake'"),
              std::string::npos)
        << bad.err;
    EXPECT_FALSE(std::filesystem::exists(work() / "bad.csv"));
}

TEST_F(SweepCommand, ChainSceneReportsItsElongation) {
    const Result result = substep("sweep chain100 --budget 2 --seconds 0.2 --csv out.csv");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const SweepTable table = readSweep(work() / "out.csv");
    ASSERT_EQ(table.rows.size(), 2u);
    for (std::size_t row = 0; row < table.rows.size(); ++row) {
        ASSERT_FALSE(table.cell(row, "chain_elongation").empty());
        const double elongation = table.number(row, "chain_elongation");
        EXPECT_TRUE(std::isfinite(elongation));
        EXPECT_GT(elongation, 0.0) << "a hanging chain stretches under its weight";
    }
    // Fig. 11: the substep split stretches less.
    EXPECT_LT(table.number(0, "chain_elongation"), table.number(1, "chain_elongation"));
}

TEST_F(SweepCommand, BudgetsAreSortedAndEachSplitOnce) {
    const Result result = substep("sweep pendulum3 --budgets 2,1,2 --seconds 0.1 --csv out.csv");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const SweepTable table = readSweep(work() / "out.csv");
    std::vector<std::string> splits;
    for (std::size_t row = 0; row < table.rows.size(); ++row)
        splits.push_back(table.cell(row, "budget") + ":" + table.splitName(row));
    EXPECT_EQ(splits, (std::vector<std::string>{"1:1x1", "2:2x1", "2:1x2"}));
}

TEST_F(SweepCommand, ErrorMeasuresAreDeterministic) {
    ASSERT_EQ(substep("sweep pendulum3 --budget 2 --seconds 0.2 --csv a.csv").exitCode, 0);
    ASSERT_EQ(substep("sweep pendulum3 --budget 2 --seconds 0.2 --csv b.csv").exitCode, 0);
    const SweepTable a = readSweep(work() / "a.csv");
    const SweepTable b = readSweep(work() / "b.csv");
    ASSERT_EQ(a.rows.size(), b.rows.size());
    for (std::size_t row = 0; row < a.rows.size(); ++row) {
        for (const std::string& column : a.header) {
            if (column == "ms_per_frame") continue;  // the one measured, not computed, column
            EXPECT_EQ(a.cell(row, column), b.cell(row, column)) << column << ", row " << row;
        }
    }
}

TEST_F(SweepCommand, BadInputExits2AndWritesNothing) {
    for (const char* arguments :
         {"sweep pendulum3 --budget 0", "sweep pendulum3 --budget 10001",
          "sweep pendulum3 --budget 4.5", "sweep pendulum3 --budget -3",
          "sweep pendulum3 --budget 99999999999999999999", "sweep pendulum3 --budgets 10,,20",
          "sweep pendulum3 --budgets 10,", "sweep pendulum3 --budgets 0,10", "sweep pendulum3",
          "sweep pendulum3 --budget 4 --seconds 0", "sweep pendulum3 --budget 4 --seconds -1",
          "sweep pendulum3 --budget 4 --seconds nan", "sweep pendulum3 --budget 4 --seconds inf",
          "sweep pendulum3 --budget 4 --seconds 1e-9", "sweep no_such_scene --budget 4",
          "sweep --budget 4"}) {
        const Result result = substep(std::string(arguments) + " --csv out.csv --plot out.png");
        EXPECT_EQ(result.exitCode, 2) << arguments;
        EXPECT_FALSE(result.err.empty()) << arguments;
        EXPECT_TRUE(workEntries().empty()) << arguments;
    }
}

TEST_F(SweepCommand, UnwritableOutputExits2BeforeSweeping) {
    const Result result = substep("sweep pendulum3 --budget 4 --csv missing/out.csv");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("missing/out.csv"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << "nothing was swept";
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SweepCommand, PlotWritesAPng) {
    if (!matplotlibAvailable()) GTEST_SKIP() << "/usr/bin/python3 with matplotlib is not installed";
    const Result result =
        substep("sweep pendulum3 --budgets 2,4 --seconds 0.2 --csv out.csv --plot out.png");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::string png = readFile(work() / "out.png");
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(workEntries(), (std::vector<std::string>{"out.csv", "out.png"}))
        << "no temporary file left";
}

TEST_F(SweepCommand, PlotWithoutCsvLeavesOnlyThePng) {
    if (!matplotlibAvailable()) GTEST_SKIP() << "/usr/bin/python3 with matplotlib is not installed";
    const Result result = substep("sweep pendulum3 --budget 2 --seconds 0.1 --plot out.png");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(workEntries(), std::vector<std::string>{"out.png"});
}

TEST_F(SweepCommand, MissingPlotterStillWritesTheCsvAndExits2) {
    const Result result =
        substep("sweep pendulum3 --budget 2 --seconds 0.1 --csv out.csv --plot out.png",
                "SUBSTEP_PYTHON=/nonexistent/python3");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("/nonexistent/python3"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("python3-matplotlib"), std::string::npos) << result.err;
    EXPECT_EQ(workEntries(), std::vector<std::string>{"out.csv"});
    EXPECT_EQ(readSweep(work() / "out.csv").rows.size(), 2u);
}

// --- error_measures.cpp, in process --------------------------------------------------------------

SceneInstance builtin(const char* name) {
    return buildScene(findBuiltinScene(name)->build());
}

TEST(ErrorMeasures, ChainAtItsRestPoseHasNoElongationAndNoDrift) {
    const SceneInstance scene = builtin("chain100");
    ErrorRecorder recorder(scene, errorReference(findBuiltinScene("chain100"), scene));
    recorder.sample();
    const ErrorMeasures measures = recorder.measures();
    ASSERT_TRUE(measures.chainElongation.has_value());
    EXPECT_NEAR(*measures.chainElongation, 0.0, 1e-12);
    EXPECT_EQ(measures.energyDrift, 0.0);
    EXPECT_EQ(measures.energyErrorFinal, 0.0);
    EXPECT_NEAR(measures.maxJointError, 0.0, 1e-12);
    EXPECT_EQ(measures.penetration, 0.0);
}

TEST(ErrorMeasures, EnergyScaleIsTheEntrysOrTheWeightTimesOneMetre) {
    const SceneInstance pendulum = builtin("pendulum3");
    EXPECT_EQ(errorReference(findBuiltinScene("pendulum3"), pendulum).energyScale, 10.0);

    // chain100 gives no scale: 100 boxes of 1 kg under g = 10 weigh 1000 N.
    const SceneInstance chain = builtin("chain100");
    EXPECT_NEAR(errorReference(findBuiltinScene("chain100"), chain).energyScale, 1000.0,
                1e-9);
    // A scene file has no entry: the same weight rule, and no chain.
    const ErrorReference reference = errorReference(nullptr, chain);
    EXPECT_NEAR(reference.energyScale, 1000.0, 1e-9);
    EXPECT_TRUE(reference.chain.endBody.empty());
}

TEST(ErrorMeasures, FollowTheirDefinitionsOverARun) {
    SceneDescription description = findBuiltinScene("pendulum3")->build();
    description.substeps = 5;
    SceneInstance scene = buildScene(description);
    ErrorRecorder recorder(scene, {.energyScale = 10.0});
    recorder.sample();
    const double initial = scene.world().energies().total();
    double largestChange = 0.0;
    // Every joint of pendulum3 is named, so the named ones are all of them.
    auto meanJointError = [&] {
        double sum = 0.0;
        for (const auto& [name, id] : scene.namedJointIds())
            sum += scene.world().jointReadout(id).error;
        return sum / static_cast<double>(scene.namedJointIds().size());
    };
    double meanSum = meanJointError();
    double largestError = scene.world().maxJointError();
    for (int frame = 1; frame <= 30; ++frame) {
        scene.physics().step(description.dt);
        recorder.sample();
        largestChange = std::max(largestChange, std::abs(scene.world().energies().total() - initial));
        meanSum += meanJointError();
        largestError = std::max(largestError, scene.world().maxJointError());
    }
    const ErrorMeasures measures = recorder.measures();
    EXPECT_EQ(recorder.sampleCount(), 31u);
    EXPECT_DOUBLE_EQ(measures.energyDrift, largestChange / 10.0);
    EXPECT_DOUBLE_EQ(measures.energyErrorFinal,
                     std::abs(scene.world().energies().total() - initial) / 10.0);
    EXPECT_DOUBLE_EQ(measures.maxJointError, largestError);
    EXPECT_NEAR(measures.meanJointError, meanSum / 31.0, 1e-15);
    EXPECT_FALSE(measures.chainElongation.has_value());
}

}  // namespace
}  // namespace substep

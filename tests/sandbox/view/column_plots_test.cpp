// Tests sandbox/view/column_plots.{h,cpp}: the window's plots of CSV columns hold, frame for
// frame, the values `substep run --csv` writes (the same sampling code, rounded to float), for
// bodies, joints, energies and soft bodies; they follow the timeline when scrubbed back and
// resumed; a restart and a switch to compare mode keep the chosen columns.

#include "../command_test_support.h"

#include "view/compare_session.h"
#include "view/view_session.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>

namespace substep::command_test {
namespace {

/// The CSV's rows by frame, each a map from column name to value.
std::vector<std::map<std::string, double>> readCsv(const std::string& text) {
    const std::vector<std::string> rows = lines(text);
    std::vector<std::map<std::string, double>> table;
    if (rows.empty()) return table;
    std::vector<std::string> header;
    std::istringstream names(rows[0]);
    for (std::string name; std::getline(names, name, ',');) header.push_back(name);
    for (std::size_t r = 1; r < rows.size(); ++r) {
        std::istringstream cells(rows[r]);
        std::map<std::string, double> row;
        std::size_t column = 0;
        for (std::string cell; std::getline(cells, cell, ',') && column < header.size(); ++column)
            row[header[column]] = std::stod(cell);
        table.push_back(std::move(row));
    }
    return table;
}

/// The first column of `plots` whose name ends with `suffix` (".vy", ".force"), or "".
std::string columnEndingWith(const view::ColumnPlots& plots, const std::string& suffix) {
    for (const std::string& column : plots.columns())
        if (column.size() > suffix.size() && column.compare(column.size() - suffix.size(), suffix.size(), suffix) == 0)
            return column;
    return "";
}

class ColumnPlotsTest : public CommandTest {
  protected:
    /// Plots `columns` in a viewer run of `scene`, steps it `frames` frames and checks every
    /// plot's samples against `run SCENE --csv` frame by frame.
    void expectPlotsMatchTheCsv(const std::string& scene, const std::vector<std::string>& suffixes, int frames) {
        const Result run = substep("run " + quoted(scene) + " --frames " + std::to_string(frames) + " --csv run.csv");
        ASSERT_EQ(run.exitCode, 0) << run.err;
        const auto csv = readCsv(readFile(work() / "run.csv"));
        ASSERT_EQ(csv.size(), static_cast<std::size_t>(frames + 1));

        view::ViewSession session(resolveScene(scene), 16.0f / 9.0f);
        view::ColumnPlots& plots = session.columnPlots();
        EXPECT_EQ(plots.columns().size() + 1, csv[0].size()) << "every CSV column but `frame`";
        std::vector<std::string> chosen;
        for (const std::string& suffix : suffixes) {
            const std::string column = suffix.front() == '.' ? columnEndingWith(plots, suffix) : suffix;
            ASSERT_FALSE(column.empty()) << scene << " has no column ending " << suffix;
            ASSERT_TRUE(plots.add(column)) << column;
            chosen.push_back(column);
        }
        EXPECT_FALSE(plots.add(chosen[0])) << "plotted already";
        EXPECT_FALSE(plots.add("no_such.column"));
        for (int frame = 1; frame <= frames; ++frame) {
            session.stepOnce();
            for (const view::ColumnPlots::Plot& plot : plots.plots()) {
                ASSERT_EQ(plots.shownCount(plot), static_cast<std::size_t>(frame));
                EXPECT_EQ(plot.history.latest(), static_cast<float>(csv[frame].at(plot.column)))
                    << scene << " " << plot.column << " at frame " << frame;
            }
        }
    }
};

TEST_F(ColumnPlotsTest, PlottedBodyJointAndEnergyColumnsEqualTheCsvAtEveryFrame) {
    expectPlotsMatchTheCsv("pendulum3", {".vy", ".wz", ".force", ".error", "energy", "kinetic", "t"}, 60);
}

TEST_F(ColumnPlotsTest, PlottedSoftBodyColumnsEqualTheCsvAtEveryFrame) {
    const fs::path scene = fs::path(SUBSTEP_ASSETS) / "scenes" / "soft_bodies.json";
    expectPlotsMatchTheCsv(scene.string(), {".volume", ".y", ".ey"}, 30);
}

TEST_F(ColumnPlotsTest, PlotsFollowTheTimelineAndAResumedRunReplacesTheLaterSamples) {
    view::ViewSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    ASSERT_TRUE(session.canRewind());
    view::ColumnPlots& plots = session.columnPlots();
    const std::string column = columnEndingWith(plots, ".vx");
    ASSERT_TRUE(plots.add(column));
    std::vector<float> first;
    for (int frame = 1; frame <= 30; ++frame) {
        session.stepOnce();
        first.push_back(plots.plots()[0].history.latest());
    }
    // Scrubbed back to frame 20: the plot ends there, its last shown sample that of frame 20.
    ASSERT_TRUE(session.scrubTo(20));
    const view::ColumnPlots::Plot& plot = plots.plots()[0];
    ASSERT_EQ(plots.shownCount(plot), 20u);
    EXPECT_EQ(view::ColumnPlots::sampleAt(plot, 19), first[19]);
    // Forward again to 25 without stepping: the kept samples show again.
    ASSERT_TRUE(session.scrubTo(25));
    EXPECT_EQ(plots.shownCount(plot), 25u);
    // Resumed from 25: the samples after it are replaced by the rerun's, which are the same.
    session.stepOnce();
    EXPECT_EQ(plot.history.count(), 26u);
    EXPECT_EQ(plots.shownCount(plot), 26u);
    EXPECT_EQ(plot.history.latest(), first[25]);
    // A restart keeps the column and starts its samples afresh from the initial state (the
    // CSV's row 0), then replays the run.
    session.restart();
    ASSERT_EQ(plots.plots().size(), 1u);
    EXPECT_EQ(plots.plots()[0].column, column);
    EXPECT_EQ(plots.plots()[0].history.count(), 1u);
    session.stepOnce();
    EXPECT_EQ(plots.plots()[0].history.count(), 2u);
    EXPECT_EQ(plots.plots()[0].history.latest(), first[0]);
}

TEST_F(ColumnPlotsTest, CompareModeKeepsThePlottedColumnsInBothRuns) {
    view::CompareSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    ASSERT_TRUE(session.first().columnPlots().add("energy"));
    session.compare(view::kPaperCompareSplits);
    ASSERT_EQ(session.runCount(), 2u);
    for (std::size_t index = 0; index < 2; ++index) {
        ASSERT_EQ(session.run(index).columnPlots().plots().size(), 1u);
        EXPECT_EQ(session.run(index).columnPlots().plots()[0].column, "energy");
    }
    session.compare(std::nullopt);
    ASSERT_EQ(session.first().columnPlots().plots().size(), 1u);
}

TEST(PlotHistoryTest, DropNewestAndAtCountFromTheOldestAcrossTheWrap) {
    view::PlotHistory history(4);
    for (int i = 1; i <= 6; ++i) history.push(static_cast<float>(i));  // holds 3 4 5 6
    ASSERT_EQ(history.count(), 4u);
    EXPECT_EQ(history.at(0), 3.0f);
    EXPECT_EQ(history.at(3), 6.0f);
    history.dropNewest(3);  // holds 3
    EXPECT_EQ(history.count(), 1u);
    EXPECT_EQ(history.latest(), 3.0f);
    history.push(7.0f);
    EXPECT_EQ(history.at(0), 3.0f);
    EXPECT_EQ(history.at(1), 7.0f);
    history.dropNewest(10);
    EXPECT_EQ(history.count(), 0u);
    EXPECT_EQ(history.latest(), 0.0f);
}

}  // namespace
}  // namespace substep::command_test

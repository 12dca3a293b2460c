// Tests sandbox/capture/golden_files.cpp: goldens written only when their bytes change, stale
// ones removed by name pattern only, and missing or damaged ones reported with what to do.

#include "capture/golden_files.h"

#include "capture/json_input.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace substep::capture {
namespace {

namespace fs = std::filesystem;

class GoldenFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() / ("golden_files_test_" + std::to_string(getpid()));
        fs::remove_all(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }

    std::string path(const std::string& name) const { return (folder_ / name).string(); }
    std::string read(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }

    fs::path folder_;
};

TEST_F(GoldenFiles, WritesCreatingFoldersAndOnlyWhenTheBytesChange) {
    const std::string file = path("capture/frame_00001.json");
    EXPECT_EQ(writeGolden(file, "one"), GoldenChange::Added);
    EXPECT_EQ(read("capture/frame_00001.json"), "one");
    const auto written = fs::last_write_time(file);
    EXPECT_EQ(writeGolden(file, "one"), GoldenChange::Unchanged);
    EXPECT_EQ(fs::last_write_time(file), written);
    EXPECT_EQ(writeGolden(file, "two"), GoldenChange::Changed);
    EXPECT_EQ(read("capture/frame_00001.json"), "two");
    // No temporary file is left beside it.
    EXPECT_EQ(std::distance(fs::directory_iterator(folder_ / "capture"), fs::directory_iterator()),
              1);
}

TEST_F(GoldenFiles, RemovesOnlyStaleFilesThatLookLikeGoldens) {
    for (const char* name : {"frame_00001.json", "frame_00001.png", "frame_00002.json",
                             "digest.txt", "notes.md", "frame_00003.txt"}) {
        writeGolden(path(std::string("c/") + name), "x");
    }
    const std::vector<std::string> removed =
        removeStaleGoldens(path("c"), {"frame_00001.json", "frame_00001.png"});
    EXPECT_EQ(removed,
              (std::vector<std::string>{path("c/digest.txt"), path("c/frame_00002.json")}));
    EXPECT_TRUE(fs::exists(path("c/notes.md")));
    EXPECT_TRUE(fs::exists(path("c/frame_00003.txt")));
    EXPECT_TRUE(fs::exists(path("c/frame_00001.png")));
    EXPECT_TRUE(removeStaleGoldens(path("missing"), {}).empty());
}

TEST_F(GoldenFiles, MissingAndDamagedGoldensSayWhatToDo) {
    const auto errorOf = [](const std::function<void()>& read) {
        try {
            read();
        } catch (const std::exception& error) {
            return std::string(error.what());
        }
        return std::string("(no error)");
    };
    const std::string missing = path("c/frame_00001.json");
    EXPECT_EQ(errorOf([&] { readGoldenState(missing, "s.json"); }),
              missing + ": no such golden; run `substep capture s.json --update` to make it");
    writeGolden(path("c/frame_00001.png"), "not a png");
    const std::string png = errorOf([&] { readGoldenImage(path("c/frame_00001.png"), "s.json"); });
    EXPECT_EQ(png.rfind(path("c/frame_00001.png") + ": cannot be decoded (", 0), 0u) << png;
    EXPECT_NE(png.find("run `substep capture s.json --update` to make it again"),
              std::string::npos);
    writeGolden(path("c/digest.txt"), "fnv1a64 0123456789abcdef frames 0-9\nextra\n");
    EXPECT_NE(errorOf([&] {
                  readGoldenDigest(path("c/digest.txt"), "s.json");
              }).find("not a digest line"),
              std::string::npos);
    EXPECT_EQ(stateFileName(7), "frame_00007.json");
    EXPECT_EQ(imageFileName(123456), "frame_123456.png");
}

}  // namespace
}  // namespace substep::capture

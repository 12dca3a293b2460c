// sandbox/view/screenshot.cpp: the P key's file names, in the working folder, never written over.

#include "view/screenshot.h"

#include "render/png_codec.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace substep::view {
namespace {

class ScreenshotTest : public ::testing::Test {
  protected:
    void SetUp() override {
        folder_ = std::filesystem::temp_directory_path() /
                  ("substep_screenshot_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                   "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(folder_);
        std::filesystem::create_directories(folder_);
    }
    void TearDown() override { std::filesystem::remove_all(folder_); }
    std::filesystem::path folder_;
};

TEST_F(ScreenshotTest, NamedAfterSceneAndFrameAndNeverOverwritten) {
    EXPECT_EQ(screenshotPath(folder_, "cradle", 120), folder_ / "substep_cradle_f120.png");
    // A scene file: its name without folders or extension, odd characters replaced.
    EXPECT_EQ(screenshotPath(folder_, "assets/scenes/my scene.json", 0), folder_ / "substep_my_scene_f0.png");

    const render::Image image{2, 1, {255, 0, 0, 255, 0, 0, 255, 255}};
    const std::filesystem::path first = screenshotPath(folder_, "cradle", 120);
    saveScreenshot(image, first);
    const std::filesystem::path second = screenshotPath(folder_, "cradle", 120);
    EXPECT_EQ(second, folder_ / "substep_cradle_f120_2.png");
    saveScreenshot(image, second);
    EXPECT_EQ(screenshotPath(folder_, "cradle", 120), folder_ / "substep_cradle_f120_3.png");

    std::ifstream file(first, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const render::Image back = render::decodePng(bytes);
    EXPECT_EQ(back.width, 2);
    EXPECT_EQ(back.rgba, image.rgba);
}

}  // namespace
}  // namespace substep::view

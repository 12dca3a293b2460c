// Tests sandbox/capture/capture_report.cpp: the HTML page and the images it shows.

#include "capture/capture_report.h"

#include "render/png_codec.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace substep::capture {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

render::Image flat(uint8_t level) {
    render::Image image{.width = 2, .height = 2};
    image.rgba.assign(16, level);
    return image;
}

TEST(CaptureReport, ShowsEachMismatchWithItsImagesAndStateTable) {
    const fs::path folder =
        fs::temp_directory_path() / ("capture_report_test_" + std::to_string(getpid()));
    fs::remove_all(folder);

    CaptureResult differs{.name = "drop", .scene = "drop.json", .checked = true};
    differs.lines.push_back("drop frame 3: state: body <b> & co");
    FrameMismatch mismatch{.frame = 3, .pixelTolerance = 8, .maxFraction = 0.01};
    mismatch.image = ImageComparison{.differing = 4, .pixels = 4, .largest = 90};
    mismatch.golden = flat(10);
    mismatch.fresh = flat(100);
    StateComparison state;
    state.outOfTolerance = 1;
    state.compared = 30;
    state.differences.push_back(
        {.what = "bodies[0] \"<b>\".position[1]", .golden = 0.5, .fresh = 0.75, .allowed = 0.0});
    mismatch.state = state;
    differs.frames.push_back(mismatch);
    const CaptureResult matches{.name = "calm", .scene = "boxes3", .checked = true};
    const CaptureResult skipped{.name = "skipped", .scene = "cradle", .checked = false};

    writeCaptureReport(folder.string(), "s.json", {differs, matches, skipped});
    const std::string html = readFile(folder / "index.html");
    EXPECT_NE(html.find("2 captures checked, 1 differs."), std::string::npos) << html;
    EXPECT_NE(html.find("<li class=bad>drop frame 3: state: body &lt;b&gt; &amp; co</li>"),
              std::string::npos);
    EXPECT_NE(html.find("calm</a> (boxes3): <span class=ok>matches"), std::string::npos);
    EXPECT_EQ(html.find("skipped"), std::string::npos) << "--only left it out";
    EXPECT_NE(
        html.find("<td>bodies[0] &quot;&lt;b&gt;&quot;.position[1]</td><td>0.5</td><td>0.75</td>"
                  "<td>0.25</td><td>0</td>"),
        std::string::npos)
        << html;
    EXPECT_EQ(render::decodePng(readFile(folder / "drop/frame_00003_golden.png")).rgba,
              flat(10).rgba);
    EXPECT_EQ(render::decodePng(readFile(folder / "drop/frame_00003_new.png")).rgba,
              flat(100).rgba);
    // Every pixel differs by 90 > 8: the heat map is red to yellow there, never the dimmed golden.
    const render::Image heat = render::decodePng(readFile(folder / "drop/frame_00003_diff.png"));
    EXPECT_EQ(heat.pixel(1, 1)[0], 255);
    EXPECT_EQ(heat.pixel(1, 1)[2], 0);
    fs::remove_all(folder);
}

}  // namespace
}  // namespace substep::capture

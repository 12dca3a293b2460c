// Tests sandbox/render_command.cpp: `substep render` end to end (the built program, headless),
// its option parsing, and the golden images under assets/golden/.

#include "render_command.h"

#include "../sandbox/command_test_support.h"
#include "command_options.h"
#include "render/png_codec.h"
#include "render_test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace substep {
namespace {

using command_test::CommandTest;
using command_test::readFile;
namespace fs = std::filesystem;

const fs::path kGoldenFolder = fs::path(SUBSTEP_SOURCE_DIR) / "assets" / "golden";

/// Skips the test when the program could make no OpenGL context on this machine.
#define SKIP_WITHOUT_OPENGL(result)                                                    \
    if ((result).exitCode == 2 && (result).err.find("no headless OpenGL") != std::string::npos) \
    GTEST_SKIP() << (result).err

TEST(RenderOptions, FrameListsTakeSingleFramesAndRanges) {
    EXPECT_EQ(parseFrameList("0,40,120"), (std::vector<long long>{0, 40, 120}));
    EXPECT_EQ(parseFrameList("120,0,40,40"), (std::vector<long long>{0, 40, 120}));
    EXPECT_EQ(parseFrameList("3-6"), (std::vector<long long>{3, 4, 5, 6}));
    EXPECT_EQ(parseFrameList("0-100:40,7"), (std::vector<long long>{0, 7, 40, 80}));
    for (const char* bad : {"", "x", "5-2", "1,,2", "-1", "0-10:0", "1:2", "0-5-9", "0-99999999999"}) {
        EXPECT_THROW(parseFrameList(bad), UsageError) << bad;
    }
    EXPECT_THROW(parseFrameList("0-10000000"), UsageError);  // too many images
}

TEST(RenderOptions, SizeIsWidthByHeight) {
    EXPECT_EQ(parseImageSize("1280x720"), (std::pair<int, int>{1280, 720}));
    EXPECT_EQ(parseImageSize("1x1"), (std::pair<int, int>{1, 1}));
    for (const char* bad : {"", "1280", "0x10", "10x0", "-5x5", "axb", "1280x720x2", "99999x10", "10 x10"}) {
        EXPECT_THROW(parseImageSize(bad), UsageError) << bad;
    }
}

TEST(RenderOptions, FilesAreNamedByFrame) {
    EXPECT_EQ(frameFileName(40), "frame_00040.png");
    EXPECT_EQ(frameFileName(1234567), "frame_1234567.png");
}

class RenderCommandTest : public CommandTest {};

TEST_F(RenderCommandTest, BadSizeExitsTwoAndWritesNothing) {
    for (const char* size : {"0x120", "160", "axb", "100000x100"}) {
        const command_test::Result result = substep(std::string("render boxes3 --frames 0 --out out --size ") + size);
        EXPECT_EQ(result.exitCode, 2) << size;
        EXPECT_NE(result.err.find("--size"), std::string::npos) << result.err;
        EXPECT_TRUE(workEntries().empty()) << size;
    }
}

TEST_F(RenderCommandTest, BadFramesOrSceneExitTwoAndWriteNothing) {
    command_test::Result result = substep("render boxes3 --frames 9-2 --out out");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("--frames"), std::string::npos) << result.err;
    result = substep("render no_such_scene --frames 0 --out out");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("no_such_scene"), std::string::npos) << result.err;
    result = substep("render boxes3 --out out");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(RenderCommandTest, OutThatIsAFileExitsTwo) {
    std::ofstream(work() / "taken") << "x";
    const command_test::Result result = substep("render boxes3 --frames 0 --out taken --size 32x24");
    SKIP_WITHOUT_OPENGL(result);
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("--out"), std::string::npos) << result.err;
}

TEST_F(RenderCommandTest, WritesEachListedFrameAtItsSize) {
    const command_test::Result result = substep("render boxes3 --frames 0,40 --out out --size 160x120");
    SKIP_WITHOUT_OPENGL(result);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("out"), std::string::npos) << "should say where the images are";
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(work() / "out")) files.push_back(entry.path().filename());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"frame_00000.png", "frame_00040.png"}));

    const render::Image first = render::decodePng(readFile(work() / "out" / "frame_00000.png"));
    const render::Image later = render::decodePng(readFile(work() / "out" / "frame_00040.png"));
    EXPECT_EQ(first.width, 160);
    EXPECT_EQ(first.height, 120);
    EXPECT_GT(render::test::distinctColours(first), 100u);
    // boxes3 starts at rest but with its springs' own oscillation: frame 40 has moved on.
    EXPECT_FALSE(first.rgba == later.rgba);
}

TEST_F(RenderCommandTest, SameFrameTwiceIsByteIdentical) {
    const command_test::Result a = substep("render pendula --frames 30 --out a --size 160x120");
    SKIP_WITHOUT_OPENGL(a);
    ASSERT_EQ(a.exitCode, 0) << a.err;
    ASSERT_EQ(substep("render pendula --frames 30 --out b --size 160x120").exitCode, 0);
    const std::string first = readFile(work() / "a" / "frame_00030.png");
    EXPECT_FALSE(first.empty());
    EXPECT_EQ(first, readFile(work() / "b" / "frame_00030.png"));
}

/// Renders SCENE at FRAME to 160x120 and compares it with assets/golden/GOLDEN. With
/// SUBSTEP_UPDATE_GOLDENS=1 in the environment the golden is rewritten instead.
void expectMatchesGolden(const fs::path& work, const command_test::Result& result, long long frame,
                         const std::string& golden) {
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const fs::path rendered = work / "out" / frameFileName(frame);
    if (const char* update = std::getenv("SUBSTEP_UPDATE_GOLDENS"); update && std::string(update) == "1") {
        fs::copy_file(rendered, kGoldenFolder / golden, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "updated " << (kGoldenFolder / golden);
    }
    const render::Image expected = render::decodePng(readFile(kGoldenFolder / golden));
    const render::Image actual = render::decodePng(readFile(rendered));
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    // Rasterisers differ in the last bits of edges and gradients (another CPU's llvmpipe, OSMesa):
    // allow small differences everywhere and larger ones on a few edge pixels.
    EXPECT_LT(render::test::fractionDiffering(actual, expected, 12), 0.02) << golden;
    EXPECT_LT(render::test::fractionDiffering(actual, expected, 64), 0.005) << golden;
}

TEST_F(RenderCommandTest, Boxes3AtFrame40MatchesItsGolden) {
    const command_test::Result result = substep("render boxes3 --frames 40 --out out --size 160x120");
    SKIP_WITHOUT_OPENGL(result);
    expectMatchesGolden(work(), result, 40, "boxes3_frame40.png");
}

TEST_F(RenderCommandTest, StillLifeMatchesItsGolden) {
    const std::string scene = command_test::quoted((kGoldenFolder / "still_life.json").string());
    const command_test::Result result = substep("render " + scene + " --frames 0 --out out --size 160x120");
    SKIP_WITHOUT_OPENGL(result);
    expectMatchesGolden(work(), result, 0, "still_life_frame0.png");
}

TEST_F(RenderCommandTest, FallsBackToOsMesaWhenEglHasNoDriver) {
    // GLVND's libEGL finds no vendor library: EGL fails as on a machine without Mesa's EGL.
    const command_test::Result egl = substep("render boxes3 --frames 0 --out egl --size 160x120");
    SKIP_WITHOUT_OPENGL(egl);
    const command_test::Result osmesa = substep("render boxes3 --frames 0 --out osmesa --size 160x120",
                                                "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
    if (osmesa.exitCode == 2 && osmesa.err.find("libOSMesa is not installed") != std::string::npos) {
        GTEST_SKIP() << osmesa.err;
    }
    ASSERT_EQ(osmesa.exitCode, 0) << osmesa.err;
    EXPECT_NE(osmesa.out.find("OSMesa"), std::string::npos) << osmesa.out;
    // Both are Mesa's llvmpipe underneath: the pictures agree.
    const render::Image a = render::decodePng(readFile(work() / "egl" / "frame_00000.png"));
    const render::Image b = render::decodePng(readFile(work() / "osmesa" / "frame_00000.png"));
    EXPECT_LT(render::test::fractionDiffering(a, b, 12), 0.02);
}

TEST_F(RenderCommandTest, BackendCanBeChosen) {
    const command_test::Result result =
        substep("render boxes3 --frames 0 --out out --size 32x24", "SUBSTEP_GL_BACKEND=osmesa");
    SKIP_WITHOUT_OPENGL(result);
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("OSMesa"), std::string::npos) << result.out;
    const command_test::Result bad = substep("render boxes3 --frames 0 --out out2 --size 32x24", "SUBSTEP_GL_BACKEND=vulkan");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("SUBSTEP_GL_BACKEND"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(work() / "out2"));
}

}  // namespace
}  // namespace substep

// Tests the `substep` program against hostile and careless input (issue 19): inputs that are not
// regular files, outputs that collide with each other, the input or a device, empty values,
// one-line messages, the time-step bounds, the contact cap's warning and a prompt exit on SIGTERM
// inside a long frame. Each case failed before the fix it names.

#include "command_test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <string>
#include <thread>
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
const std::string kHang = quoted(kHangScene.string());

class SubstepHardening : public CommandTest {
  protected:
    /// Passes when the run exited 2 with exactly one line on stderr holding `fragment`.
    static ::testing::AssertionResult oneLineError(const Result& result, const std::string& fragment) {
        if (result.exitCode != 2)
            return ::testing::AssertionFailure() << "exit " << result.exitCode << ": " << result.err;
        if (lines(result.err).size() != 1)
            return ::testing::AssertionFailure() << "not one line: \"" << result.err << "\"";
        if (result.err.find(fragment) == std::string::npos)
            return ::testing::AssertionFailure() << "no \"" << fragment << "\" in " << result.err;
        return ::testing::AssertionSuccess();
    }

    /// A scene of `count` spheres created at one point, `substeps` per frame.
    void writePile(const fs::path& path, int count, int substeps) const {
        std::string text = R"({"substep_scene": 1, "substeps": )" + std::to_string(substeps) +
                           R"(, "bodies": [)";
        for (int i = 0; i < count; ++i) {
            text += std::string(i == 0 ? "" : ",") +
                    R"({"shape": {"type": "sphere", "radius": 0.1}, "position": [0, 1, 0]})";
        }
        std::ofstream(path) << text << "]}";
    }
};

TEST_F(SubstepHardening, NonRegularScenesAreRefusedAtOnce) {
    // Before: /dev/zero was read without end and a FIFO blocked forever.
    ASSERT_EQ(::mkfifo((work() / "fifo.json").c_str(), 0600), 0);
    for (const std::string& scene : {std::string("/dev/zero"), std::string("fifo.json")}) {
        const Result result = substep("run " + scene + " --frames 1 --csv out.csv");
        EXPECT_TRUE(oneLineError(result, scene + ": cannot read: not a regular file")) << scene;
    }
    EXPECT_EQ(workEntries(), std::vector<std::string>{"fifo.json"});
}

TEST_F(SubstepHardening, NonRegularOutputIsRefusedAndKept) {
    // Before: --csv onto a FIFO (or, as root, onto /dev/null) replaced it by a regular file.
    ASSERT_EQ(::mkfifo((work() / "pipe").c_str(), 0600), 0);
    const Result result = substep("run " + kHang + " --frames 2 --csv pipe");
    EXPECT_TRUE(oneLineError(result, "pipe: not a regular file"));
    EXPECT_TRUE(fs::is_fifo(work() / "pipe"));
    EXPECT_EQ(workEntries(), std::vector<std::string>{"pipe"});
}

TEST_F(SubstepHardening, OutputsMayNotCollideWithEachOtherOrTheInput) {
    Result result = substep("run " + kHang + " --frames 2 --csv x.out --json ./x.out");
    EXPECT_TRUE(oneLineError(result, "--json ./x.out: the same file as --csv"));
    EXPECT_TRUE(workEntries().empty());

    fs::copy_file(kHangScene, work() / "scene.json");
    const std::string before = readFile(work() / "scene.json");
    result = substep("run scene.json --frames 2 --csv scene.json");
    EXPECT_TRUE(oneLineError(result, "--csv scene.json: is an input of this command"));
    EXPECT_EQ(readFile(work() / "scene.json"), before);
    EXPECT_EQ(workEntries(), std::vector<std::string>{"scene.json"});
}

TEST_F(SubstepHardening, EmptyValuesAreUsageErrors) {
    // Before: an empty value read as "not given" and was ignored.
    for (const std::string& arguments :
         {"run " + kHang + " --frames ''", "run " + kHang + " --csv ''", "run " + kHang + " --json ''",
          "run " + kHang + " --dt ''", std::string("run ''"), std::string("bench hang --json ''"),
          "sweep " + kHang + " --budget 2 --csv ''"}) {
        const Result result = substep(arguments);
        EXPECT_TRUE(oneLineError(result, "empty")) << arguments;
    }
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SubstepHardening, UsageErrorsAndOddFileNamesGiveOneLine) {
    // Before: CLI11 printed its error and "Run with --help ..." on two lines.
    EXPECT_TRUE(oneLineError(substep("run " + kHang + " --no-such-option"), "--no-such-option"));
    EXPECT_TRUE(oneLineError(substep("frobnicate"), "frobnicate"));
    EXPECT_TRUE(oneLineError(substep("run " + kHang + " --frames"), "--frames"));
    // A newline in a file name is shown escaped.
    EXPECT_TRUE(oneLineError(substep("run 'a\nb.json'"), "a\\nb.json"));
    EXPECT_TRUE(oneLineError(substep("run " + kHang + " --frames 1 --csv 'no\nsuch/x.csv'"),
                             "no\\nsuch/x.csv"));
    EXPECT_TRUE(workEntries().empty());
}

TEST_F(SubstepHardening, TimeStepHasTheBoundsOfAFilesDt) {
    // Before: --dt 1e-320 and --dt 1e300 went NaN at frame 1.
    for (const char* dt : {"1e-320", "1e-7", "1e300", "1.5"}) {
        const Result result = substep("run " + kHang + " --frames 1 --dt " + dt);
        EXPECT_TRUE(oneLineError(result, "--dt")) << dt;
    }
    EXPECT_EQ(substep("run " + kHang + " --frames 1 --dt 1e-6").exitCode, 0);
    EXPECT_EQ(substep("run " + kHang + " --frames 1 --dt 1").exitCode, 0);
}

TEST_F(SubstepHardening, PiledBodiesWarnThatContactsAreCapped) {
    // 600 spheres at one point: 179700 candidate pairs, over the 131072 a frame keeps.
    writePile(work() / "pile.json", 600, 1);
    const Result result = substep("run pile.json --frames 1 --json s.json");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("warning: frame 1 found more than 131072 contact pairs; 48628 dropped"),
              std::string::npos)
        << result.err;
}

TEST_F(SubstepHardening, SigtermInsideALongFrameExitsPromptlyWithNothingWritten) {
    // Before: signals were checked between frames only; this frame takes minutes (300 spheres
    // at one point, 44850 pairs, 10000 substeps).
    writePile(work() / "pile.json", 300, 10000);
    const pid_t child = ::fork();
    if (child == 0) {
        if (::chdir(work().c_str()) != 0) ::_exit(99);
        ::execl(SUBSTEP_EXECUTABLE, "substep", "run", "pile.json", "--frames", "2", "--csv",
                "out.csv", "--json", "s.json", static_cast<char*>(nullptr));
        ::_exit(98);
    }
    ASSERT_GT(child, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // into the first frame
    ::kill(child, SIGTERM);
    // A generous bound, far below the frame's length: the test must not hang if it fails.
    int status = 0;
    pid_t done = 0;
    for (int wait = 0; wait < 300 && done == 0; ++wait) {
        done = ::waitpid(child, &status, WNOHANG);
        if (done == 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (done == 0) {
        ::kill(child, SIGKILL);
        ::waitpid(child, &status, 0);
        FAIL() << "still running 30 s after SIGTERM";
    }
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
    EXPECT_EQ(workEntries(), std::vector<std::string>{"pile.json"}) << "no output, no temporary file";
}

}  // namespace
}  // namespace substep

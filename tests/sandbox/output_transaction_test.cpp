// Tests sandbox/output_transaction.cpp: a command's outputs appear together or not at all, and
// outputs that name the same file as each other or as an input are refused.

#include "output_transaction.h"

#include "command_options.h"

#include "scratch_directory_test.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>
#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace substep {
namespace {

namespace fs = std::filesystem;

class OutputTransactionTest : public test::ScratchDirectoryTest {
  protected:
    std::string at(const std::string& name) const { return (directory_ / name).string(); }
};

TEST_F(OutputTransactionTest, AllOutputsAppearOnCommit) {
    {
        OutputTransaction outputs;
        outputs.add("--csv", at("a.csv")).write("a\n");
        outputs.add("--json", at("b.json")).write("{}\n");
        EXPECT_EQ(entries().size(), 2u) << "two temporary files, no target yet";
        EXPECT_FALSE(fs::exists(at("a.csv")));
        outputs.commit();
    }
    EXPECT_EQ(entries(), (std::vector<std::string>{"a.csv", "b.json"}));
    EXPECT_EQ(contents(at("a.csv")), "a\n");
}

TEST_F(OutputTransactionTest, OneFailedWriteLeavesEveryTargetAsItWas) {
    // Before: `run --csv A --json B` committed A before B failed. A file-size limit makes the
    // second output's write fail (EFBIG) where a full disk would.
    std::ofstream(at("a.csv")) << "previous\n";
    struct rlimit previous {};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &previous), 0);
    const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = previous;
    limit.rlim_cur = 1 << 16;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
    bool threw = false;
    {
        OutputTransaction outputs;
        outputs.add("--csv", at("a.csv")).write("new\n");
        outputs.add("--json", at("b.json")).write(std::string(1 << 17, 'x'));
        try {
            outputs.commit();
        } catch (const OutputError& error) {
            threw = true;
            EXPECT_NE(std::string(error.what()).find("b.json: cannot write"), std::string::npos)
                << error.what();
        }
    }
    ::setrlimit(RLIMIT_FSIZE, &previous);
    std::signal(SIGXFSZ, previousHandler);
    EXPECT_TRUE(threw);
    EXPECT_EQ(entries(), std::vector<std::string>{"a.csv"}) << "no temporary file left either";
    EXPECT_EQ(contents(at("a.csv")), "previous\n");
}

TEST_F(OutputTransactionTest, WithoutCommitNothingAppears) {
    {
        OutputTransaction outputs;
        outputs.add("--out", at("frame_00000.png")).write("png");
        outputs.add("--out", at("frame_00001.png")).write("png");
    }
    EXPECT_TRUE(entries().empty());
}

TEST_F(OutputTransactionTest, TheSameFileTwiceIsRefused) {
    fs::create_directories(directory_ / "sub");
    OutputTransaction outputs;
    outputs.add("--csv", at("x.out"));
    try {
        outputs.add("--json", (directory_ / "sub" / ".." / "x.out").string());
        FAIL() << "no error";
    } catch (const UsageError& error) {
        EXPECT_EQ(std::string(error.what()), "--json " + (directory_ / "sub" / ".." / "x.out").string() +
                                                 ": the same file as --csv; give each output its own file");
    }
}

TEST_F(OutputTransactionTest, AnInputIsNeverAnOutput) {
    std::ofstream(at("scene.json")) << "{}";
    fs::create_symlink("scene.json", directory_ / "alias.json");
    OutputTransaction outputs({at("scene.json")});
    for (const std::string& name : {at("scene.json"), at("alias.json"), at("./scene.json")}) {
        EXPECT_THROW(outputs.add("--csv", name), UsageError) << name;
    }
    EXPECT_EQ(contents(at("scene.json")), "{}");
}

TEST_F(OutputTransactionTest, AnEmptyNameIsAUsageError) {
    OutputTransaction outputs;
    EXPECT_THROW(outputs.add("--csv", ""), UsageError);
}

}  // namespace
}  // namespace substep

// Tests sandbox/atomic_file.cpp: an output appears whole on commit and not at all otherwise; a
// target that is not a regular file is refused, a symlink is written through, stale temporary
// files of dead processes are removed, names print on one line.

#include "atomic_file.h"

#include "scratch_directory_test.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace substep {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public test::ScratchDirectoryTest {
};

TEST_F(AtomicFileTest, CommitMovesTheWholeFileIntoPlace) {
    const fs::path target = directory_ / "out.csv";
    {
        AtomicFile file(target.string());
        file.write("a,b\n");
        EXPECT_FALSE(fs::exists(target)) << "visible before commit";
        EXPECT_EQ(entries().size(), 1u) << "the temporary file sits next to the target";
        file.write("1,2\n");
        file.commit();
    }
    EXPECT_EQ(entries(), std::vector<std::string>{"out.csv"});
    EXPECT_EQ(contents(target), "a,b\n1,2\n");
}

TEST_F(AtomicFileTest, ReplacesAnExistingFile) {
    const fs::path target = directory_ / "out.csv";
    std::ofstream(target) << "old contents that are longer than the new ones\n";
    {
        AtomicFile file(target.string());
        file.write("new\n");
        file.commit();
    }
    EXPECT_EQ(contents(target), "new\n");
}

TEST_F(AtomicFileTest, WithoutCommitNothingIsLeft) {
    const fs::path target = directory_ / "out.csv";
    {
        AtomicFile file(target.string());
        file.write("partial");
    }
    EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, DiscardKeepsThePreviousFile) {
    const fs::path target = directory_ / "out.csv";
    std::ofstream(target) << "previous\n";
    {
        AtomicFile file(target.string());
        file.write("partial");
        file.discard();
    }
    EXPECT_EQ(entries(), std::vector<std::string>{"out.csv"});
    EXPECT_EQ(contents(target), "previous\n");
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsNamingTheFile) {
    const std::string target = (directory_ / "missing" / "out.csv").string();
    try {
        AtomicFile file(target);
        FAIL() << "no error";
    } catch (const OutputError& error) {
        EXPECT_NE(std::string(error.what()).find(target), std::string::npos) << error.what();
    }
    EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, DirectoryTargetThrows) {
    fs::create_directories(directory_ / "sub");
    EXPECT_THROW(AtomicFile((directory_ / "sub").string()), OutputError);
    EXPECT_THROW(AtomicFile(directory_.string() + "/"), OutputError);
    EXPECT_THROW(AtomicFile(""), OutputError);
    EXPECT_EQ(entries(), std::vector<std::string>{"sub"});
}

TEST_F(AtomicFileTest, NonRegularTargetIsRefusedAndLeftInPlace) {
    // Before: a FIFO (or, as root, /dev/null) was replaced by a regular file on commit.
    const fs::path fifo = directory_ / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    try {
        AtomicFile file(fifo.string());
        file.write("x");
        file.commit();
        ADD_FAILURE() << "no error";
    } catch (const OutputError& error) {
        EXPECT_EQ(std::string(error.what()),
                  fifo.string() + ": not a regular file (a device, FIFO or socket); refusing to replace it");
    }
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_EQ(entries(), std::vector<std::string>{"pipe"});
    EXPECT_THROW(AtomicFile("/dev/null"), OutputError);
}

TEST_F(AtomicFileTest, SymlinkIsWrittenThroughAndStaysALink) {
    fs::create_directories(directory_ / "real");
    const fs::path target = directory_ / "real" / "out.csv";
    std::ofstream(target) << "old\n";
    const fs::path link = directory_ / "link.csv";
    fs::create_symlink(fs::path("real") / "out.csv", link);
    {
        AtomicFile file(link.string());
        file.write("new\n");
        file.commit();
    }
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(contents(target), "new\n");
    EXPECT_EQ(entries(), (std::vector<std::string>{"link.csv", "real"}));
    // A link to nothing names no file to write.
    fs::create_symlink(directory_ / "nowhere" / "x.csv", directory_ / "dangling.csv");
    EXPECT_THROW(AtomicFile((directory_ / "dangling.csv").string()), OutputError);
}

TEST_F(AtomicFileTest, StaleTemporariesOfDeadProcessesAreRemoved) {
    // A child that has exited (and been reaped) is a PID that no longer runs.
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_GT(child, 0);
    ::waitpid(child, nullptr, 0);
    const std::string dead = ".out.csv.tmp-" + std::to_string(child) + "-0";
    const std::string alive = ".out.csv.tmp-" + std::to_string(::getppid()) + "-0";
    for (const std::string& name : {dead, alive, std::string(".notes.tmp-x-1"), std::string("keep.csv")})
        std::ofstream(directory_ / name) << "x";
    removeStaleTemporaries(directory_.string());
    std::vector<std::string> expected = {alive, ".notes.tmp-x-1", "keep.csv"};
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(entries(), expected);
}

TEST(PrintableName, ControlCharactersAreEscaped) {
    EXPECT_EQ(printableName("a\nb.csv"), "a\\nb.csv");
    EXPECT_EQ(printableName("x\x1b[31m"), "x\\x1b[31m");
    EXPECT_EQ(printableName("plain/name.json"), "plain/name.json");
}

}  // namespace
}  // namespace substep

// Tests sandbox/atomic_file.cpp: an output appears whole on commit and not at all otherwise.

#include "atomic_file.h"

#include <gtest/gtest.h>

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

class AtomicFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        directory_ = fs::temp_directory_path() /
                     ("atomic_file_test_" + std::to_string(getpid()) + "_" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(directory_);
        fs::create_directories(directory_);
    }
    void TearDown() override { fs::remove_all(directory_); }

    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(directory_)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    static std::string contents(const fs::path& path) {
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }

    fs::path directory_;
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

}  // namespace
}  // namespace substep

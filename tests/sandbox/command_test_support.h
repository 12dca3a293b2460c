#pragma once
// Shared by the tests that run the built `substep` program (substep_command_test.cpp,
// bench_command_test.cpp, sweep_command_test.cpp): a fixture with an empty working folder per
// test, running the program there with its output captured, and reading files back.
// The including target defines SUBSTEP_EXECUTABLE, the path of the built program.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace substep::command_test {

namespace fs = std::filesystem;

/// What one run of the program did.
struct Result {
    int exitCode = -1;  ///< -1 when it did not exit normally (a signal)
    std::string out;
    std::string err;
};

/// The whole file, bytes as they are; empty when it cannot be read.
inline std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The lines of `text`, without their line ends.
inline std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> result;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        result.push_back(line);
    return result;
}

/// `text` quoted for the shell, whatever it holds.
inline std::string quoted(const std::string& text) {
    std::string result = "'";
    for (const char c : text)
        result += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return result + "'";
}

/// Each test runs the program in its own empty working folder; stdout and stderr are captured
/// outside it, so "nothing left behind" means the folder holds only what the test put there.
class CommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() / (std::string(test->test_suite_name()) + "_" +
                                             std::to_string(getpid()) + "_" + test->name());
        fs::remove_all(root_);
        fs::create_directories(work());
    }
    void TearDown() override { fs::remove_all(root_); }

    /// The working folder the program runs in.
    fs::path work() const { return root_ / "work"; }

    /// Runs `substep ARGUMENTS` in work(); `environment` is prefixed (e.g. "VAR=value").
    Result substep(const std::string& arguments, const std::string& environment = "") const {
        const fs::path out = root_ / "stdout.txt";
        const fs::path err = root_ / "stderr.txt";
        const std::string prefix = environment.empty() ? "" : environment + " ";
        const std::string command = "cd " + quoted(work().string()) + " && " + prefix +
                                    quoted(SUBSTEP_EXECUTABLE) + " " + arguments + " >" +
                                    quoted(out.string()) + " 2>" + quoted(err.string());
        const int status = std::system(command.c_str());
        Result result;
        result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        result.out = readFile(out);
        result.err = readFile(err);
        return result;
    }

    /// The names in work(), sorted.
    std::vector<std::string> workEntries() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(work()))
            names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

  private:
    fs::path root_;
};

}  // namespace substep::command_test

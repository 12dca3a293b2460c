// Tests sandbox/capture/state_file.cpp: golden state files read back exactly what was written,
// and a damaged one is an error naming the file and the JSON path.

#include "capture/state_file.h"

#include "capture/json_input.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

namespace substep::capture {
namespace {

/// Values whose shortest decimal forms are long or unusual: they must come back bit for bit.
CaptureState awkwardState() {
    CaptureState state;
    state.frame = 42;
    state.time = 42.0 / 60.0;
    state.bodies.push_back(
        {.name = "a \"quoted\" name",
         .position = {0.1 + 0.2, -1e-300, std::numeric_limits<double>::denorm_min()},
         .orientation = {std::sqrt(0.5), 0.0, -std::sqrt(0.5), 1e-17},
         .velocity = {std::numeric_limits<double>::max(), -0.0, 1.0 / 3.0},
         .angularVelocity = {123456789.123456789, -2.5e-8, 7.0}});
    state.bodies.push_back({.name = ""});
    state.joints.push_back({.name = "j", .force = 19.62, .torque = 1.0 / 7.0, .error = 3e-12});
    state.softBodies.push_back({.name = "tyre", .centre = {1, 2, 3}, .volume = 0.0123});
    return state;
}

template <std::size_t N>
void expectBitsEqual(const std::array<double, N>& a, const std::array<double, N>& b) {
    for (std::size_t i = 0; i < N; ++i) {
        // -0.0 reads back as 0 (JSON has one zero); the comparison and the digest see the same
        // value.
        if (a[i] == 0.0 && b[i] == 0.0) continue;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i])) << i;
    }
}

TEST(StateFile, ReadsBackExactlyWhatWasWritten) {
    const CaptureState state = awkwardState();
    const std::string text = formatStateFile(state);
    const CaptureState read = parseStateFile(text, "g.json");
    EXPECT_EQ(read.frame, 42);
    EXPECT_EQ(read.time, state.time);
    ASSERT_EQ(read.bodies.size(), 2u);
    EXPECT_EQ(read.bodies[0].name, state.bodies[0].name);
    expectBitsEqual(read.bodies[0].position, state.bodies[0].position);
    expectBitsEqual(read.bodies[0].orientation, state.bodies[0].orientation);
    expectBitsEqual(read.bodies[0].velocity, state.bodies[0].velocity);
    expectBitsEqual(read.bodies[0].angularVelocity, state.bodies[0].angularVelocity);
    EXPECT_EQ(read.bodies[1].name, "");
    ASSERT_EQ(read.joints.size(), 1u);
    EXPECT_EQ(read.joints[0].torque, 1.0 / 7.0);
    ASSERT_EQ(read.softBodies.size(), 1u);
    EXPECT_EQ(read.softBodies[0].volume, 0.0123);
    // Written again, the same bytes, but for the sign of zero, which JSON readers drop ("-0" reads
    // as the integer 0): the comparison holds -0 and 0 equal, and the digest hashes the run itself.
    std::string unsigned_zero = text;
    unsigned_zero.replace(unsigned_zero.find(", -0, "), 6, ", 0, ");
    EXPECT_EQ(formatStateFile(read), unsigned_zero);
}

TEST(StateFile, OneBodyOrJointPerLineForReadableDiffs) {
    const std::string text = formatStateFile(awkwardState());
    EXPECT_NE(text.find("\n  {\"name\": \"a \\\"quoted\\\" name\", \"position\": "
                        "[0.30000000000000004, -1e-300, 5e-324]"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("\n  {\"name\": \"j\", \"force\": 19.62, \"torque\": 0.14285714285714285, "
                        "\"error\": 3e-12}"),
              std::string::npos)
        << text;
}

TEST(StateFile, DamagedFilesAreErrorsNamingFileAndPath) {
    const std::string text = formatStateFile(awkwardState());
    const auto errorOf = [](const std::string& damaged) {
        try {
            parseStateFile(damaged, "g/frame_00042.json");
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("(no error)");
    };
    // Truncated anywhere: an error, never a partial state.
    for (const std::size_t length :
         {std::size_t{0}, std::size_t{10}, text.size() / 2, text.size() - 3}) {
        const std::string message = errorOf(text.substr(0, length));
        EXPECT_EQ(message.rfind("g/frame_00042.json: ", 0), 0u) << length << ": " << message;
    }
    std::string badNumber = text;
    badNumber.replace(badNumber.find("19.62"), 5, "\"19\"");
    EXPECT_EQ(errorOf(badNumber),
              "g/frame_00042.json: joints[0].force: expected a number, got a string");
    std::string shortArray = text;
    shortArray.replace(shortArray.find("[1, 2, 3]"), 9, "[1, 2]");
    EXPECT_EQ(errorOf(shortArray),
              "g/frame_00042.json: soft_bodies[0].centre: expected 3 elements, got 2");
}

}  // namespace
}  // namespace substep::capture

// Tests sandbox/capture/json_input.cpp: JSON reading whose every error names file and path.

#include "capture/json_input.h"

#include <gtest/gtest.h>

namespace substep::capture {
namespace {

std::string errorOf(const std::function<void()>& read) {
    try {
        read();
    } catch (const InputError& error) {
        return error.what();
    }
    return "(no error)";
}

TEST(JsonInput, DuplicateKeysAreErrorsNamingTheirPath) {
    EXPECT_EQ(errorOf([] { parseJson(R"({"a": [1, {"b": 1, "b": 2}]})", "f.json"); }),
              "f.json: a[1].b: duplicate key (it is already given earlier in this object)");
    // The same key in two different objects is fine.
    EXPECT_NO_THROW(parseJson(R"({"a": {"b": 1}, "c": {"b": 1}})", "f.json"));
}

TEST(JsonInput, SyntaxErrorsNameLineColumnAndPath) {
    const std::string message = errorOf([] { parseJson("{\"a\": [1,\n 2,", "f.json"); });
    EXPECT_NE(message.find("f.json: a[1]: not valid JSON at line 2"), std::string::npos) << message;
    EXPECT_EQ(errorOf([] { parseJson("  \n", "f.json"); }),
              "f.json: is empty (or truncated): no JSON in it");
    const std::string overflow = errorOf([] { parseJson(R"({"x": 1e999})", "f.json"); });
    EXPECT_NE(overflow.find("f.json: x: number out of range"), std::string::npos) << overflow;
}

TEST(JsonInput, CheckedReadsNameThePathAndTheRange) {
    const nlohmann::ordered_json document =
        parseJson(R"({"n": 2.5, "i": 7, "big": 18446744073709551615, "s": 3})", "f.json");
    const JsonAt root(document, "", "f.json");
    EXPECT_EQ(root.member("n").number(0, 10), 2.5);
    EXPECT_EQ(errorOf([&] { root.member("n").number(3, 10); }),
              "f.json: n: must be between 3 and 10, got 2.5");
    EXPECT_EQ(errorOf([&] { root.member("n").integer(0, 10); }),
              "f.json: n: expected a whole number, got 2.5");
    EXPECT_EQ(root.member("i").integer(0, 10), 7);
    EXPECT_EQ(errorOf([&] { root.member("i").integer(8, 10); }),
              "f.json: i: must be a whole number from 8 to 10, got 7");
    EXPECT_EQ(errorOf([&] { root.member("big").integer(0, 10); }),
              "f.json: big: must be a whole number from 0 to 10, got 18446744073709551615");
    EXPECT_EQ(errorOf([&] { root.member("s").string(); }),
              "f.json: s: expected a string, got a number");
    EXPECT_EQ(errorOf([&] { root.member("missing"); }),
              "f.json: top level: missing key \"missing\"");
    EXPECT_EQ(errorOf([&] {
                  root.requireObject({"n", "i"});
              }),
              "f.json: big: unknown key (expected one of: n, i)");
}

}  // namespace
}  // namespace substep::capture

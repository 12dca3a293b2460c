/// Scene files, the validator of the loader (scene_loader_validator.h): bounds, typed reads and
/// objects with checked keys.

#include "scene/scene_loader_validator.h"

#include "scene/scene_loader.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace substep::scene_loader {

namespace {

std::string boundText(double value, const char* text) {
    return text ? text : formatNumber(value);
}

}  // namespace

Interval positiveUpTo(double max) {
    return {.lo = 0, .hi = max, .loOpen = true, .hiSanity = true};
}
Interval sizeUpTo(double max) {
    return {.lo = 0, .hi = max, .loOpen = true, .hiSanity = true, .least = kMinSize};
}
Interval nonNegativeUpTo(double max) {
    return {.lo = 0, .hi = max, .hiSanity = true};
}
Interval within(double max) {
    return {.lo = -max, .hi = max, .loSanity = true, .hiSanity = true};
}
Interval closed(double lo, double hi, const char* loText, const char* hiText) {
    return {.lo = lo, .hi = hi, .loText = loText, .hiText = hiText};
}
Interval angles(double lo, double hi, const char* loText, const char* hiText) {
    return {
        .lo = lo - kAngleTolerance, .hi = hi + kAngleTolerance, .loText = loText, .hiText = hiText};
}

std::string checkInterval(double value, const Interval& interval) {
    const bool below = value < interval.lo || (interval.loOpen && value == interval.lo);
    const bool above = value > interval.hi || (interval.hiOpen && value == interval.hi);
    if (!below && !above && value < interval.least) {
        char least[32];  // %g: 0.0001 and 1e-06, as people write them
        std::snprintf(least, sizeof least, "%g", interval.least);
        return std::string("must be >= ") + least +
               " (smaller values lose precision or underflow), got " + formatNumber(value);
    }
    if (!below && !above) return "";
    const std::string lo = boundText(interval.lo, interval.loText);
    const std::string hi = boundText(interval.hi, interval.hiText);
    std::string rule;
    if (interval.lo > -kInf && interval.hi < kInf && !interval.loSanity && !interval.hiSanity) {
        rule = std::string("must be in ") + (interval.loOpen ? "(" : "[") + lo + ", " + hi +
               (interval.hiOpen ? ")" : "]");
    } else if (below) {
        rule = std::string("must be ") + (interval.loOpen ? "> " : ">= ") + lo;
        if (interval.loSanity) rule += " (a sanity bound against absurd values)";
    } else {
        rule = std::string("must be ") + (interval.hiOpen ? "< " : "<= ") + hi;
        if (interval.hiSanity) rule += " (a sanity bound against absurd values)";
    }
    return rule + ", got " + formatNumber(value);
}

void Validator::fail(const std::string& path, const std::string& problem) const {
    throw SceneError(file_, path.empty() ? "top level" : path, problem);
}

double Validator::number(const Node& node, const Interval& interval) const {
    if (!node.value.is_number()) fail(node.path, "must be a number, got " + describe(node.value));
    const double value = node.value.get<double>();
    if (!std::isfinite(value)) fail(node.path, "must be a finite number");
    if (std::string problem = checkInterval(value, interval); !problem.empty()) {
        fail(node.path, problem);
    }
    return value;
}

double Validator::angle(const Node& node, double lo, double hi, const char* loText,
                        const char* hiText) const {
    return std::clamp(number(node, angles(lo, hi, loText, hiText)), lo, hi);
}

int Validator::integer(const Node& node, int lo, int hi) const {
    const std::string rule =
        "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!node.value.is_number()) fail(node.path, rule + ", got " + describe(node.value));
    if (node.value.is_number_float()) {
        const double value = node.value.get<double>();
        if (value != std::floor(value)) fail(node.path, rule + ", got " + formatNumber(value));
        if (value < lo || value > hi) fail(node.path, rule + ", got " + formatNumber(value));
        return static_cast<int>(value);
    }
    if (node.value.is_number_unsigned()) {
        const uint64_t value = node.value.get<uint64_t>();
        if (value > static_cast<uint64_t>(hi) || static_cast<int64_t>(value) < lo) {
            fail(node.path, rule + ", got " + std::to_string(value));
        }
        return static_cast<int>(value);
    }
    const int64_t value = node.value.get<int64_t>();
    if (value < lo || value > hi) fail(node.path, rule + ", got " + std::to_string(value));
    return static_cast<int>(value);
}

bool Validator::boolean(const Node& node) const {
    if (!node.value.is_boolean()) {
        fail(node.path, "must be true or false, got " + describe(node.value));
    }
    return node.value.get<bool>();
}

std::string Validator::string(const Node& node) const {
    if (!node.value.is_string()) fail(node.path, "must be a string, got " + describe(node.value));
    return node.value.get<std::string>();
}

std::vector<double> Validator::numbers(const Node& node, std::size_t n, const Interval& interval,
                                       const char* what) const {
    if (!node.value.is_array() || node.value.size() != n) {
        const std::string got = node.value.is_array()
                                    ? "an array of " + std::to_string(node.value.size())
                                    : describe(node.value);
        fail(node.path, std::string("must be ") + what + ", got " + got);
    }
    std::vector<double> values;
    for (std::size_t i = 0; i < n; ++i) {
        values.push_back(number({node.value[i], elementPath(node.path, i)}, interval));
    }
    return values;
}

Vec3 Validator::vec3(const Node& node, const Interval& interval) const {
    const auto v = numbers(node, 3, interval, "an array of 3 numbers [x, y, z]");
    return Vec3(v[0], v[1], v[2]);
}

Vec3 Validator::direction(const Node& node) const {
    const Vec3 v = vec3(node, {});
    const double length = v.stableNorm();  // no overflow for huge components
    if (!(length > kDirectionEpsilon)) {
        fail(node.path, "must be a non-zero direction, got length " + formatNumber(length));
    }
    return (v / length).normalized();
}

Quat Validator::quaternion(const Node& node) const {
    const auto v = numbers(node, 4, {}, "a quaternion [w, x, y, z] of 4 numbers");
    Eigen::Vector4d c(v[0], v[1], v[2], v[3]);
    const double length = c.stableNorm();
    if (!(length > kDirectionEpsilon)) {
        fail(node.path,
             "must be a non-zero quaternion [w, x, y, z], got length " + formatNumber(length));
    }
    c = (c / length).normalized();
    return Quat(c[0], c[1], c[2], c[3]);
}

Range Validator::range(const Node& node, const Interval& interval) const {
    const auto v = numbers(node, 2, interval, "an array [lower, upper] of 2 numbers");
    if (v[0] > v[1]) {
        fail(node.path,
             "lower limit " + formatNumber(v[0]) + " is above upper limit " + formatNumber(v[1]));
    }
    return {v[0], v[1]};
}

Range Validator::angleRange(const Node& node) const {
    Range r = range(node, angles(-kPi, kPi, "-pi", "pi"));
    r.lower = std::clamp(r.lower, -kPi, kPi);
    r.upper = std::clamp(r.upper, -kPi, kPi);
    return r;
}

std::string Validator::name(const Node& node) const {
    std::string text = string(node);
    if (text.empty()) fail(node.path, "must not be empty (leave the key out for no name)");
    for (char c : text) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == ',' || c == '"') {
            fail(node.path,
                 "must not contain control characters, ',' or '\"' (names become "
                 "CSV column headers), got " +
                     jsonQuoted(text));
        }
    }
    return text;
}

ObjectReader::ObjectReader(const Validator& validator, const Node& node, const char* what)
    : validator_(validator), value_(node.value), path_(node.path) {
    if (!value_.is_object()) {
        validator_.fail(path_, std::string("must be ") + what + ", got " + describe(value_));
    }
}

std::optional<Node> ObjectReader::get(std::string_view key) const {
    const auto it = value_.find(key);
    if (it == value_.end()) return std::nullopt;
    return Node{*it, pathOf(key)};
}

Node ObjectReader::require(std::string_view key, const std::string& hint) const {
    auto node = get(key);
    if (!node) validator_.fail(pathOf(key), "missing (required)" + hint);
    return *node;
}

void ObjectReader::allowOnly(const std::vector<std::string>& allowed) const {
    for (const auto& [key, value] : value_.items()) {
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
            failUnknown(key, allowed);
        }
    }
}

void ObjectReader::failUnknown(const std::string& key,
                               const std::vector<std::string>& allowed) const {
    std::string hint = suggestion(key, allowed);
    if (hint.empty()) hint = " (expected " + joinList(allowed, " or ") + ")";
    validator_.fail(pathOf(key), "unknown key" + hint);
}

}  // namespace substep::scene_loader

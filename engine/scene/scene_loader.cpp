/// Scene files (JSON, version 1) -> SceneDescription, validating everything (DESIGN.md "Scene
/// files"). The first problem found throws a SceneError `FILE: JSON.PATH: what is wrong`.
///
/// Rules and bounds (the README quotes this block)
/// -----------------------------------------------
/// Numbers must be finite JSON numbers (`1e999` overflows and is rejected, and so is a non-zero
/// literal that underflows to 0 such as `1e-400`). Integers may be written `20` or `20.0`, never
/// `20.5`. Unknown keys and duplicate keys are errors at every level. A bound marked (sanity) is
/// not physics: it rejects values that can only be typing mistakes and keeps the solver in a
/// range where double precision still works.
///
///   substep_scene          required, exactly 1
///   gravity                each component in [-1e4, 1e4] m/s² (sanity)
///   dt                     (0, 1] s
///   substeps, iterations   integers in [1, 10000] and [1, 1000]
///   coordinates            positions, anchors, camera points, plane offset, max_distance,
///                          prismatic limits and target_offset: |x| <= 1e6 m (sanity)
///   sizes                  sphere/capsule/cylinder radius, box size, cylinder length: (0, 1e4] m;
///                          capsule length [0, 1e4] m
///   mass                   (0, 1e9] kg; density (0, 1e6] kg/m³; density x volume <= 1e9 kg
///   speeds                 velocity, angular_velocity, target_velocity: |v| <= 1e5 per component
///   compliances            compliance, limit_, drive_, twist_compliance: [0, 1e9] (sanity)
///   damping                linear, angular: [0, 1e6] 1/s (sanity)
///   friction               static, dynamic: [0, 1e3] (sanity); restitution [0, 1]
///   angles                 hinge limits, target_angle, twist_limits in [-pi, pi]; swing_limit in
///                          [0, pi]; values up to 1e-4 beyond ±pi (a rounded 3.1416) are clamped
///   camera fov             (0, pi) rad; target must differ from position
///   directions             quaternions [w, x, y, z], axes and normals must be non-zero (length
///                          > 1e-12) and are normalised; a normal must not be parallel to its axis
///                          (sine of the angle > 1e-6) and is made perpendicular to it
///   names                  non-empty, no control characters, ',' or '"' (they name CSV columns);
///                          unique among bodies (and "world" is reserved) or among joints
///   static bodies          no mass, density or non-zero velocity; planes only on static bodies,
///                          placed by normal and offset alone (no position or orientation)
///   joints                 body0/body1 name existing bodies (omitted or "world" = the world), not
///                          both the world and not the same body; a key the joint type does not
///                          use is an error; target_angle and target_velocity exclude each other
///   mesh                   `file` (relative to the scene file's folder; any format assimp reads),
///                          `scale` (a number or [x, y, z], each in (0, 1e4], default 1), `convex`
///                          (default false: a triangle mesh, static bodies only); a convex mesh
///                          collides and weighs as its hull, which must enclose volume
///   spline                 `points` (at least 2 [x, y, z], coordinates |x| <= 1e6 m, at most
///                          100000; repeated neighbours are merged), `radius` (0, 1e4] m, `closed`
///                          (default false; a closed curve needs 3 distinct points), `hollow`
///                          (default false: a rail ridden on; true: a pipe run inside); static only
///   heightfield            `heights`: rows along z, each the same number of heights along x (at
///                          least 2 x 2, at most 4096 x 4096), |h| <= 1e6 m; `size` [x, z] extents
///                          in (0, 1e6] m, centred on the body's position; static only
///
/// Extensions to DESIGN.md: optional top-level `name` and `description` strings (for readers; the
/// scene's name stays the file stem), and spherical `twist_compliance` (defaults to
/// `limit_compliance`). Defaults not stated there: plane normal [0, 1, 0], offset 0; a missing
/// friction or damping member keeps its default.

#include "scene/scene_loader.h"

#include "physics/collision/convex_mesh_shape.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/spline_tube.h"
#include "physics/mass_properties.h"
#include "scene/mesh_import.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace substep {

namespace {

std::string composeMessage(const std::string& file, const std::string& path,
                           const std::string& problem) {
    return path.empty() ? file + ": " + problem : file + ": " + path + ": " + problem;
}

}  // namespace

SceneError::SceneError(const std::string& file, const std::string& path, const std::string& problem)
    : std::runtime_error(composeMessage(file, path, problem)),
      file_(file),
      path_(path),
      problem_(problem) {}

namespace {

// Ordered so that "unknown key" reports the first offender in file order.
using Json = nlohmann::ordered_json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = M_PI;

constexpr double kMaxGravity = 1e4;     // m/s² per component
constexpr double kMaxCoordinate = 1e6;  // m
constexpr double kMaxSize = 1e4;        // m
constexpr double kMaxMass = 1e9;        // kg
constexpr double kMaxDensity = 1e6;     // kg/m³
constexpr double kMaxSpeed = 1e5;       // m/s, rad/s
constexpr double kMaxCompliance = 1e9;  // m/N, rad/(N m)
constexpr double kMaxDamping = 1e6;     // 1/s
constexpr double kMaxFriction = 1e3;
constexpr double kAngleTolerance = 1e-4;  // rad beyond ±pi accepted as rounding, then clamped
constexpr double kParallelSine = 1e-6;
constexpr int kMaxSubsteps = 10000;
constexpr int kMaxIterations = 1000;
constexpr std::size_t kMaxKeys = 1000;                // per JSON object
constexpr std::size_t kMaxDepth = 64;                 // JSON nesting
constexpr std::uintmax_t kMaxFileBytes = 256u << 20;  // 256 MiB

// ---------------------------------------------------------------------------------------------
// Text helpers

/// Shortest text that reads back as the same double.
std::string formatNumber(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

/// A string as a JSON literal (quoted and escaped), so messages stay on one line.
std::string jsonQuoted(std::string_view text) {
    return Json(std::string(text)).dump(-1, ' ', false, Json::error_handler_t::replace);
}

bool isIdentifier(std::string_view key) {
    if (key.empty() || std::isdigit(static_cast<unsigned char>(key[0]))) return false;
    return std::all_of(key.begin(), key.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
}

/// `parent.key`, or `parent["odd key"]` for keys that are not identifiers. The root path is "".
std::string memberPath(const std::string& parent, std::string_view key) {
    if (!isIdentifier(key)) return parent + "[" + jsonQuoted(key) + "]";
    return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string elementPath(const std::string& parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

/// What a value is, for "must be X, got Y".
std::string describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return value.get<bool>() ? "true" : "false";
        case Json::value_t::number_integer:
            return std::to_string(value.get<int64_t>());
        case Json::value_t::number_unsigned:
            return std::to_string(value.get<uint64_t>());
        case Json::value_t::number_float:
            return formatNumber(value.get<double>());
        case Json::value_t::string: {
            std::string text = value.get<std::string>();
            if (text.size() > 40) text = text.substr(0, 37) + "...";
            return "the string " + jsonQuoted(text);
        }
        case Json::value_t::array:
            return "an array";
        case Json::value_t::object:
            return "an object";
        default:
            return "an unsupported value";
    }
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// ` (did you mean "x"?)` when one candidate is a plausible typo of `word`, else "".
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates) {
    const std::string* best = nullptr;
    std::size_t bestDistance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const std::string& candidate : candidates) {
        const std::size_t distance = editDistance(word, candidate);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = &candidate;
        }
    }
    return best ? " (did you mean " + jsonQuoted(*best) + "?)" : "";
}

std::string joinList(const std::vector<std::string>& items, const char* lastSeparator) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (i > 0) out += i + 1 == items.size() ? lastSeparator : ", ";
        out += items[i];
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Parsing: a SAX handler that builds the document while knowing the JSON path of every value,
// so syntax errors, overflowing numbers and duplicate keys are reported where they occur.

class DocumentBuilder {
  public:
    using number_integer_t = Json::number_integer_t;
    using number_unsigned_t = Json::number_unsigned_t;
    using number_float_t = Json::number_float_t;
    using string_t = Json::string_t;
    using binary_t = Json::binary_t;

    DocumentBuilder(Json& root, std::string_view text, const std::string& file)
        : root_(root), text_(text), file_(file) {}

    bool null() { return add(Json(nullptr)); }
    bool boolean(bool value) { return add(Json(value)); }
    bool number_integer(number_integer_t value) { return add(Json(value)); }
    bool number_unsigned(number_unsigned_t value) { return add(Json(value)); }
    bool number_float(number_float_t value, const string_t& literal) {
        // strtod turns 1e-400 into 0 silently; a value the file did not say is an error.
        if (value == 0.0 && hasNonZeroMantissa(literal)) {
            const std::string number =
                literal.size() > 40 ? literal.substr(0, 37) + "..." : literal;
            fail(valuePath(),
                 "number " + number + " is too small to represent (it underflows to 0)");
        }
        return add(Json(value));
    }
    bool string(string_t& value) { return add(Json(std::move(value))); }
    bool binary(binary_t&) { return false; }  // JSON text has no binary values

    bool start_object(std::size_t) { return open(Json::object()); }
    bool start_array(std::size_t) { return open(Json::array()); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(string_t& key) {
        Frame& frame = stack_.back();
        // Key lookups in an ordered object are linear; no valid object comes near this many.
        if (frame.container->size() >= kMaxKeys) {
            fail(frame.path, "has more than " + std::to_string(kMaxKeys) + " keys");
        }
        if (frame.container->contains(key)) {
            fail(memberPath(frame.path, key),
                 "duplicate key (it is already given earlier in this object)");
        }
        frame.key = key;
        frame.keyPending = true;
        return true;
    }

    bool parse_error(std::size_t position, const std::string& lastToken,
                     const nlohmann::detail::exception& error) {
        if (error.id == 406) {
            // Number overflow: point at the start of the number.
            const std::size_t start =
                position >= lastToken.size() ? position - lastToken.size() : 0;
            const std::string number =
                lastToken.size() > 40 ? lastToken.substr(0, 37) + "..." : lastToken;
            fail(valuePath(), "number " + number + " overflows a double (" + location(start) + ")");
        }
        // Keep nlohmann's description, drop its prefix and location (ours counts the same way).
        std::string detail = error.what();
        if (const auto dash = detail.find(" - "); dash != std::string::npos) {
            detail = detail.substr(dash + 3);
        } else if (const auto bracket = detail.find("] "); bracket != std::string::npos) {
            detail = detail.substr(bracket + 2);
        }
        fail(valuePath(), "syntax error at " + location(position > 0 ? position - 1 : 0) + ": " +
                              shortenLastRead(detail));
    }

  private:
    struct Frame {
        Json* container;
        std::string path;
        std::string key;          // objects: the last key read
        bool keyPending = false;  // objects: its value has not been read yet
        std::size_t index = 0;    // arrays: the index of the next element
    };

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw SceneError(file_, path.empty() ? "top level" : path, problem);
    }

    /// Path of the value being read next.
    std::string valuePath() const {
        if (stack_.empty()) return "";
        const Frame& frame = stack_.back();
        if (frame.container->is_object()) {
            return frame.keyPending ? memberPath(frame.path, frame.key) : frame.path;
        }
        return elementPath(frame.path, frame.index);
    }

    /// `line L, column C` of a byte offset (columns count bytes, from 1).
    std::string location(std::size_t offset) const {
        offset = std::min(offset, text_.size());
        const std::size_t line = 1 + std::count(text_.begin(), text_.begin() + offset, '\n');
        const std::size_t lineStart = text_.rfind('\n', offset == 0 ? 0 : offset - 1);
        const std::size_t column =
            lineStart == std::string_view::npos || offset == 0 ? offset + 1 : offset - lineStart;
        return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }

    /// nlohmann quotes the text it last read, which can be the rest of the file (an unclosed
    /// string) and can hold invalid UTF-8: keep its last 40 bytes, non-ASCII ones as \xNN.
    static std::string shortenLastRead(const std::string& detail) {
        const std::string marker = "last read: '";
        const std::size_t start = detail.find(marker);
        if (start == std::string::npos) return detail;
        const std::size_t tokenStart = start + marker.size();
        std::size_t tokenEnd = detail.find("'; expected", tokenStart);
        if (tokenEnd == std::string::npos) tokenEnd = detail.rfind('\'');
        if (tokenEnd == std::string::npos || tokenEnd < tokenStart) return detail;
        std::string token = detail.substr(tokenStart, tokenEnd - tokenStart);
        if (token.size() > 40) token = "..." + token.substr(token.size() - 40);
        std::string clean;
        for (const char c : token) {
            const auto byte = static_cast<unsigned char>(c);
            if (byte < 0x80) {
                clean += c;
            } else {
                static const char* hex = "0123456789ABCDEF";
                clean += {'\\', 'x', hex[byte >> 4], hex[byte & 15]};
            }
        }
        return detail.substr(0, tokenStart) + clean + detail.substr(tokenEnd);
    }

    static bool hasNonZeroMantissa(const std::string& literal) {
        for (char c : literal) {
            if (c == 'e' || c == 'E') break;
            if (c >= '1' && c <= '9') return true;
        }
        return false;
    }

    Json* add(Json&& value) {
        if (stack_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        Frame& frame = stack_.back();
        if (frame.container->is_object()) {
            Json& slot = (*frame.container)[frame.key];
            slot = std::move(value);
            frame.keyPending = false;
            return &slot;
        }
        frame.container->push_back(std::move(value));
        ++frame.index;
        return &frame.container->back();
    }

    bool open(Json&& container) {
        if (stack_.size() >= kMaxDepth) {
            fail(valuePath(),
                 "nested too deeply (more than " + std::to_string(kMaxDepth) + " levels)");
        }
        std::string path = valuePath();
        Json* slot = add(std::move(container));
        stack_.push_back({slot, std::move(path), {}, false, 0});
        return true;
    }

    bool close() {
        stack_.pop_back();
        return true;
    }

    Json& root_;
    std::string_view text_;
    const std::string& file_;
    std::vector<Frame> stack_;
};

// ---------------------------------------------------------------------------------------------
// Validation helpers

/// An allowed interval. A bound marked `sanity` rejects absurd values rather than stating a rule
/// of the physics; messages say so. `loText`/`hiText` print bounds like "pi" by name.
struct Interval {
    double lo = -kInf;
    double hi = kInf;
    bool loOpen = false;
    bool hiOpen = false;
    bool loSanity = false;
    bool hiSanity = false;
    const char* loText = nullptr;
    const char* hiText = nullptr;
};

Interval positiveUpTo(double max) {
    return {.lo = 0, .hi = max, .loOpen = true, .hiSanity = true};
}
Interval nonNegativeUpTo(double max) {
    return {.lo = 0, .hi = max, .hiSanity = true};
}
Interval within(double max) {
    return {.lo = -max, .hi = max, .loSanity = true, .hiSanity = true};
}
Interval closed(double lo, double hi, const char* loText = nullptr, const char* hiText = nullptr) {
    return {.lo = lo, .hi = hi, .loText = loText, .hiText = hiText};
}
/// Angles in [lo, hi] with a little slack at ±pi for rounded literals; values are clamped after.
Interval angles(double lo, double hi, const char* loText, const char* hiText) {
    return {
        .lo = lo - kAngleTolerance, .hi = hi + kAngleTolerance, .loText = loText, .hiText = hiText};
}

std::string boundText(double value, const char* text) {
    return text ? text : formatNumber(value);
}

/// Empty when `value` lies in `interval`, else what is wrong.
std::string checkInterval(double value, const Interval& interval) {
    const bool below = value < interval.lo || (interval.loOpen && value == interval.lo);
    const bool above = value > interval.hi || (interval.hiOpen && value == interval.hi);
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

/// A value in the document and its JSON path.
struct Node {
    const Json& value;
    std::string path;
};

class Validator {
  public:
    explicit Validator(const std::string& file) : file_(file) {}

    /// The scene file as named in messages (mesh files are found relative to its folder).
    const std::string& file() const { return file_; }

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw SceneError(file_, path.empty() ? "top level" : path, problem);
    }

    double number(const Node& node, const Interval& interval = {}) const {
        if (!node.value.is_number())
            fail(node.path, "must be a number, got " + describe(node.value));
        const double value = node.value.get<double>();
        if (!std::isfinite(value)) fail(node.path, "must be a finite number");
        if (std::string problem = checkInterval(value, interval); !problem.empty()) {
            fail(node.path, problem);
        }
        return value;
    }

    /// An angle in [lo, hi] (given with a little slack at ±pi and clamped).
    double angle(const Node& node, double lo, double hi, const char* loText,
                 const char* hiText) const {
        return std::clamp(number(node, angles(lo, hi, loText, hiText)), lo, hi);
    }

    int integer(const Node& node, int lo, int hi) const {
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

    bool boolean(const Node& node) const {
        if (!node.value.is_boolean()) {
            fail(node.path, "must be true or false, got " + describe(node.value));
        }
        return node.value.get<bool>();
    }

    std::string string(const Node& node) const {
        if (!node.value.is_string())
            fail(node.path, "must be a string, got " + describe(node.value));
        return node.value.get<std::string>();
    }

    /// An array of exactly n numbers, each in `interval` (paths name the element).
    std::vector<double> numbers(const Node& node, std::size_t n, const Interval& interval,
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

    Vec3 vec3(const Node& node, const Interval& interval) const {
        const auto v = numbers(node, 3, interval, "an array of 3 numbers [x, y, z]");
        return Vec3(v[0], v[1], v[2]);
    }

    /// A non-zero vector, normalised.
    Vec3 direction(const Node& node) const {
        const Vec3 v = vec3(node, {});
        const double length = v.stableNorm();  // no overflow for huge components
        if (!(length > kDirectionEpsilon)) {
            fail(node.path, "must be a non-zero direction, got length " + formatNumber(length));
        }
        return (v / length).normalized();
    }

    /// A non-zero quaternion [w, x, y, z], normalised.
    Quat quaternion(const Node& node) const {
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

    /// [lo, hi] with both ends in `interval` and lo <= hi.
    Range range(const Node& node, const Interval& interval) const {
        const auto v = numbers(node, 2, interval, "an array [lower, upper] of 2 numbers");
        if (v[0] > v[1]) {
            fail(node.path, "lower limit " + formatNumber(v[0]) + " is above upper limit " +
                                formatNumber(v[1]));
        }
        return {v[0], v[1]};
    }

    /// A range of angles within [-pi, pi] (clamped after the rounding slack).
    Range angleRange(const Node& node) const {
        Range r = range(node, angles(-kPi, kPi, "-pi", "pi"));
        r.lower = std::clamp(r.lower, -kPi, kPi);
        r.upper = std::clamp(r.upper, -kPi, kPi);
        return r;
    }

    /// A name for CSV columns and joint references.
    std::string name(const Node& node) const {
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

  private:
    const std::string& file_;
};

/// An object whose keys are checked against what its context allows.
class ObjectReader {
  public:
    ObjectReader(const Validator& validator, const Node& node, const char* what = "an object")
        : validator_(validator), value_(node.value), path_(node.path) {
        if (!value_.is_object()) {
            validator_.fail(path_, std::string("must be ") + what + ", got " + describe(value_));
        }
    }

    const std::string& path() const { return path_; }
    std::string pathOf(std::string_view key) const { return memberPath(path_, key); }

    bool has(std::string_view key) const { return value_.contains(key); }

    std::optional<Node> get(std::string_view key) const {
        const auto it = value_.find(key);
        if (it == value_.end()) return std::nullopt;
        return Node{*it, pathOf(key)};
    }

    Node require(std::string_view key, const std::string& hint = "") const {
        auto node = get(key);
        if (!node) validator_.fail(pathOf(key), "missing (required)" + hint);
        return *node;
    }

    /// Every key must be one of `allowed`.
    void allowOnly(const std::vector<std::string>& allowed) const {
        for (const auto& [key, value] : value_.items()) {
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
                failUnknown(key, allowed);
            }
        }
    }

    [[noreturn]] void failUnknown(const std::string& key,
                                  const std::vector<std::string>& allowed) const {
        std::string hint = suggestion(key, allowed);
        if (hint.empty()) hint = " (expected " + joinList(allowed, " or ") + ")";
        validator_.fail(pathOf(key), "unknown key" + hint);
    }

    const Json& value() const { return value_; }

  private:
    const Validator& validator_;
    const Json& value_;
    std::string path_;
};

// ---------------------------------------------------------------------------------------------
// The scene

double shapeVolume(const Shape& shape) {
    switch (shape.type) {
        case ShapeType::Sphere:
            return 4.0 / 3.0 * kPi * std::pow(shape.radius, 3);
        case ShapeType::Box:
            return shape.size.prod();
        case ShapeType::Capsule:
            return kPi * shape.radius * shape.radius * shape.length +
                   4.0 / 3.0 * kPi * std::pow(shape.radius, 3);
        case ShapeType::Cylinder:
            return kPi * shape.radius * shape.radius * shape.length;
        case ShapeType::Mesh:  // a closed mesh's volume (a convex one's hull)
            return shapeMassProperties(shape, 1.0).mass;
        default:
            return 0.0;
    }
}

/// `mesh {file, scale, convex}`, the file found relative to the scene file's folder.
Shape parseMeshShape(const Validator& v, const ObjectReader& obj, const Node& typeNode,
                     bool isStatic) {
    obj.allowOnly({"type", "file", "scale", "convex"});
    const Node fileNode = obj.require("file", " (a mesh file such as \"meshes/bunny.obj\")");
    const std::string file = v.string(fileNode);
    if (file.empty()) v.fail(fileNode.path, "must name a mesh file, got an empty string");
    Vec3 scale = Vec3::Ones();
    if (auto s = obj.get("scale")) {
        scale = s->value.is_array() ? v.vec3(*s, positiveUpTo(kMaxSize))
                                    : Vec3::Constant(v.number(*s, positiveUpTo(kMaxSize)));
    }
    bool convex = false;
    const auto convexNode = obj.get("convex");
    if (convexNode) convex = v.boolean(*convexNode);
    if (!convex && !isStatic) {
        v.fail(convexNode ? convexNode->path : typeNode.path,
               "a dynamic mesh must be convex (add \"convex\": true to collide and weigh as its "
               "convex hull); a non-convex mesh can only be on a static body");
    }

    const std::filesystem::path path = std::filesystem::path(v.file()).parent_path() / file;
    MeshImport imported = importTriangleMesh(path, scale);
    if (!imported.ok()) v.fail(fileNode.path, imported.error);
    auto mesh = std::make_shared<const TriangleMesh>(std::move(imported.mesh));
    try {
        return convex ? convexMeshShape(mesh) : triangleMeshShape(mesh);
    } catch (const std::invalid_argument& e) {
        v.fail(fileNode.path, "mesh file " + path.string() + ": " + e.what());
    }
}

constexpr std::size_t kMaxSplinePoints = 100000;
constexpr std::size_t kMaxHeightfieldSide = 4096;

/// `spline {points, radius, closed, hollow}`: a tube around a Catmull–Rom curve (static only).
Shape parseSplineShape(const Validator& v, const ObjectReader& obj, const Node& typeNode,
                       bool isStatic) {
    if (!isStatic) {
        v.fail(typeNode.path, "a spline must be on a static body (add \"static\": true)");
    }
    obj.allowOnly({"type", "points", "radius", "closed", "hollow"});
    const Node pointsNode = obj.require("points", " (control points [[x, y, z], ...])");
    if (!pointsNode.value.is_array() || pointsNode.value.size() < 2) {
        const std::string got = pointsNode.value.is_array()
                                    ? "an array of " + std::to_string(pointsNode.value.size())
                                    : describe(pointsNode.value);
        v.fail(pointsNode.path, "must be an array of at least 2 points [x, y, z], got " + got);
    }
    if (pointsNode.value.size() > kMaxSplinePoints) {
        v.fail(pointsNode.path, "has more than " + std::to_string(kMaxSplinePoints) +
                                    " points (a sanity bound against absurd values)");
    }
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < pointsNode.value.size(); ++i) {
        points.push_back(v.vec3({pointsNode.value[i], elementPath(pointsNode.path, i)},
                                within(kMaxCoordinate)));
    }
    const double radius = v.number(obj.require("radius", " (the tube's radius)"),
                                   positiveUpTo(kMaxSize));
    bool closed = false, hollow = false;
    const auto closedNode = obj.get("closed");
    if (closedNode) closed = v.boolean(*closedNode);
    if (auto h = obj.get("hollow")) hollow = v.boolean(*h);
    if (closed) {
        // Distinct points, as the curve will see them (repeated neighbours merged).
        std::size_t distinct = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            distinct += i == 0 || points[i] != points[i - 1];
        }
        if (distinct > 1 && points.front() == points.back()) --distinct;
        if (distinct < 3) {
            v.fail(closedNode->path, "a closed spline needs at least 3 distinct points, got " +
                                         std::to_string(distinct));
        }
    }
    return splineShape(makeSplineTube(std::move(points), radius, closed, hollow));
}

/// `heightfield {heights, size}`: rows of heights along z, each along x (static only).
Shape parseHeightfieldShape(const Validator& v, const ObjectReader& obj, const Node& typeNode,
                            bool isStatic) {
    if (!isStatic) {
        v.fail(typeNode.path, "a heightfield must be on a static body (add \"static\": true)");
    }
    obj.allowOnly({"type", "heights", "size"});
    const Node heightsNode = obj.require("heights", " (rows along z of heights along x)");
    const Json& rows = heightsNode.value;
    if (!rows.is_array() || rows.size() < 2) {
        const std::string got =
            rows.is_array() ? "an array of " + std::to_string(rows.size()) : describe(rows);
        v.fail(heightsNode.path, "must be an array of at least 2 rows, got " + got);
    }
    if (rows.size() > kMaxHeightfieldSide) {
        v.fail(heightsNode.path, "has more than " + std::to_string(kMaxHeightfieldSide) +
                                     " rows (a sanity bound against absurd values)");
    }
    std::vector<double> heights;
    std::size_t columns = 0;
    for (std::size_t j = 0; j < rows.size(); ++j) {
        const std::string rowPath = elementPath(heightsNode.path, j);
        const Json& row = rows[j];
        if (!row.is_array()) v.fail(rowPath, "must be an array of heights, got " + describe(row));
        if (j == 0) {
            columns = row.size();
            if (columns < 2 || columns > kMaxHeightfieldSide) {
                v.fail(rowPath, "must hold 2 to " + std::to_string(kMaxHeightfieldSide) +
                                    " heights, got " + std::to_string(columns));
            }
        } else if (row.size() != columns) {
            v.fail(rowPath, "must hold " + std::to_string(columns) + " heights like row 0, got " +
                                std::to_string(row.size()));
        }
        for (std::size_t i = 0; i < row.size(); ++i) {
            heights.push_back(v.number({row[i], elementPath(rowPath, i)}, within(kMaxCoordinate)));
        }
    }
    const auto size = v.numbers(obj.require("size", " (extents [x, z])"), 2,
                                positiveUpTo(kMaxCoordinate), "an array [x, z] of 2 numbers");
    return heightfieldShape(makeHeightfield(static_cast<int>(columns),
                                            static_cast<int>(rows.size()), std::move(heights),
                                            size[0], size[1]));
}

Shape parseShape(const Validator& v, const Node& node, bool isStatic) {
    const ObjectReader obj(v, node);
    const Node typeNode = obj.require("type", " (sphere, box, capsule, cylinder or plane)");
    const std::string type = v.string(typeNode);

    if (type == "mesh") return parseMeshShape(v, obj, typeNode, isStatic);
    if (type == "spline") return parseSplineShape(v, obj, typeNode, isStatic);
    if (type == "heightfield") return parseHeightfieldShape(v, obj, typeNode, isStatic);
    if (type == "sphere") {
        obj.allowOnly({"type", "radius"});
        return sphereShape(v.number(obj.require("radius"), positiveUpTo(kMaxSize)));
    }
    if (type == "box") {
        obj.allowOnly({"type", "size"});
        return boxShape(
            v.vec3(obj.require("size", " (full extents [x, y, z])"), positiveUpTo(kMaxSize)));
    }
    if (type == "capsule") {
        obj.allowOnly({"type", "radius", "length"});
        const double radius = v.number(obj.require("radius"), positiveUpTo(kMaxSize));
        const double length = v.number(obj.require("length", " (segment between the cap centres)"),
                                       nonNegativeUpTo(kMaxSize));
        return capsuleShape(radius, length);
    }
    if (type == "cylinder") {
        obj.allowOnly({"type", "radius", "length"});
        const double radius = v.number(obj.require("radius"), positiveUpTo(kMaxSize));
        const double length = v.number(obj.require("length", " (between the flat faces)"),
                                       positiveUpTo(kMaxSize));
        return cylinderShape(radius, length);
    }
    if (type == "plane") {
        if (!isStatic) {
            v.fail(typeNode.path, "a plane must be on a static body (add \"static\": true)");
        }
        obj.allowOnly({"type", "normal", "offset"});
        Vec3 normal = Vec3::UnitY();
        double offset = 0.0;
        if (auto n = obj.get("normal")) normal = v.direction(*n);
        if (auto o = obj.get("offset")) offset = v.number(*o, within(kMaxCoordinate));
        return planeShape(normal, offset);
    }
    v.fail(typeNode.path,
           "unknown shape type " + jsonQuoted(type) +
               " (expected sphere, box, capsule, cylinder, plane, mesh, heightfield or spline)");
}

SceneBody parseBody(const Validator& v, const Node& node,
                    const std::vector<std::pair<std::string, std::string>>& namesSoFar) {
    const ObjectReader obj(v, node, "a body object");
    obj.allowOnly({"name", "shape", "static", "mass", "density", "position", "orientation",
                   "velocity", "angular_velocity", "friction", "restitution", "collide"});
    SceneBody body;
    BodyDef& def = body.def;

    if (auto n = obj.get("name")) {
        body.name = v.name(*n);
        if (body.name == "world") {
            v.fail(n->path, "\"world\" is reserved: joints use it for the world itself");
        }
        for (const auto& [other, otherPath] : namesSoFar) {
            if (other == body.name) {
                v.fail(n->path, "duplicate body name " + jsonQuoted(body.name) +
                                    " (already used at " + otherPath + ")");
            }
        }
    }

    bool isStatic = false;
    if (auto s = obj.get("static")) isStatic = v.boolean(*s);
    def.type = isStatic ? BodyType::Static : BodyType::Dynamic;
    def.shape = parseShape(
        v, obj.require("shape", " (e.g. {\"type\": \"sphere\", \"radius\": 0.5})"), isStatic);

    // Mass: static bodies have none; dynamic ones take a mass or a density, not both.
    const auto mass = obj.get("mass");
    const auto density = obj.get("density");
    if (isStatic) {
        if (mass)
            v.fail(mass->path, "a static body has no mass (remove it, or make the body dynamic)");
        if (density)
            v.fail(density->path,
                   "a static body has no density (remove it, or make the body dynamic)");
    }
    if (mass && density) v.fail(density->path, "give mass or density, not both");
    if (mass) def.mass = v.number(*mass, positiveUpTo(kMaxMass));
    if (density) def.density = v.number(*density, positiveUpTo(kMaxDensity));
    if (!isStatic && !mass) {
        const double derived = def.density * shapeVolume(def.shape);
        if (derived > kMaxMass) {
            v.fail(density ? density->path : obj.pathOf("shape"),
                   "density " + formatNumber(def.density) + " kg/m³ gives this shape a mass of " +
                       formatNumber(derived) + " kg, above the 1e+09 kg sanity bound");
        }
    }

    const bool isPlane = def.shape.type == ShapeType::Plane;
    if (auto p = obj.get("position")) {
        def.position = v.vec3(*p, within(kMaxCoordinate));
        if (isPlane && !def.position.isZero(0.0)) {
            v.fail(p->path,
                   "a plane is placed by its normal and offset (world coordinates), not by "
                   "a position");
        }
    }
    if (auto q = obj.get("orientation")) {
        def.orientation = v.quaternion(*q);
        if (isPlane && def.orientation.vec().norm() > kDirectionEpsilon) {
            v.fail(q->path,
                   "a plane is placed by its normal and offset (world coordinates), not by "
                   "an orientation");
        }
    }
    if (auto vel = obj.get("velocity")) {
        def.velocity = v.vec3(*vel, within(kMaxSpeed));
        if (isStatic && !def.velocity.isZero(0.0)) v.fail(vel->path, "a static body does not move");
    }
    if (auto w = obj.get("angular_velocity")) {
        def.angularVelocity = v.vec3(*w, within(kMaxSpeed));
        if (isStatic && !def.angularVelocity.isZero(0.0))
            v.fail(w->path, "a static body does not move");
    }

    if (auto f = obj.get("friction")) {
        const ObjectReader friction(v, *f, "an object {\"static\": μs, \"dynamic\": μd}");
        friction.allowOnly({"static", "dynamic"});
        if (auto s = friction.get("static"))
            def.staticFriction = v.number(*s, nonNegativeUpTo(kMaxFriction));
        if (auto d = friction.get("dynamic"))
            def.dynamicFriction = v.number(*d, nonNegativeUpTo(kMaxFriction));
    }
    if (auto e = obj.get("restitution")) def.restitution = v.number(*e, closed(0.0, 1.0));
    if (auto c = obj.get("collide")) def.collide = v.boolean(*c);
    return body;
}

/// Bit per joint type, for the table of which keys each type uses.
constexpr unsigned bit(JointType type) {
    return 1u << static_cast<unsigned>(type);
}
constexpr unsigned kDistance = bit(JointType::Distance);
constexpr unsigned kFixed = bit(JointType::Fixed);
constexpr unsigned kHinge = bit(JointType::Hinge);
constexpr unsigned kSpherical = bit(JointType::Spherical);
constexpr unsigned kPrismatic = bit(JointType::Prismatic);
constexpr unsigned kAllJoints = kDistance | kFixed | kHinge | kSpherical | kPrismatic;
constexpr unsigned kFramed = kFixed | kHinge | kSpherical | kPrismatic;  // those with axes

struct JointKey {
    const char* key;
    unsigned types;
};

// A distance joint links two points: it has no axes. Fixed joints use their frames (axis and
// normal) as the locked relative orientation.
constexpr JointKey kJointKeys[] = {
    {"name", kAllJoints},
    {"type", kAllJoints},
    {"body0", kAllJoints},
    {"body1", kAllJoints},
    {"anchor0", kAllJoints},
    {"anchor1", kAllJoints},
    {"compliance", kAllJoints},
    {"damping", kAllJoints},
    {"collide", kAllJoints},
    {"axis0", kFramed},
    {"axis1", kFramed},
    {"normal0", kFramed},
    {"normal1", kFramed},
    {"max_distance", kDistance},
    {"limits", kHinge | kPrismatic},
    {"limit_compliance", kHinge | kPrismatic | kSpherical},
    {"target_angle", kHinge},
    {"target_velocity", kHinge},
    {"target_offset", kPrismatic},
    {"drive_compliance", kHinge | kPrismatic},
    {"swing_limit", kSpherical},
    {"twist_limits", kSpherical},
    {"twist_compliance", kSpherical},
};

struct JointTypeName {
    const char* name;
    JointType type;
};
constexpr JointTypeName kJointTypes[] = {
    {"distance", JointType::Distance},   {"fixed", JointType::Fixed},
    {"hinge", JointType::Hinge},         {"spherical", JointType::Spherical},
    {"prismatic", JointType::Prismatic},
};

std::string jointTypesText(unsigned types) {
    std::vector<std::string> names;
    for (const auto& t : kJointTypes) {
        if (types & bit(t.type)) names.push_back(t.name);
    }
    return joinList(names, " and ");
}

std::string articled(const char* typeName) {
    return std::string(typeName[0] == 'a' || typeName[0] == 'e' || typeName[0] == 'i' ? "an "
                                                                                      : "a ") +
           typeName;
}

SceneJoint parseJoint(const Validator& v, const Node& node,
                      const std::vector<std::string>& bodyNames,
                      const std::vector<std::pair<std::string, std::string>>& jointNamesSoFar) {
    const ObjectReader obj(v, node, "a joint object");

    // The type decides which keys are allowed, so it comes first.
    const Node typeNode = obj.require("type", " (distance, fixed, hinge, spherical or prismatic)");
    const std::string typeText = v.string(typeNode);
    const JointTypeName* typeEntry = nullptr;
    for (const auto& t : kJointTypes) {
        if (typeText == t.name) typeEntry = &t;
    }
    if (!typeEntry) {
        v.fail(typeNode.path, "unknown joint type " + jsonQuoted(typeText) +
                                  " (expected distance, fixed, hinge, spherical or prismatic)");
    }
    const JointType type = typeEntry->type;

    std::vector<std::string> allowed;
    for (const auto& k : kJointKeys) {
        if (k.types & bit(type)) allowed.push_back(k.key);
    }
    for (const auto& [key, value] : obj.value().items()) {
        const auto known = std::find_if(std::begin(kJointKeys), std::end(kJointKeys),
                                        [&](const JointKey& k) { return key == k.key; });
        if (known == std::end(kJointKeys)) obj.failUnknown(key, allowed);
        if (!(known->types & bit(type))) {
            v.fail(obj.pathOf(key), "does not apply to " + articled(typeEntry->name) +
                                        " joint (only to " + jointTypesText(known->types) +
                                        " joints)");
        }
    }

    SceneJoint joint;
    JointDef& def = joint.def;
    def.type = type;

    if (auto n = obj.get("name")) {
        joint.name = v.name(*n);
        for (const auto& [other, otherPath] : jointNamesSoFar) {
            if (other == joint.name) {
                v.fail(n->path, "duplicate joint name " + jsonQuoted(joint.name) +
                                    " (already used at " + otherPath + ")");
            }
        }
    }

    // Bodies: names of bodies defined in "bodies"; omitted or "world" is the world.
    const auto readBody = [&](const char* key) -> std::string {
        const auto b = obj.get(key);
        if (!b) return "";
        std::string name = v.string(*b);
        if (name.empty())
            v.fail(b->path,
                   "must name a body (leave the key out, or say \"world\", for the world)");
        if (name == "world") return name;
        if (std::find(bodyNames.begin(), bodyNames.end(), name) == bodyNames.end()) {
            v.fail(b->path, "no body named " + jsonQuoted(name) + suggestion(name, bodyNames));
        }
        return name;
    };
    joint.body0 = readBody("body0");
    joint.body1 = readBody("body1");
    const bool world0 = joint.body0.empty() || joint.body0 == "world";
    const bool world1 = joint.body1.empty() || joint.body1 == "world";
    if (world0 && world1) {
        const std::string path = obj.has("body1")   ? obj.pathOf("body1")
                                 : obj.has("body0") ? obj.pathOf("body0")
                                                    : obj.path();
        v.fail(path, "both ends of the joint are the world: body0 or body1 must name a body");
    }
    if (!world0 && joint.body0 == joint.body1) {
        v.fail(obj.pathOf("body1"), "joins body " + jsonQuoted(joint.body1) + " to itself");
    }

    if (auto a = obj.get("anchor0")) def.anchor0 = v.vec3(*a, within(kMaxCoordinate));
    if (auto a = obj.get("anchor1")) def.anchor1 = v.vec3(*a, within(kMaxCoordinate));
    if (auto a = obj.get("axis0")) def.axis0 = v.direction(*a);
    if (auto a = obj.get("axis1")) def.axis1 = v.direction(*a);
    // Normals: not parallel to their axis, then made exactly perpendicular to it.
    const auto readNormal = [&](const char* key, const Vec3& axis) -> std::optional<Vec3> {
        const auto n = obj.get(key);
        if (!n) return std::nullopt;
        const Vec3 normal = v.direction(*n);
        const Vec3 perpendicular = normal - normal.dot(axis) * axis;
        if (perpendicular.norm() <= kParallelSine) {
            v.fail(n->path, "is parallel to the joint axis (a normal must be perpendicular to it)");
        }
        return perpendicular.normalized();
    };
    def.normal0 = readNormal("normal0", def.axis0);
    def.normal1 = readNormal("normal1", def.axis1);
    if (auto c = obj.get("compliance"))
        def.compliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));

    if (auto d = obj.get("max_distance"))
        def.maxDistance = v.number(*d, nonNegativeUpTo(kMaxCoordinate));
    if (auto l = obj.get("limits")) {
        def.limits =
            type == JointType::Hinge ? v.angleRange(*l) : v.range(*l, within(kMaxCoordinate));
    }
    if (auto c = obj.get("limit_compliance"))
        def.limitCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    if (auto t = obj.get("target_angle")) def.targetAngle = v.angle(*t, -kPi, kPi, "-pi", "pi");
    if (auto t = obj.get("target_velocity")) {
        if (def.targetAngle) {
            v.fail(t->path, "give target_angle (a drive) or target_velocity (a motor), not both");
        }
        def.targetVelocity = v.number(*t, within(kMaxSpeed));
    }
    if (auto t = obj.get("target_offset")) def.targetOffset = v.number(*t, within(kMaxCoordinate));
    if (auto c = obj.get("drive_compliance"))
        def.driveCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    if (auto s = obj.get("swing_limit")) def.swingLimit = v.angle(*s, 0.0, kPi, "0", "pi");
    if (auto t = obj.get("twist_limits")) def.twistLimits = v.angleRange(*t);
    if (auto c = obj.get("twist_compliance"))
        def.twistCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));

    if (auto d = obj.get("damping")) {
        const ObjectReader damping(v, *d, "an object {\"linear\": ..., \"angular\": ...}");
        damping.allowOnly({"linear", "angular"});
        if (auto l = damping.get("linear"))
            def.linearDamping = v.number(*l, nonNegativeUpTo(kMaxDamping));
        if (auto a = damping.get("angular"))
            def.angularDamping = v.number(*a, nonNegativeUpTo(kMaxDamping));
    }
    if (auto c = obj.get("collide")) def.collide = v.boolean(*c);
    return joint;
}

SceneCamera parseCamera(const Validator& v, const Node& node) {
    const ObjectReader obj(v, node, "an object {\"position\", \"target\", \"fov\"}");
    obj.allowOnly({"position", "target", "fov"});
    SceneCamera camera;
    if (auto p = obj.get("position")) camera.position = v.vec3(*p, within(kMaxCoordinate));
    if (auto t = obj.get("target")) camera.target = v.vec3(*t, within(kMaxCoordinate));
    if (auto f = obj.get("fov")) {
        camera.fov =
            v.number(*f, {.lo = 0, .hi = kPi, .loOpen = true, .hiOpen = true, .hiText = "pi"});
    }
    if ((camera.target - camera.position).norm() <= kDirectionEpsilon) {
        v.fail(obj.has("target") ? obj.pathOf("target") : obj.pathOf("position"),
               "the camera target must differ from its position");
    }
    return camera;
}

SceneDescription parseDocument(const Validator& v, const Json& root) {
    const ObjectReader top(v, {root, ""}, "a JSON object");

    // The version decides how to read everything else, so it is checked first.
    const auto version = top.get("substep_scene");
    if (!version) {
        v.fail("substep_scene", "missing: a scene file starts with \"substep_scene\": 1");
    }
    if (!version->value.is_number() || version->value != 1) {
        v.fail(version->path, version->value.is_number()
                                  ? "unsupported version " + describe(version->value) +
                                        " (this build reads version 1)"
                                  : "must be 1, got " + describe(version->value));
    }
    top.allowOnly({"substep_scene", "name", "description", "gravity", "dt", "substeps",
                   "iterations", "bodies", "joints", "camera"});

    SceneDescription scene;
    // Documented extension: a title and a description, for people reading the file.
    if (auto n = top.get("name")) v.string(*n);
    if (auto d = top.get("description")) v.string(*d);

    if (auto g = top.get("gravity")) scene.gravity = v.vec3(*g, within(kMaxGravity));
    if (auto dt = top.get("dt")) scene.dt = v.number(*dt, {.lo = 0, .hi = 1, .loOpen = true});
    if (auto s = top.get("substeps")) scene.substeps = v.integer(*s, 1, kMaxSubsteps);
    if (auto i = top.get("iterations")) scene.iterations = v.integer(*i, 1, kMaxIterations);

    std::vector<std::pair<std::string, std::string>> bodyNames;  // name, path
    if (auto bodies = top.get("bodies")) {
        if (!bodies->value.is_array()) {
            v.fail(bodies->path, "must be an array of bodies, got " + describe(bodies->value));
        }
        for (std::size_t i = 0; i < bodies->value.size(); ++i) {
            const Node node{bodies->value[i], elementPath(bodies->path, i)};
            scene.bodies.push_back(parseBody(v, node, bodyNames));
            if (!scene.bodies.back().name.empty()) {
                bodyNames.emplace_back(scene.bodies.back().name, memberPath(node.path, "name"));
            }
        }
    }

    std::vector<std::string> names;
    for (const auto& [name, path] : bodyNames)
        names.push_back(name);
    std::vector<std::pair<std::string, std::string>> jointNames;
    if (auto joints = top.get("joints")) {
        if (!joints->value.is_array()) {
            v.fail(joints->path, "must be an array of joints, got " + describe(joints->value));
        }
        for (std::size_t i = 0; i < joints->value.size(); ++i) {
            const Node node{joints->value[i], elementPath(joints->path, i)};
            scene.joints.push_back(parseJoint(v, node, names, jointNames));
            if (!scene.joints.back().name.empty()) {
                jointNames.emplace_back(scene.joints.back().name, memberPath(node.path, "name"));
            }
        }
    }

    if (auto c = top.get("camera")) scene.camera = parseCamera(v, *c);
    return scene;
}

}  // namespace

SceneDescription parseSceneText(std::string_view text, const std::string& fileLabel) {
    if (std::all_of(text.begin(), text.end(),
                    [](char c) { return std::isspace(static_cast<unsigned char>(c)); })) {
        throw SceneError(fileLabel, "",
                         "the file is empty (a scene starts with {\"substep_scene\": 1})");
    }
    Json root;
    DocumentBuilder builder(root, text, fileLabel);
    // strict: nothing may follow the document; comments are not JSON.
    Json::sax_parse(text, &builder, Json::input_format_t::json, true, false);

    SceneDescription scene = parseDocument(Validator(fileLabel), root);
    scene.name = std::filesystem::path(fileLabel).stem().string();
    return scene;
}

SceneDescription loadSceneFile(const std::string& path) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw SceneError(path, "", "cannot read: is a directory, not a scene file");
    }
    const auto size = std::filesystem::file_size(path, error);
    if (!error && size > kMaxFileBytes) {
        throw SceneError(path, "", "cannot read: larger than 256 MiB, too large for a scene file");
    }
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int code = errno;
        throw SceneError(
            path, "",
            std::string("cannot read: ") + (code != 0 ? std::strerror(code) : "failed to open"));
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw SceneError(path, "", "cannot read: I/O error while reading");
    return parseSceneText(text.str(), path);
}

}  // namespace substep

#pragma once
/// Scene files, the validator of the loader: the bounds every value is checked against (the
/// table in docs/SCENE_FORMAT.md), typed reads that check a value and report its JSON path
/// (Validator), and objects whose keys are checked against what their context allows
/// (ObjectReader). Every failure throws one SceneError `FILE: JSON.PATH: what is wrong`.
///
/// Internal to the scene library (public entry points: scene_loader.h). A reader of a new
/// top-level key (scene_loader_sections.h) reads its values through these, so its messages
/// read like every other.

#include "physics/joints/joint.h"
#include "physics/math.h"
#include "scene/scene_loader_json.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace substep::scene_loader {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kPi = M_PI;

// Bounds; the (sanity) ones reject values that can only be typing mistakes.
inline constexpr double kMaxGravity = 1e4;     // m/s² per component
inline constexpr double kMaxCoordinate = 1e6;  // m
inline constexpr double kMaxSize = 1e4;        // m
inline constexpr double kMaxMass = 1e9;        // kg
inline constexpr double kMaxDensity = 1e6;     // kg/m³
inline constexpr double kMaxSpeed = 1e5;       // m/s, rad/s
inline constexpr double kMaxCompliance = 1e9;  // m/N, rad/(N m)
inline constexpr double kMaxDamping = 1e6;     // 1/s
inline constexpr double kMaxFriction = 1e3;
inline constexpr double kAngleTolerance = 1e-4;  // rad beyond ±pi accepted as rounding, clamped
inline constexpr double kParallelSine = 1e-6;
/// Lower bounds with a physical reason: below them a body's mass, inertia or the time step
/// underflow or lose their precision (a 1e-320 m box went NaN at frame 1; a 1e-110 m sphere
/// weighed exactly 0 and froze). 0.1 mm, 1 mg and 1 µs are far below anything the engine is
/// meant to simulate.
inline constexpr double kMinSize = 1e-4;      // m: radii, extents, lengths, scales
inline constexpr double kMinMass = 1e-6;      // kg, given or derived from the density
inline constexpr double kMinInertia = 1e-15;  // kg m², each principal moment
inline constexpr int kMaxSubsteps = 10000;
inline constexpr int kMaxIterations = 1000;

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
    /// Within (lo, hi] but below this, a value underflows what it feeds (a mass, an inertia):
    /// reported after the rule above, with its own message.
    double least = -kInf;
};

/// (0, max], the upper bound a sanity bound.
Interval positiveUpTo(double max);
/// (0, max] and at least kMinSize: a size (radius, extent, length, scale).
Interval sizeUpTo(double max);
/// [0, max], the upper bound a sanity bound.
Interval nonNegativeUpTo(double max);
/// [-max, max], both sanity bounds.
Interval within(double max);
/// [lo, hi], both rules of the format.
Interval closed(double lo, double hi, const char* loText = nullptr, const char* hiText = nullptr);
/// Angles in [lo, hi] with a little slack at ±pi for rounded literals; values are clamped after.
Interval angles(double lo, double hi, const char* loText, const char* hiText);

/// Empty when `value` lies in `interval`, else what is wrong (`must be > 0, got -1`).
std::string checkInterval(double value, const Interval& interval);

/// A value in the document and its JSON path.
struct Node {
    const Json& value;
    std::string path;
};

/// Typed reads of document values, each checked and reported at its node's path.
class Validator {
  public:
    /// `file` names the scene file in messages; it must outlive the validator.
    explicit Validator(const std::string& file) : file_(file) {}

    /// The scene file as named in messages (mesh files are found relative to its folder).
    const std::string& file() const { return file_; }

    /// Throws SceneError(file, path or "top level", problem).
    [[noreturn]] void fail(const std::string& path, const std::string& problem) const;

    /// A finite number in `interval`.
    double number(const Node& node, const Interval& interval = {}) const;
    /// An angle in [lo, hi] (given with a little slack at ±pi and clamped).
    double angle(const Node& node, double lo, double hi, const char* loText,
                 const char* hiText) const;
    /// An integer in [lo, hi]; `20.0` counts, `20.5` does not.
    int integer(const Node& node, int lo, int hi) const;
    bool boolean(const Node& node) const;
    std::string string(const Node& node) const;

    /// An array of exactly n numbers, each in `interval` (paths name the element); `what`
    /// describes the expected array in the message.
    std::vector<double> numbers(const Node& node, std::size_t n, const Interval& interval,
                                const char* what) const;
    /// [x, y, z], each component in `interval`.
    Vec3 vec3(const Node& node, const Interval& interval) const;
    /// A non-zero vector, normalised.
    Vec3 direction(const Node& node) const;
    /// A non-zero quaternion [w, x, y, z], normalised.
    Quat quaternion(const Node& node) const;
    /// [lo, hi] with both ends in `interval` and lo <= hi.
    Range range(const Node& node, const Interval& interval) const;
    /// A range of angles within [-pi, pi] (clamped after the rounding slack).
    Range angleRange(const Node& node) const;
    /// A name for CSV columns and joint references.
    std::string name(const Node& node) const;

  private:
    const std::string& file_;
};

/// An object whose keys are checked against what its context allows.
class ObjectReader {
  public:
    /// Fails unless `node` is an object; `what` describes the expected object in the message.
    ObjectReader(const Validator& validator, const Node& node, const char* what = "an object");

    const std::string& path() const { return path_; }
    std::string pathOf(std::string_view key) const { return memberPath(path_, key); }

    bool has(std::string_view key) const { return value_.contains(key); }

    /// The member `key`, if present.
    std::optional<Node> get(std::string_view key) const;

    /// The member `key`; fails with `missing (required)` and `hint` when absent.
    Node require(std::string_view key, const std::string& hint = "") const;

    /// Every key must be one of `allowed`.
    void allowOnly(const std::vector<std::string>& allowed) const;

    /// Fails with `unknown key` at `key`, suggesting the nearest of `allowed` or listing them.
    [[noreturn]] void failUnknown(const std::string& key,
                                  const std::vector<std::string>& allowed) const;

    const Json& value() const { return value_; }

  private:
    const Validator& validator_;
    const Json& value_;
    std::string path_;
};

}  // namespace substep::scene_loader

#pragma once
/// Capture scripts (DESIGN.md "Capture scripts"): which scenes to run, with which settings, and
/// what to compare at which frames. parseCaptureScript validates the whole file before anything
/// runs; every problem is one InputError naming the file and the JSON path
/// (`gallery.json: captures[0].frames`).

#include "scene/scene.h"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace substep::capture {

/// |a − b| ≤ abs + rel·|b|, b the golden value. Zero and zero: exact.
struct Tolerance {
    double abs = 0.0;
    double rel = 0.0;
    bool exact() const { return abs == 0.0 && rel == 0.0; }
};

/// What `state` compares: every body, joint and soft body, with a tolerance for all and
/// (an addition to DESIGN.md) per named body or joint.
struct StateCheck {
    Tolerance tolerance;
    std::map<std::string, Tolerance> bodies;  ///< by body name
    std::map<std::string, Tolerance> joints;  ///< by joint name
    /// True when every tolerance is exact: the run's digest must then match too.
    bool exact() const;
};

/// What `image` compares.
struct ImageCheck {
    int width = 160;
    int height = 120;
    std::optional<SceneCamera> camera;  ///< none: the scene's own, else one that frames the bodies
    int pixelTolerance = 0;             ///< a pixel differs when a channel differs by more
    double maxFraction = 0.0;           ///< the capture fails when more pixels than this differ
};

/// Bounds over the captured run (frames 0 to the last captured), whatever the goldens say.
struct MetricBounds {
    std::optional<double> maxJointError;  ///< m
    std::optional<double> energyDrift;    ///< max |E(t) − E(0)| / energy scale (as `sweep`)
    std::optional<double> penetration;    ///< deepest contact overlap, m
    bool any() const { return maxJointError || energyDrift || penetration; }
};

struct CaptureSpec {
    std::string name;
    std::string scene;      ///< as written in the script
    std::string scenePath;  ///< the built-in name, or the file resolved against the script's folder
    std::vector<std::pair<std::string, double>> knobs;  ///< `set`, in file order
    std::optional<int> substeps;
    std::optional<int> iterations;
    std::optional<double> dt;
    std::vector<long long> frames;  ///< strictly increasing
    std::optional<StateCheck> state;
    std::optional<ImageCheck> image;
    MetricBounds metrics;
    std::string path;  ///< `captures[3]`, for messages
};

struct CaptureScript {
    std::string file;          ///< as given on the command line
    std::string goldenFolder;  ///< SCRIPT without `.json`, then `.golden`
    std::vector<CaptureSpec> captures;
};

/// Accepted values.
inline constexpr long long kMaxCaptureFrame = 1'000'000;
inline constexpr std::size_t kMaxCaptureFrames = 1000;  ///< frames listed per capture
inline constexpr int kMaxCaptureImageSide = 4096;

/// Reads and validates the script at `file`. Throws InputError.
CaptureScript parseCaptureScript(const std::string& file);

/// Validates script text; `file` names it in messages and places relative scene files and goldens.
CaptureScript parseCaptureScriptText(std::string_view text, const std::string& file);

}  // namespace substep::capture

#pragma once
/// Scene files (JSON, version 1; DESIGN.md "Scene files"): parsing and complete validation into a
/// SceneDescription. Every problem is reported as one SceneError naming the file and the JSON path
/// of the offending value, so the `substep` command can print it and exit with code 2.
/// The format's rules and bounds: docs/SCENE_FORMAT.md. How the loader is laid out, and where a
/// reader of a new top-level key plugs in: scene_loader.cpp and scene_loader_sections.h.

#include "scene/scene.h"

#include <stdexcept>
#include <string>
#include <string_view>

namespace substep {

/// The accepted frame length, a file's `dt` and the command line's `--dt` alike (s): below
/// 1 µs the substep length loses its precision (1e-320 went NaN at frame 1), above 1 s a frame
/// is no longer a frame.
inline constexpr double kMinTimeStep = 1e-6;
inline constexpr double kMaxTimeStep = 1.0;

/// A scene file that cannot be read or is not a valid scene. what() is the complete one-line
/// message, `FILE: JSON.PATH: what is wrong` (e.g.
/// `scenes/a.json: bodies[3].shape.radius: must be > 0, got -1`), or `FILE: what is wrong` for
/// problems with the file as a whole (unreadable).
class SceneError : public std::runtime_error {
  public:
    /// `path` may be empty when the problem is the file itself.
    SceneError(const std::string& file, const std::string& path, const std::string& problem);

    const std::string& file() const { return file_; }
    /// JSON path of the offending value (`bodies[0].position[1]`), "top level" for the document
    /// itself, empty for file-level problems.
    const std::string& path() const { return path_; }
    /// The description without file and path (`must be > 0, got -1`).
    const std::string& problem() const { return problem_; }

  private:
    std::string file_;
    std::string path_;
    std::string problem_;
};

/// Reads and validates a scene file. The description's name is the file's stem
/// (`scenes/cradle.json` -> `cradle`). Throws SceneError, also when the file cannot be read.
SceneDescription loadSceneFile(const std::string& path);

/// Validates scene text; `fileLabel` names the source in messages and its stem names the scene.
/// Throws SceneError.
SceneDescription parseSceneText(std::string_view text, const std::string& fileLabel);

}  // namespace substep

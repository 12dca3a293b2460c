#pragma once
/// Watches the JSON file a viewed scene came from, so the viewer reloads it when it is saved
/// (edit the file in one window, see the scene in the other).

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

namespace substep::view {

class SceneFileWatch {
  public:
    /// Watches `path`; an empty path (a built-in scene) watches nothing.
    void watch(const std::string& path);

    /// True once each time the file's modification time has changed since watch() or the last
    /// true answer. Looks at the file at most every `interval`, so a frame loop may ask freely;
    /// a file that vanishes (an editor saving by rename) counts as unchanged until it is back.
    bool changed(std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

    static constexpr std::chrono::milliseconds interval{250};

  private:
    std::filesystem::path path_;
    std::optional<std::filesystem::file_time_type> stamp_;
    std::chrono::steady_clock::time_point nextLook_{};
};

}  // namespace substep::view

#include "view/scene_file_watch.h"

#include <system_error>

namespace substep::view {
namespace {

std::optional<std::filesystem::file_time_type> modificationTime(const std::filesystem::path& path) {
    std::error_code error;
    const auto time = std::filesystem::last_write_time(path, error);
    if (error) return std::nullopt;
    return time;
}

}  // namespace

void SceneFileWatch::watch(const std::string& path) {
    path_ = path;
    stamp_ = path.empty() ? std::nullopt : modificationTime(path_);
    nextLook_ = {};
}

bool SceneFileWatch::changed(std::chrono::steady_clock::time_point now) {
    if (path_.empty() || now < nextLook_) return false;
    nextLook_ = now + interval;
    const auto stamp = modificationTime(path_);
    if (!stamp || stamp == stamp_) return false;
    stamp_ = stamp;
    return true;
}

}  // namespace substep::view

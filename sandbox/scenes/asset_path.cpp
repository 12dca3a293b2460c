#include "scenes/asset_path.h"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace substep {
namespace {

namespace fs = std::filesystem;

/// The folders that may hold assets, in search order.
std::vector<fs::path> assetFolders() {
    std::vector<fs::path> folders;
    if (const char* dir = std::getenv("SUBSTEP_ASSET_DIR"); dir != nullptr && *dir != '\0')
        folders.emplace_back(dir);
    // Linux names the running executable here; elsewhere this part of the search is skipped.
    std::error_code error;
    const fs::path executable = fs::read_symlink("/proc/self/exe", error);
    if (!error) {
        fs::path dir = executable.parent_path();
        for (int up = 0; up < 3 && !dir.empty(); ++up, dir = dir.parent_path()) {
            folders.push_back(dir / "assets");
            folders.push_back(dir / "share" / "substep" / "assets");
        }
    }
#ifdef SUBSTEP_SOURCE_DIR
    folders.push_back(fs::path(SUBSTEP_SOURCE_DIR) / "assets");
#endif
    return folders;
}

}  // namespace

fs::path findAsset(std::string_view relative) {
    const std::vector<fs::path> folders = assetFolders();
    for (const fs::path& folder : folders) {
        std::error_code error;
        const fs::path candidate = folder / relative;
        if (fs::is_regular_file(candidate, error)) return candidate;
    }
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a known false positive) on a literal
    // joined to a temporary string with operator+.
    std::string message = "asset '";
    message.append(relative).append("' not found; looked in");
    for (const fs::path& folder : folders) message.append(" ").append(folder.string()).append(",");
    message += " (set SUBSTEP_ASSET_DIR to the folder holding it)";
    throw std::runtime_error(message);
}

}  // namespace substep

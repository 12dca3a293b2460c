#pragma once
/// Finding the repository's asset files (assets/meshes/bunny.obj, ...) at run time, wherever the
/// program was started from: built-in scenes that load a mesh call this from their builders.

#include <filesystem>
#include <string_view>

namespace substep {

/// The file `relative` (e.g. "meshes/bunny.obj") under the first assets folder that holds it:
/// $SUBSTEP_ASSET_DIR, then assets/ next to the executable and up to two folders above it (a
/// build tree, an install's share/substep/assets), then the source tree the program was built
/// from. Throws std::runtime_error naming the file and every place searched when none has it.
std::filesystem::path findAsset(std::string_view relative);

}  // namespace substep

#pragma once
/// The goldens of a capture script on disk: `SCRIPT.golden/NAME/frame_NNNNN.json` (state),
/// `frame_NNNNN.png` (image) and `digest.txt` (the run's digest). Reading checks each file and
/// says what to do when one is missing or damaged; writing replaces a file atomically, and only
/// when its bytes change, so `--update` run twice changes nothing.

#include "capture/capture_state.h"
#include "render/image.h"

#include <string>
#include <vector>

namespace substep::capture {

/// What writeGolden did to a file.
enum class GoldenChange { Unchanged, Added, Changed };

const char* goldenChangeName(GoldenChange change);

/// Paths inside `goldenFolder` (CaptureScript::goldenFolder).
std::string captureFolder(const std::string& goldenFolder, const std::string& capture);
std::string stateFileName(long long frame);  ///< frame_00040.json
std::string imageFileName(long long frame);  ///< frame_00040.png
inline constexpr const char* kDigestFileName = "digest.txt";

/// Readers. A missing file throws InputError telling to run `substep capture SCRIPT --update`;
/// a damaged one (truncated, not JSON, not PNG) throws InputError naming what is wrong in it.
CaptureState readGoldenState(const std::string& path, const std::string& scriptFile);
render::Image readGoldenImage(const std::string& path, const std::string& scriptFile);
std::string readGoldenDigest(const std::string& path, const std::string& scriptFile);
/// Throws the missing-golden InputError when `path` is not a file.
void requireGolden(const std::string& path, const std::string& scriptFile);

/// Writes `bytes` to `path` through a temporary file and a rename, creating folders, unless
/// the file already holds exactly those bytes.
GoldenChange writeGolden(const std::string& path, const std::string& bytes);

/// Removes the files in `folder` that look like goldens (frame_*.json, frame_*.png, digest.txt)
/// but are not in `keep` (file names); returns the paths removed.
std::vector<std::string> removeStaleGoldens(const std::string& folder,
                                            const std::vector<std::string>& keep);

}  // namespace substep::capture

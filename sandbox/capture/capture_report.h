#pragma once
/// `--report DIR`: an HTML page, DIR/index.html, that shows for every capture whether it matched,
/// every mismatch line, for each differing image the golden, the new frame and a heat map of the
/// difference side by side (PNGs beside the page), and each differing state as a table.

#include "capture/capture_result.h"

#include <string>
#include <vector>

namespace substep::capture {

/// Creates DIR when missing. Throws OutputError naming --report when it is not a usable folder.
void prepareReportFolder(const std::string& directory);

/// Writes the page and its images, each file whole (temporary file, then rename). Throws
/// OutputError when DIR cannot be made or written.
void writeCaptureReport(const std::string& directory, const std::string& scriptFile,
                        const std::vector<CaptureResult>& results);

}  // namespace substep::capture

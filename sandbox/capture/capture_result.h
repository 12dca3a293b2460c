#pragma once
/// What comparing one capture found: the records the command prints a line per mismatch from and
/// the report draws its page from.

#include "capture/image_diff.h"
#include "capture/state_comparison.h"
#include "render/image.h"

#include <optional>
#include <string>
#include <vector>

namespace substep::capture {

/// A captured frame that differs from its goldens.
struct FrameMismatch {
    long long frame = 0;
    std::optional<StateComparison> state;  ///< set when the state differs
    std::optional<ImageComparison> image;  ///< set when the image differs
    int pixelTolerance = 0;
    double maxFraction = 0.0;
    render::Image golden;  ///< the golden and the new image, when the image differs
    render::Image fresh;
};

struct CaptureResult {
    std::string name;
    std::string scene;
    std::vector<std::string> lines;     ///< one summary line per mismatch, as printed
    std::vector<FrameMismatch> frames;  ///< the frames that differ
    bool checked = false;               ///< false: --only left it out
    bool matches() const { return lines.empty(); }
};

}  // namespace substep::capture

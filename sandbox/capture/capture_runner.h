#pragma once
/// Runs one capture: steps its scene from frame 0 to the last listed frame, keeping the state and
/// the image at each listed frame, the digest of every frame's state and the error measures.

#include "capture/capture_script.h"
#include "capture/capture_state.h"
#include "capture/frame_renderer.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace substep::capture {

struct CapturedFrame {
    long long frame = 0;
    std::optional<CaptureState> state;   ///< when the capture compares state
    std::optional<render::Image> image;  ///< when it compares images
};

struct CapturedRun {
    std::vector<CapturedFrame> frames;   ///< the listed frames reached, in order
    std::string digest;                  ///< RunDigest's line; empty without `state`
    RunMetrics metrics;                  ///< over frames 0 to the last reached
    std::optional<long long> nonFinite;  ///< the frame the state turned non-finite at
    int interrupted = 0;                 ///< the signal that stopped the run, or 0
};

/// Runs `spec` on `scene` (fresh, at frame 0). `renderer` must be given when the capture has an
/// image check. `progress` is called with each frame number reached.
CapturedRun runCapture(CaptureScene& scene, const CaptureSpec& spec, FrameRenderer* renderer,
                       const std::function<void(long long)>& progress);

}  // namespace substep::capture

#pragma once
/// The golden state file `frame_NNNNN.json`: one frame's CaptureState as JSON that people can
/// read and diff (a body, joint or soft body per line) with numbers in shortest round-trip form,
/// so a golden read back is exactly the state that was written.

#include "capture/capture_state.h"

#include <string>
#include <string_view>

namespace substep::capture {

/// The file's text. Same state, same bytes. The state must be finite (JSON has no NaN).
std::string formatStateFile(const CaptureState& state);

/// Reads a state file back. Throws InputError naming `file` and the JSON path of what is wrong
/// (a truncated or corrupted golden).
CaptureState parseStateFile(std::string_view text, const std::string& file);

}  // namespace substep::capture

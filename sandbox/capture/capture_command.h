#pragma once
/// `substep capture SCRIPT [--update] [--report DIR] [--only NAME ...]`: scripted regression
/// captures (DESIGN.md "Capture scripts"). Runs every capture of the script, compares each
/// listed frame's state and image with the goldens beside the script, checks the metric bounds,
/// and prints a line per mismatch; `--update` writes the goldens instead.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace substep {

struct CaptureOptions {
    std::string script;
    bool update = false;
    std::string reportDirectory;
    std::vector<std::string> only;  ///< capture names; empty: all
};

/// Declares `capture` and its options on `app`, bound to `options`.
CLI::App* addCaptureCommand(CLI::App& app, CaptureOptions& options);

/// Runs the captures. Returns 0 when everything matches (or the goldens were written), 1 when
/// something differs, a metric bound fails or a state turns non-finite, 2 for bad input (a
/// script error naming file and JSON path, a missing or damaged golden, no OpenGL context).
int captureCommand(const CaptureOptions& options);

}  // namespace substep

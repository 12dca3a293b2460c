#pragma once
/// `substep run SCENE`: the headless simulation of DESIGN.md's command contract. It steps the
/// scene frame by frame, records row 0 (the initial state) and a row per frame to `--csv`, and
/// writes the summary to `--json` and, in words, to stdout.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace substep {

/// The options as typed. Numbers stay text until runCommand checks them, so every bad value
/// gets the same kind of message (and `010` is ten, not CLI11's octal eight).
struct RunOptions {
    std::string scene;
    std::string frames;  ///< empty when not given
    std::string seconds;
    std::string substeps;
    std::string iterations;
    std::string dt;
    std::string csvPath;
    std::string jsonPath;
    std::vector<std::string> knobs;  ///< --set NAME=VALUE, in order
    std::string threads;             ///< --threads N (default 1)
    std::string jointProjection;     ///< "paper" or "start"; empty: the scene's
    std::string restitution;         ///< "swept" or "paper"; empty: the scene's
};

/// Accepted ranges (DESIGN.md for substeps and iterations; frames is a sanity bound).
inline constexpr long long kMaxSubsteps = 10000;
inline constexpr long long kMaxIterations = 1000;
inline constexpr long long kMaxFrames = 10'000'000;
/// Simulated time when neither --frames nor --seconds is given (s).
inline constexpr double kDefaultSeconds = 5.0;

/// Declares `run` and its options on `app`, bound to `options`.
CLI::App* addRunCommand(CLI::App& app, RunOptions& options);

/// Runs the simulation. Returns the exit code: 0 success, 1 the state turned non-finite,
/// 2 bad input (options, scene) or an output that cannot be written.
int runCommand(const RunOptions& options);

}  // namespace substep

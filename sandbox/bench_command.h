#pragma once
/// `substep bench [SCENE ...]`: milliseconds per frame per scene, laid out like the paper's
/// Table 1. Each scene runs at its own dt, substeps and iterations: a warm-up second, then
/// `--seconds` of simulated time with only world.step timed, `--repeats` times from a fresh
/// build; the figure reported is the median of the repeats' mean ms/frame. One thread.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace substep {

/// The options as typed; numbers stay text until benchCommand checks them (as in RunOptions).
struct BenchOptions {
    std::vector<std::string> scenes;  ///< empty: every built-in scene
    std::string jsonPath;
    std::string seconds;
    std::string repeats;
    std::string threads;  ///< --threads N (default 1)
    std::string warmUp;   ///< --warm-up T: untimed seconds before the timed ones (default 1)
    bool sleeping = false;  ///< --sleeping: WorldSettings::sleeping on in every scene
    std::string restitution;  ///< "swept" or "paper"; empty: each scene's
};

/// Defaults and accepted ranges.
inline constexpr double kBenchDefaultSeconds = 3.0;
inline constexpr double kBenchMaxSeconds = 3600.0;  ///< a sanity bound against typing mistakes
inline constexpr double kBenchWarmUpSeconds = 1.0;
inline constexpr long long kBenchDefaultRepeats = 3;
inline constexpr long long kBenchMaxRepeats = 100;

/// Declares `bench` and its options on `app`, bound to `options`.
CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options);

/// Runs the benchmark. Returns the exit code: 0 success, 1 some scene turned non-finite (it is
/// marked in the table and the JSON), 2 bad input (options, scenes) or an unwritable output.
int benchCommand(const BenchOptions& options);

}  // namespace substep

#pragma once
/// `substep sweep SCENE`: error against run time at fixed budgets (issue 6). For each budget
/// B = substeps x iterations it runs every split (B x 1, ..., 1 x B) from a fresh build of the
/// scene, times world.step frame by frame and records the error measures (error_measures.h).
/// One CSV row per split; an optional PNG plot drawn by tools/plot_sweep.py.

#include <CLI/CLI.hpp>

#include <string>

namespace substep {

/// The options as typed; runSweep checks them (numbers stay text, as in RunOptions).
struct SweepOptions {
    std::string scene;
    std::string budget;   ///< one budget; empty when not given
    std::string budgets;  ///< comma-separated list; empty when not given
    std::string seconds;  ///< simulated time per split (default 5 s)
    std::string csvPath;
    std::string plotPath;
    std::string threads;  ///< --threads N (default 1)
    std::string jointProjection;  ///< "paper" or "start"; empty: the scene's
    std::string restitution;      ///< "swept" or "paper"; empty: the scene's
};

/// Accepted budgets (a sanity bound: budget 10000 has 25 splits of 10000 passes per frame).
inline constexpr long long kMaxBudget = 10000;

/// The CSV header, in contract order: `budget,substeps,iterations,ms_per_frame`, then the
/// error measures.
inline constexpr const char* kSweepCsvHeader =
    "budget,substeps,iterations,ms_per_frame,energy_drift,energy_error_final,max_joint_error,"
    "mean_joint_error,chain_elongation,penetration";

/// Declares `sweep` and its options on `app`, bound to `options`.
CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options);

/// Runs the sweep. Returns the exit code: 0 success; 1 some split turned non-finite (its row
/// holds `inf` measures, the other rows and outputs are written); 2 bad input, an output that
/// cannot be written, or a plot that cannot be drawn (python3 or matplotlib missing; the CSV
/// is still written). The plotter is /usr/bin/python3 unless SUBSTEP_PYTHON names another.
int sweepCommand(const SweepOptions& options);

}  // namespace substep

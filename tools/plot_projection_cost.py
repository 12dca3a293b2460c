#!/usr/bin/python3
"""Plots the energy error against the time per frame for the joint projections, from
`substep sweep --csv` files (one per projection): the cost companion of Fig. 9 redrawn
(docs/fidelity/README.md). One colour per file, one line per budget, each point a split substeps x iterations of one of
the budgets, log-log.

    /usr/bin/python3 tools/plot_projection_cost.py OUT.png LABEL=SWEEP.csv [LABEL=SWEEP.csv ...]
        [--title TEXT] [--measure energy_error_final]

Needs Debian's python3-matplotlib.
"""

import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # plot_style.py, beside this file
import plot_style  # noqa: E402


def read_sweep(path, measure):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if not reader.fieldnames or "ms_per_frame" not in reader.fieldnames or measure not in reader.fieldnames:
            sys.exit(f"plot_projection_cost.py: {path}: not a `substep sweep --csv` file with {measure}")
        rows = [(float(r["ms_per_frame"]), float(r[measure]), r["substeps"], r["iterations"], r["budget"])
                for r in reader]
    if not rows:
        sys.exit(f"plot_projection_cost.py: {path}: no rows")
    return rows


def main():
    parser = argparse.ArgumentParser(description="Plot an error measure against ms/frame per projection")
    parser.add_argument("png")
    parser.add_argument("sweeps", nargs="+", metavar="LABEL=SWEEP.csv")
    parser.add_argument("--title", default="energy error against cost")
    parser.add_argument("--measure", default="energy_error_final")
    args = parser.parse_args()
    sweeps = []
    for item in args.sweeps:
        label, sep, path = item.partition("=")
        if not sep or not label or not path:
            parser.error(f"expected LABEL=SWEEP.csv, got '{item}'")
        sweeps.append((label, read_sweep(path, args.measure)))

    plt = plot_style.import_pyplot("plot_projection_cost.py")
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, (label, rows) in enumerate(sweeps):
        colour = plot_style.line_colour(plt, i, len(sweeps))
        budgets = sorted({r[4] for r in rows}, key=int)
        for k, budget in enumerate(budgets):  # one line per budget, as plot_sweep.py draws them
            line = sorted(r for r in rows if r[4] == budget)
            ax.plot([r[0] for r in line], [max(r[1], 1e-12) for r in line], marker="o", linewidth=1.2,
                    label=label if k == 0 else None, color=colour)
        for ms, value, substeps, iterations, _ in rows:
            ax.annotate(f"{substeps}x{iterations}", (ms, max(value, 1e-12)), fontsize=6,
                        xytext=(3, 3), textcoords="offset points", color=colour)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ms per frame (one core)")
    ax.set_ylabel(args.measure + " (/ m g L)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=9, title="joint projection")
    ax.set_title(args.title)
    fig.tight_layout()
    plot_style.save_png(fig, args.png, prefix=".plot_projection_cost-")


if __name__ == "__main__":
    main()

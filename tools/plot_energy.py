#!/usr/bin/python3
"""Plots total energy against time from `substep run --csv` files, one line per file: the
time-series companion of `substep sweep` (paper Fig. 9: a triple pendulum's energy over 10 s for
several splits of one budget).

    /usr/bin/python3 tools/plot_energy.py OUT.png LABEL=RUN.csv [LABEL=RUN.csv ...] [--title TEXT]

LABEL names the line (e.g. 40x1 for 40 substeps x 1 iteration). The PNG is written to a
temporary name beside OUT.png and renamed into place. Needs Debian's python3-matplotlib.
"""

import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # plot_style.py, beside this file
import plot_style  # noqa: E402


def read_run(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if not reader.fieldnames or "t" not in reader.fieldnames or "energy" not in reader.fieldnames:
            sys.exit(f"plot_energy.py: {path}: not a `substep run --csv` file (no t or energy column)")
        rows = [(float(r["t"]), float(r["energy"])) for r in reader]
    if not rows:
        sys.exit(f"plot_energy.py: {path}: no rows")
    return rows


def main():
    parser = argparse.ArgumentParser(description="Plot energy against time from substep run CSVs")
    parser.add_argument("png")
    parser.add_argument("runs", nargs="+", metavar="LABEL=RUN.csv")
    parser.add_argument("--title", default="total energy against time")
    args = parser.parse_args()
    runs = []
    for item in args.runs:
        label, sep, path = item.partition("=")
        if not sep or not label or not path:
            parser.error(f"expected LABEL=RUN.csv, got '{item}'")
        runs.append((label, read_run(path)))

    plt = plot_style.import_pyplot("plot_energy.py")
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, (label, rows) in enumerate(runs):
        ax.plot([t for t, _ in rows], [e for _, e in rows], linewidth=1.4, label=label,
                color=plot_style.line_colour(plt, i, len(runs)))
    ax.axhline(runs[0][1][0][1], color="grey", linestyle="--", linewidth=1, label="E(0)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("total energy (J)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9, title="substeps x iterations")
    ax.set_title(args.title)
    fig.tight_layout()

    plot_style.save_png(fig, args.png, prefix=".plot_energy-")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Plots a `substep sweep` CSV: error against ms/frame, one line per budget, each point
labelled with its split (substeps x iterations), log axes, one panel per error measure that is
non-zero somewhere.

    /usr/bin/python3 tools/plot_sweep.py SWEEP.csv OUT.png [--title TEXT]
    /usr/bin/python3 tools/plot_sweep.py --check      # exit 0 if matplotlib is importable, else 3

`substep sweep --plot` runs this. The PNG is written to a temporary name beside OUT.png and
renamed into place, so OUT.png is whole or untouched. Debian's python3-matplotlib is all it needs.
"""

import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # plot_style.py, beside this file
import plot_style  # noqa: E402

# Error columns of the CSV contract, with the axis label of each.
MEASURES = [
    ("energy_drift", "energy drift  max |E(t) - E(0)| / E_scale"),
    ("energy_error_final", "final energy error  |E(T) - E(0)| / E_scale"),
    ("max_joint_error", "largest joint error (m)"),
    ("mean_joint_error", "mean joint error (m)"),
    ("chain_elongation", "chain elongation at T (relative)"),
    ("penetration", "penetration depth (m)"),
]


def number(text):
    """A CSV cell as a float; blank (no such measure) is None."""
    return float(text) if text.strip() else None


def read_sweep(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_sweep.py: {path}: no rows")
    missing = [c for c in ("budget", "substeps", "iterations", "ms_per_frame") if c not in rows[0]]
    if missing:
        sys.exit(f"plot_sweep.py: {path}: not a sweep CSV (no {', '.join(missing)})")
    return rows


def label_log_axis(axis):
    """Plain numbers at 1, 2 and 5 times each power of ten (1, 1.5, 2, 3, 5, 7 within a decade)
    when the axis spans less than three decades, where matplotlib would label only the powers
    (often one or none); its powers of ten beyond."""
    from matplotlib import ticker
    low, high = axis.get_view_interval()
    if low > 0 and high / low < 1e3:
        subs = (1.0, 1.5, 2.0, 3.0, 5.0, 7.0) if high / low < 10 else (1.0, 2.0, 5.0)
        axis.set_major_locator(ticker.LogLocator(subs=subs))
        axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_formatter(ticker.NullFormatter())


def plottable(value):
    # Log axes: zero, negative, blank and non-finite values have no place on them.
    return value is not None and math.isfinite(value) and value > 0


def draw(rows, png, title):
    plt = plot_style.import_pyplot("plot_sweep.py")
    measures = [(key, label) for key, label in MEASURES
                if key in rows[0] and any(plottable(number(r[key])) for r in rows)]
    if not measures:
        sys.exit("plot_sweep.py: every error measure is zero or blank; nothing to plot")

    budgets = sorted({int(r["budget"]) for r in rows})
    columns = 1 if len(measures) == 1 else 2
    panel_rows = math.ceil(len(measures) / columns)
    fig, axes = plt.subplots(panel_rows, columns, figsize=(6.2 * columns, 4.6 * panel_rows),
                             squeeze=False)
    legend = {}  # one legend for the figure: label -> line
    for ax, (key, label) in zip(axes.flat, measures):
        for b, budget in enumerate(budgets):
            colour = plot_style.line_colour(plt, b, len(budgets))
            points = [(float(r["ms_per_frame"]), number(r[key]), f'{r["substeps"]}x{r["iterations"]}')
                      for r in rows if int(r["budget"]) == budget]
            points = [p for p in points if plottable(p[1]) and p[0] > 0]
            if not points:
                continue
            (line,) = ax.plot([p[0] for p in points], [p[1] for p in points], "o-", color=colour,
                              markersize=4, linewidth=1.2)
            legend.setdefault(budget, line)
            for x, y, split in points:
                ax.annotate(split, (x, y), textcoords="offset points", xytext=(4, 3),
                            fontsize=7, color=colour)
        ax.set_xscale("log")
        ax.set_yscale("log")
        label_log_axis(ax.xaxis)
        label_log_axis(ax.yaxis)
        ax.set_xlabel("ms per frame (median, inside world.step)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.25)
    for ax in list(axes.flat)[len(measures):]:
        ax.set_visible(False)
    # Title, then the budgets' legend in one row beneath it, then the panels.
    height = fig.get_figheight()
    fig.suptitle(title + "\nlabels: substeps x iterations; lower is better", y=1 - 0.08 / height,
                 va="top")
    fig.legend([legend[b] for b in sorted(legend)], [f"budget {b}" for b in sorted(legend)],
               loc="upper center", ncol=len(legend), fontsize=9, frameon=False,
               bbox_to_anchor=(0.5, 1 - 0.55 / height))
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.8 / height))

    plot_style.save_png(fig, png, prefix=".plot_sweep-")


def main():
    parser = argparse.ArgumentParser(description="Plot a substep sweep CSV")
    parser.add_argument("csv", nargs="?")
    parser.add_argument("png", nargs="?")
    parser.add_argument("--title", help="plot title (default: the CSV's file name)")
    parser.add_argument("--check", action="store_true", help="only check that matplotlib imports")
    args = parser.parse_args()
    if args.check:
        plot_style.import_pyplot("plot_sweep.py", quiet=True)  # the caller explains
        return
    if not args.csv or not args.png:
        parser.error("CSV and PNG are required")
    rows = read_sweep(args.csv)
    draw(rows, args.png, args.title or f"error against run time: {os.path.basename(args.csv)}")


if __name__ == "__main__":
    main()

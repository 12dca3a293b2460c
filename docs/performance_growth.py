#!/usr/bin/python3
# Draws docs/performance_growth.png from the figures of docs/PERFORMANCE_LOG.md ("How the cost grows",
# and session 18's "Issue 18 on a fourth machine"):
#   /usr/bin/python3 docs/performance_growth.py docs/performance_growth.png
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
# N = 1000, 4000, 16000 spheres in a box (tests/benchmarks/pile_benchmark.cpp's spheresInABox),
# one core: (contact points per frame, ms per frame).
# Session 18, the fourth machine, build 700fdbe: frames 181-240, the pile settled.
settled = ([2514, 10870, 43215], [7.83, 59.23, 287.65])
# The same build, BM_spheres_in_a_box/N/1: frames 61-120 (falling, landing, piling).
falling = ([2274, 9278, 37916], [8.53, 56.2, 269])
# 2026-11-24 (the Zen 4), BM_spheres_in_a_box/N/1 after the fused one-point path. Its 16000
# spheres lost up to a third of their contact pairs to the fixed cap of 131072 while falling
# (docs/STABILITY.md), so its last point is of a broken fall.
zen4 = ([2184, 8625, 33042], [16.4, 75.5, 418])
fig, ax = plt.subplots(figsize=(6.4, 4.4))
for (c, t), label, mark in ((settled, "session 18, settled (frames 181-240)", "s"),
                            (falling, "session 18, frames 61-120 (BM_spheres_in_a_box)", "o"),
                            (zen4, "2026-11-24, Zen 4, from 1 s (pairs capped at 16000)", "^")):
    ax.plot(c, t, mark + "-", label=label, alpha=1.0 if "session 18" in label else 0.5)
for x, y in zip(*settled):
    ax.annotate(f"{y:g} ms", (x, y), textcoords="offset points", xytext=(6, -12), fontsize=8)
linear = [settled[1][0] * c / settled[0][0] for c in (settled[0][0], settled[0][-1])]
ax.plot([settled[0][0], settled[0][-1]], linear, ":", color="gray", label="linear in contacts from N = 1000 (settled)")
ax.set_xscale("log"); ax.set_yscale("log")
ax.set_xlabel("contact points per frame (N = 1000, 4000, 16000 spheres)")
ax.set_ylabel("ms per frame, 20 substeps, one core")
ax.set_title("N spheres in a box: cost against contacts")
ax.legend(fontsize=7); ax.grid(True, which="both", alpha=0.3)
fig.tight_layout(); fig.savefig(__import__("sys").argv[1], dpi=110)

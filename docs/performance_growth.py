#!/usr/bin/python3
# Draws docs/performance_growth.png from the figures of docs/PERFORMANCE_LOG.md ("How the cost grows"):
#   /usr/bin/python3 docs/performance_growth.py docs/performance_growth.png
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
# BM_spheres_in_a_box/N/1, CPU ms per frame against contact points per frame (docs/PERFORMANCE_LOG.md)
before = ([2283, 8713, 33430], [19.9, 87.0, 398])   # general correction path (2026-11-24, earlier session)
after = ([2184, 8625, 33042], [16.4, 75.5, 418])    # fused one-point path
fig, ax = plt.subplots(figsize=(6, 4.2))
for (c, t), label, mark in ((before, "general correction path", "o"), (after, "fused one-point path", "s")):
    ax.plot(c, t, mark + "-", label=label)
    for x, y in zip(c, t): ax.annotate(f"{y:g} ms", (x, y), textcoords="offset points", xytext=(5, -12), fontsize=8)
lin = [after[1][0] * c / after[0][0] for c in after[0][0:1] + [33042]]
ax.plot([after[0][0], 33042], lin, ":", color="gray", label="linear in contacts from N = 1000")
ax.set_xscale("log"); ax.set_yscale("log")
ax.set_xlabel("contact points per frame (N = 1000, 4000, 16000 spheres)")
ax.set_ylabel("CPU ms per frame, 20 substeps, one core")
ax.set_title("N spheres in a box: cost against contacts")
ax.legend(fontsize=8); ax.grid(True, which="both", alpha=0.3)
fig.tight_layout(); fig.savefig(__import__("sys").argv[1], dpi=110)

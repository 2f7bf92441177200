#!/usr/bin/python3
"""Plot the atmosphere speed-vs-error CSV (benchmarks/atmosphere_speed_vs_error --csv) as a PNG.

usage: plot_speed_vs_error.py FIGURES.csv OUT.png [TITLE]
x: milliseconds per frame (full channel render), y: median relative luminance error (log).
Pareto-optimal models are joined by a line; the default model (the CSV's default column) is ringed.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = list(csv.DictReader(open(sys.argv[1])))
    if not rows:
        print(f"{sys.argv[1]}: no rows", file=sys.stderr)
        return 1
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for r in rows:
        x, y = float(r["ms_frame"]), 100 * float(r["median"])
        ax.scatter([x], [y], s=40, color="tab:blue" if r["pareto"] == "1" else "tab:gray", zorder=3)
        ax.annotate(r["model"], (x, y), textcoords="offset points", xytext=(6, 4), fontsize=9)
        if r.get("default") == "1":
            ax.scatter([x], [y], s=160, facecolors="none", edgecolors="tab:red", zorder=4,
                       label=f"default ({r['model']})")
    front = sorted((float(r["ms_frame"]), 100 * float(r["median"])) for r in rows if r["pareto"] == "1")
    ax.plot([p[0] for p in front], [p[1] for p in front], color="tab:blue", lw=1, label="Pareto front")
    ax.set_yscale("log")
    ax.set_xlabel("ms per frame (channel render)")
    ax.set_ylabel("median relative luminance error vs reference (%)")
    ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "Cupola atmosphere: speed vs error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2])
    print(f"wrote {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

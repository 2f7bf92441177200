#!/usr/bin/python3
"""Plot the eclipse speed-vs-error CSV (benchmarks/eclipse_speed_vs_error --csv) as a PNG.

usage: plot_eclipse_speed_vs_error.py FIGURES.csv OUT.png [TITLE]
Left: per-pixel cost of each shadow mode (GPU pass minus the "none" baseline) against the max and
mean absolute error of the visible fraction in the penumbra (Sun-Moon a = 0.9..1.1 and a = 3.7).
The illustrative mode has no numeric error: a dashed line marks its cost.
Right: lookup-table size (texels) against its error and build time.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else None


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = list(csv.DictReader(open(sys.argv[1])))
    modes = [r for r in rows if r["kind"] == "mode"]
    luts = [r for r in rows if r["kind"] == "lut_size"]
    if not modes:
        print(f"{sys.argv[1]}: no mode rows", file=sys.stderr)
        return 1
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8), dpi=120)
    colors = {"exact": "tab:blue", "fast": "tab:orange", "lut": "tab:green"}
    for r in modes:
        x = num(r, "ns_per_pixel")
        if r["name"] == "illustrative":
            cost = "~0" if abs(x) < 0.5 else f"{x:.1f}"
            ax.axvline(x, color="tab:purple", ls="--", lw=1, label=f"illustrative ({cost} ns/px, no numeric error)")
            continue
        if r["name"] not in colors:
            continue
        c = colors[r["name"]]
        ax.scatter([x], [num(r, "sun_moon_max")], marker="o", color=c, s=45, zorder=3)
        ax.scatter([x], [num(r, "sun_moon_mean")], marker="o", facecolors="none", edgecolors=c, s=45, zorder=3)
        ax.scatter([x], [num(r, "earth_moon_max")], marker="^", color=c, s=45, zorder=3)
        ax.scatter([x], [num(r, "earth_moon_mean")], marker="^", facecolors="none", edgecolors=c, s=45, zorder=3)
        ax.annotate(r["name"], (x, num(r, "sun_moon_max")), textcoords="offset points", xytext=(7, 4), fontsize=9)
    ax.scatter([], [], marker="o", color="gray", label="Sun-Moon (a 0.9..1.1) max")
    ax.scatter([], [], marker="o", facecolors="none", edgecolors="gray", label="Sun-Moon mean")
    ax.scatter([], [], marker="^", color="gray", label="Earth from Moon (a 3.7) max")
    ax.scatter([], [], marker="^", facecolors="none", edgecolors="gray", label="Earth from Moon mean")
    ax.set_yscale("log")
    ax.set_xlabel("GPU cost, ns per pixel (llvmpipe, minus baseline)")
    ax.set_ylabel("|visible fraction - reference| in the penumbra")
    ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "Cupola eclipse shadow modes: speed vs error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="center right", fontsize=7)

    if luts:
        texels = []
        for r in luts:
            w, h = (int(v) for v in r["name"].split("x"))
            texels.append(w * h)
        bx.plot(texels, [num(r, "sun_moon_max") for r in luts], "o-", color="tab:green", label="Sun-Moon max")
        bx.plot(texels, [num(r, "sun_moon_mean") for r in luts], "o--", color="tab:green", mfc="none", label="Sun-Moon mean")
        bx.plot(texels, [num(r, "earth_moon_max") for r in luts], "^-", color="tab:olive", label="a 3.7 max")
        bx.plot(texels, [num(r, "earth_moon_mean") for r in luts], "^--", color="tab:olive", mfc="none", label="a 3.7 mean")
        for t, r in zip(texels, luts):
            bx.annotate(r["name"], (t, num(r, "sun_moon_max")), textcoords="offset points", xytext=(4, 6), fontsize=7)
        bx.set_xscale("log")
        bx.set_yscale("log")
        bx.set_xlabel("LUT texels (RGBA32F, 16 bytes each)")
        bx.set_ylabel("|visible fraction - reference|")
        bx.set_title("lookup table: size vs error (build ms on the right axis)")
        bx.grid(True, which="both", alpha=0.3)
        cx = bx.twinx()
        cx.plot(texels, [num(r, "build_ms") for r in luts], "s:", color="tab:gray", label="build ms (2 cores)")
        cx.set_yscale("log")
        cx.set_ylabel("build ms")
        lines = bx.get_legend_handles_labels()
        more = cx.get_legend_handles_labels()
        bx.legend(lines[0] + more[0], lines[1] + more[1], loc="lower left", fontsize=7)
    else:
        bx.axis("off")
    fig.tight_layout()
    fig.savefig(sys.argv[2])
    print(f"wrote {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Plots `vct benchmark --mode scaling` (benchmarks/scaling.sh): per-pass and frame medians against the pixel
count and against the voxel count N³, log-log, and fits each pass's growth exponent (ms ∝ x^k over the measured
points). Benchmark scripts only: matplotlib (Debian's python3-matplotlib) is never needed to build or test.

Usage: plot_scaling.py SCALING.json OUT_PREFIX   → OUT_PREFIX-pixels.png, OUT_PREFIX-voxels.png, exponents printed
"""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fit_exponent(xs, ys):
    """Least-squares slope of log y against log x (points with y > 0 only); None with fewer than 2."""
    points = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(points) < 2:
        return None
    mx = sum(p[0] for p in points) / len(points)
    my = sum(p[1] for p in points) / len(points)
    sxx = sum((p[0] - mx) ** 2 for p in points)
    return sum((p[0] - mx) * (p[1] - my) for p in points) / sxx if sxx > 0 else None


def plot(report, sweep, x_of, x_label, out_path):
    points = [p for p in report["points"] if p["sweep"] == sweep and "pass_median_ms" in p]
    failed = [p for p in report["points"] if p["sweep"] == sweep and "error" in p]
    if not points:
        print(f"{sweep}: no measured points")
        return
    passes = list(points[0]["pass_median_ms"].keys())
    xs = [x_of(p) for p in points]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    print(f"{sweep}: growth exponent k (ms ∝ {x_label}^k)")
    for name in passes + ["frame"]:
        ys = [p["frame_median_ms"] if name == "frame" else p["pass_median_ms"].get(name, 0.0) for p in points]
        k = fit_exponent(xs, ys)
        label = f"{name} (k = {k:.2f})" if k is not None else f"{name} (0 ms)"
        print(f"  {name:10s} {'—' if k is None else f'{k:5.2f}'}   " + "  ".join(f"{y:8.2f}" for y in ys))
        shown = [(x, y) for x, y in zip(xs, ys) if y > 0]
        if shown:
            ax.plot(*zip(*shown), marker="o", linewidth=2.5 if name == "frame" else 1.2,
                    color="black" if name == "frame" else None, label=label)
    for p in failed:
        print(f"  failed at {x_of(p)}: {p['error']}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(x_label)
    ax.set_ylabel("GPU median ms")
    title = f"{report['device']}, {report['scene']}, default configuration"
    if failed:
        title += f" ({len(failed)} point(s) failed, see JSON)"
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out_path, dpi=110)
    print(f"wrote {out_path}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        report = json.load(f)
    prefix = sys.argv[2]
    plot(report, "pixels", lambda p: p["pixels"], "pixels", prefix + "-pixels.png")
    plot(report, "voxels", lambda p: p["voxels"] ** 3, "voxels (N³)", prefix + "-voxels.png")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The cost curves of docs/benchmarks.md: time against the vertex count for smoothing, distance
and matching, measured on generated shapes (no data needed), printed as a Markdown table and
plotted (log-log) to an SVG.

Usage: bench/cost_curves.py [--build build/release] [--svg docs/images/cost_curves.svg]
                            [--json FILE] [--from-json FILE]

- smoothing: `BM_FairingFiveStepsCurve` (five implicit-fairing steps on a noisy torus),
- distance: `BM_ExactHausdorff` (a noisy torus against its tenth),
- matching: `genflow demo --level 3…6` (the articulated limb; the match's own seconds).

`--json` keeps the measurements, `--from-json` plots kept ones without measuring again. The plot
needs matplotlib (Debian's python3-matplotlib); without it the table is still printed.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

DEMO_LEVELS = (3, 4, 5, 6)


def google_benchmark(binary, name):
    """(vertices, seconds) of each size of a Google Benchmark cost curve."""
    run = subprocess.run([binary, f"--benchmark_filter=^{name}/", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True)
    points = []
    for result in json.loads(run.stdout)["benchmarks"]:
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[result["time_unit"]]
        points.append((int(result["V"]), result["real_time"] * scale))
    return points


def demo_curve(genflow):
    """(vertices, seconds) of `genflow demo` at each level: the match's own time."""
    points = []
    for level in DEMO_LEVELS:
        with tempfile.TemporaryDirectory(prefix="cost_curves") as out:
            subprocess.run([genflow, "demo", "--output-dir", out, "--level", str(level),
                            "--quiet"], check=True, stdout=subprocess.DEVNULL)
            with open(os.path.join(out, "summary.json")) as summary:
                seconds = json.load(summary)["seconds"]
        points.append((10 * 4 ** level + 2, seconds))
    return points


def measure(build):
    return {
        "smoothing: five implicit-fairing steps": google_benchmark(
            os.path.join(build, "bench", "genflow_flow_bench"), "BM_FairingFiveStepsCurve"),
        "distance: exact Hausdorff": google_benchmark(
            os.path.join(build, "bench", "genflow_hausdorff_bench"), "BM_ExactHausdorff"),
        "matching: genflow demo": demo_curve(os.path.join(build, "genflow")),
    }


def print_table(curves):
    print("| curve | vertices: seconds |")
    print("|---|---|")
    for name, points in curves.items():
        cells = ", ".join(f"{v:,}: {t:.3g} s" for v, t in points)
        print(f"| {name} | {cells} |")


def plot(curves, svg):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        plt.rcParams["svg.hashsalt"] = "genflow"  # the same file for the same figures
    except ImportError:
        print("cost_curves.py: no plot: matplotlib is not installed "
              "(apt-get install python3-matplotlib)", file=sys.stderr)
        return 2
    figure, axes = plt.subplots(figsize=(6.4, 4.2))
    for (name, points), marker in zip(curves.items(), "osd"):
        axes.loglog([v for v, _ in points], [t for _, t in points], marker=marker, label=name)
    # A line of slope one through the smallest smoothing point: linear cost, for reference.
    v0, t0 = next(iter(curves.values()))[0]
    largest = max(v for points in curves.values() for v, _ in points)
    axes.loglog([v0, largest], [t0, t0 * largest / v0], linestyle=":", color="grey",
                label="linear in the vertex count")
    axes.set_xlabel("vertices")
    axes.set_ylabel("seconds (2 cores)")
    axes.grid(True, which="major", linewidth=0.4)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(svg, metadata={"Date": None})
    print(f"plotted to {svg}")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--svg", default="docs/images/cost_curves.svg")
    parser.add_argument("--json", help="write the measurements to this file")
    parser.add_argument("--from-json", help="plot these measurements instead of measuring")
    args = parser.parse_args()
    if args.from_json:
        with open(args.from_json) as kept:
            curves = json.load(kept)
    else:
        curves = measure(args.build)
    if args.json:
        with open(args.json, "w") as out:
            json.dump(curves, out, indent=1)
    print_table(curves)
    return plot(curves, args.svg)


if __name__ == "__main__":
    sys.exit(main())

# SPDX-License-Identifier: MIT
"""The speed of genflow against its anchors, side by side in one run (issue 55's table).

Each row times whole processes, genflow's and its anchor's in turn (A B A B ...), and prints the
median wall time of each, their ratio and the goal. Per-step rows time STEPS steps and no step
and divide the difference by STEPS, so that reading and set-up do not count. The anchors:
bench/anchors/fairing_anchor (libigl's implicit fairing loop re-expressed with Eigen) and, where
Debian's libcgal-dev was installed when genflow was configured (`scripts/install-deps.sh
--anchors`), bench/anchors/hausdorff_anchor (CGAL 5.5's bounded-error Hausdorff distance).
Matching has no anchor in Debian: its rows give genflow's time against the goal alone.

Usage: /usr/bin/python3 bench/anchors/anchors.py [--build build/release] [--runs 3]
           [--only fairing,frozen,fixed,cpu,volume,hausdorff,match,demo]
Needs $GENFLOW_DATA (default ../shared/data) for the meshes; rows without their data are skipped.
"""

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time


def run_once(command):
    """Wall and processor seconds of one run of `command` (a list), which must succeed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit("anchors: %s failed: %s" % (" ".join(command), done.stderr.decode()[-300:]))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def interleaved(commands, runs):
    """Median (wall, cpu) of each command, run in turn `runs` times after one warm-up each."""
    for command in commands:
        run_once(command)
    times = [[] for _ in commands]
    for _ in range(runs):
        for k, command in enumerate(commands):
            times[k].append(run_once(command))
    return [(statistics.median(t[0] for t in ts), statistics.median(t[1] for t in ts))
            for ts in times]


class Table:
    def __init__(self):
        print("| work | genflow | anchor | ratio | goal |")
        print("|---|---:|---:|---:|---:|")

    @staticmethod
    def row(work, ours, theirs, goal):
        ratio = "%.2f×" % (ours / theirs) if theirs else "—"
        theirs_text = "%.3f s" % theirs if theirs else "—"
        print("| %s | %.3f s | %s | %s | %s |" % (work, ours, theirs_text, ratio, goal))
        sys.stdout.flush()


def per_step(genflow, anchor, mesh, steps, runs, method="fairing", rebuild=False, extra=()):
    """Seconds per step of genflow smooth (with `extra` flags) and of the fairing anchor, and
    their fixed costs."""
    out = os.path.join(tempfile.gettempdir(), "anchors_smoothed.ply")
    ours = [genflow, "smooth", mesh, out, "--method", method, "--json"] + list(extra)
    theirs_out = os.path.join(tempfile.gettempdir(), "anchors_anchor.ply")
    anchor_flags = [theirs_out] + (["--rebuild"] if rebuild else [])
    (ours_n, ours_n_cpu), (ours_0, _), (theirs_n, theirs_n_cpu), (theirs_0, _) = interleaved(
        [ours + ["--steps", str(steps)], ours + ["--steps", "0"],
         [anchor, mesh, str(steps)] + anchor_flags, [anchor, mesh, "0"] + anchor_flags], runs)
    return {"ours_step": (ours_n - ours_0) / steps, "theirs_step": (theirs_n - theirs_0) / steps,
            "ours_fixed": ours_0, "theirs_fixed": theirs_0,
            "ours_cpu": ours_n_cpu, "theirs_cpu": theirs_n_cpu}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only",
                        default="fairing,frozen,fixed,cpu,volume,hausdorff,match,demo")
    args = parser.parse_args()
    only = set(args.only.split(","))
    data = os.environ.get("GENFLOW_DATA", "../shared/data")
    genflow = os.path.join(args.build, "genflow")
    fairing = os.path.join(args.build, "bench", "fairing_anchor")
    hausdorff = os.path.join(args.build, "bench", "hausdorff_anchor")
    decimate = os.path.join(args.build, "bench", "decimate")
    print("machine: %d cores, %s; %d runs each, interleaved, medians of whole processes\n"
          % (os.cpu_count(), time.strftime("%Y-%m-%d"), args.runs))
    table = Table()
    work = tempfile.mkdtemp(prefix="anchors")
    meshes = [("horse 48K", os.path.join(data, "smoothing", "horse_noisy.ply"), False),
              ("armadillo 43K", os.path.join(data, "smoothing", "armadillo.ply"), False)]
    big = os.path.join(work, "armadillo_173k.ply")
    if os.path.exists(meshes[1][1]):
        subprocess.run([decimate, meshes[1][1], big, "--subdivide"], check=True,
                       stdout=subprocess.DEVNULL)
        meshes.append(("armadillo subdivided to 173K", big, True))
    measured = {}
    for name, mesh, rebuild in meshes:
        if not os.path.exists(mesh) or not only & {"fairing", "fixed", "cpu"}:
            continue
        m = per_step(genflow, fairing, mesh, 10, args.runs, rebuild=rebuild)
        measured[name] = m
        if "fairing" in only:
            table.row("implicit fairing, per step, %s%s"
                      % (name, " (the anchor rebuilds K and M)" if rebuild else ""),
                      m["ours_step"], m["theirs_step"], "≤ 0.5×")
    for name, mesh, rebuild in meshes:
        if "frozen" in only and os.path.exists(mesh):
            m = per_step(genflow, fairing, mesh, 10, args.runs, rebuild=rebuild,
                         extra=["--freeze-metric"])
            table.row("implicit fairing, frozen metric (`--freeze-metric`), per step, %s%s"
                      % (name, " (the anchor rebuilds K and M)" if rebuild else ""),
                      m["ours_step"], m["theirs_step"], "≤ 0.5×")
    for name, m in measured.items():
        if "fixed" in only:
            table.row("fixed cost of smooth (`--steps 0`), " + name, m["ours_fixed"],
                      m["theirs_fixed"], "≤ 1×")
        if "cpu" in only and rebuild_name(name):
            table.row("CPU time, 10 steps, " + name, m["ours_cpu"], m["theirs_cpu"], "≤ 1×")
    if "volume" in only and os.path.exists(meshes[0][1]):
        plain = measured.get(meshes[0][0]) or per_step(genflow, fairing, meshes[0][1], 10, args.runs)
        volume = per_step(genflow, fairing, meshes[0][1], 10, args.runs, method="volume-fairing")
        table.row("volume-controlled against plain fairing, per step, horse 48K",
                  volume["ours_step"], plain["ours_step"], "≤ 1.5×")
    if "hausdorff" in only:
        hausdorff_rows(table, genflow, hausdorff, decimate, meshes, work, args.runs)
    if "match" in only:
        match_rows(table, genflow, data, work, args.runs)
    if "demo" in only:
        (demo, _), = interleaved([[genflow, "demo", "--output-dir", os.path.join(work, "demo"), "--quiet"]],
                                 args.runs)
        table.row("`genflow demo` (2.5K generated limb, articulated)", demo, None, "< 3 s")


def rebuild_name(name):
    return "173K" in name


def hausdorff_rows(table, genflow, anchor, decimate, meshes, work, runs):
    for name, mesh, _ in meshes[1:]:
        if not os.path.exists(mesh):
            continue
        coarse = os.path.join(work, os.path.basename(mesh) + ".decimated.ply")
        subprocess.run([decimate, mesh, coarse, "--ratio", "0.1"], check=True,
                       stdout=subprocess.DEVNULL)
        # The anchor computes the Hausdorff distance alone, so genflow does too.
        ours = [genflow, "distance", mesh, coarse, "--json", "--hausdorff-only"]
        if os.path.exists(anchor):
            (a, _), (b, _) = interleaved([ours, [anchor, mesh, coarse, "1e-4"]], runs)
        else:
            (a, _), = interleaved([ours], runs)
            b = None
        table.row("exact symmetric Hausdorff, %s vs its 10 %% decimation%s"
                  % (name, "" if b else " (CGAL anchor not built: install libcgal-dev)"),
                  a, b, "≤ 0.25×")


def match_rows(table, genflow, data, work, runs):
    cat = os.path.join(data, "matching", "tosca", "cat0.ply")
    cat_target = os.path.join(data, "matching", "remeshed", "tosca_cat_0_4_target_remeshed.ply")
    if os.path.exists(cat) and os.path.exists(cat_target):
        (t, _), = interleaved([[genflow, "match", cat, cat_target, "-o",
                                os.path.join(work, "cat.ply"), "--quiet"]], runs)
        table.row("match TOSCA cat 28K → 21K (no anchor in Debian; Fast_RNRR 6.49 s)", t, None,
                  "≤ 0.7× (4.5 s)")
    faust = os.path.join(data, "benchmarks", "faust_r_train")
    if os.path.exists(os.path.join(faust, "tr_reg_000.off")):
        (t, _), = interleaved([[genflow, "match", os.path.join(faust, "tr_reg_000.off"),
                                os.path.join(faust, "tr_reg_012.off"), "-o",
                                os.path.join(work, "faust.ply"), "--quiet"]], runs)
        table.row("match, FAUST_r 000 → 012, 5K vertices (no anchor in Debian)", t, None,
                  "< 3 s")


if __name__ == "__main__":
    main()

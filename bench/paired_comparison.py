# SPDX-License-Identifier: MIT
"""Two runs of a correspondence benchmark compared pair by pair (docs/benchmarks.md, "Ablation").

A change to the matcher is judged on the pairs both runs matched: the mean error of each run,
within and across subjects, the per-pair change with a seeded bootstrap interval of its mean
(a run's mean moves by a few hundredths from pair to pair noise alone, so a change smaller than
its interval says nothing), how many pairs got better or worse by more than a tenth of a
percent of √area, the mirrored pairs, and the processor time a pair, stage by stage. With
--eval, two outputs of `genflow eval` on the same pairs file (held-out pairs: docs/eval) are
compared row by row as well.

Usage: /usr/bin/python3 bench/paired_comparison.py BASE CANDIDATE
           [--eval BASE_EVAL.md CANDIDATE_EVAL.md] [--resamples 10000] [--seed 1]
BASE and CANDIDATE: directories of `genflow benchmark` pair files (NAME.json; a directory of
bench/ablation.sh, whose pair files are in its pairs/, is taken as it is). Exit 2 on bad input.
"""

import argparse
import glob
import json
import os
import random
import statistics
import sys

# Pairs that change by more than this (error ×100, a tenth of a percent of √area) are counted
# as better or worse: below it a change is within what a flow's rounding moves.
NOTABLE_CHANGE = 0.1


def fail(message):
    print("paired_comparison.py: " + message, file=sys.stderr)
    sys.exit(2)


def load_pairs(directory):
    """The pair files of one run, by pair name."""
    if os.path.isdir(os.path.join(directory, "pairs")):
        directory = os.path.join(directory, "pairs")
    if not os.path.isdir(directory):
        fail(directory + " is not a directory")
    pairs = {}
    for path in sorted(glob.glob(os.path.join(directory, "*.json"))):
        try:
            with open(path, encoding="utf-8") as file:
                pair = json.load(file)
            pairs[os.path.basename(path)[:-5]] = {
                "error": 100 * float(pair["mean"]),
                "within": bool(pair["within_subject"]),
                "mirrored": bool(pair["mirrored"]),
                "seconds": float(pair["processor_seconds"]),
                "stages": {s["stage"]: float(s["processor_seconds"])
                           for s in pair.get("details", {}).get("stage_times", [])},
            }
        except (OSError, ValueError, KeyError, TypeError) as error:
            fail("%s: not a pair file of genflow benchmark (%s)" % (path, error))
    if not pairs:
        fail(directory + " holds no pair files (NAME.json)")
    return pairs


def bootstrap_interval(changes, resamples, seed):
    """The 95 % interval of the mean of `changes`, resampled with replacement."""
    generator = random.Random(seed)
    means = sorted(statistics.fmean(generator.choices(changes, k=len(changes)))
                   for _ in range(resamples))
    return means[int(0.025 * resamples)], means[int(0.975 * resamples) - 1]


def error_rows(base, candidate, names):
    """Mean error ×100 of each run over all, within-subject and across-subject pairs."""
    rows = []
    for label, keep in (("all", lambda n: True), ("within subjects", lambda n: base[n]["within"]),
                        ("across subjects", lambda n: not base[n]["within"])):
        chosen = [n for n in names if keep(n)]
        if chosen:
            b = statistics.fmean(base[n]["error"] for n in chosen)
            c = statistics.fmean(candidate[n]["error"] for n in chosen)
            rows.append("| error ×100, %s (%d) | %.3f | %.3f | %+.3f |" % (label, len(chosen), b,
                                                                           c, c - b))
    return rows


def summary_rows(base, candidate, names, resamples, seed):
    changes = [candidate[n]["error"] - base[n]["error"] for n in names]
    low, high = bootstrap_interval(changes, resamples, seed)
    b_time = statistics.fmean(base[n]["seconds"] for n in names)
    c_time = statistics.fmean(candidate[n]["seconds"] for n in names)
    ratios = [candidate[n]["seconds"] / base[n]["seconds"] for n in names
              if base[n]["seconds"] > 0]
    rows = ["| | base | candidate | change |", "|---|---:|---:|---:|"]
    rows += error_rows(base, candidate, names)
    rows += [
        "| median pair | %.2f | %.2f | |" % (statistics.median(base[n]["error"] for n in names),
                                             statistics.median(candidate[n]["error"]
                                                               for n in names)),
        "| mirrored | %d | %d | |" % (sum(base[n]["mirrored"] for n in names),
                                      sum(candidate[n]["mirrored"] for n in names)),
        "| per pair change: mean (95 %% bootstrap interval) | | | %+.3f (%+.3f to %+.3f) |"
        % (statistics.fmean(changes), low, high),
        "| per pair change: median; better / worse by > %.1f | | | %+.3f; %d / %d |"
        % (NOTABLE_CHANGE, statistics.median(changes),
           sum(c < -NOTABLE_CHANGE for c in changes), sum(c > NOTABLE_CHANGE for c in changes)),
        "| largest change: worse / better | | | %+.2f / %+.2f |" % (max(changes), min(changes)),
        "| processor time a pair | %.1f s | %.1f s | %.2f× |" % (b_time, c_time, c_time / b_time),
    ]
    if ratios:
        rows.append("| per pair time ratio: median (range) | | | %.2f× (%.2f–%.2f×) |"
                    % (statistics.median(ratios), min(ratios), max(ratios)))
    return rows


def stage_rows(base, candidate, names):
    """Mean processor time a pair of every stage above 1 % of the base's total."""
    total = statistics.fmean(base[n]["seconds"] for n in names)
    stages = []
    for n in names:
        stages += [s for s in base[n]["stages"] if s not in stages]
    rows = ["| stage | base | candidate | ratio |", "|---|---:|---:|---:|"]
    for stage in stages:
        b = statistics.fmean(base[n]["stages"].get(stage, 0.0) for n in names)
        c = statistics.fmean(candidate[n]["stages"].get(stage, 0.0) for n in names)
        if b > 0.01 * total:
            rows.append("| %s | %.2f s | %.2f s | %.2f× |" % (stage, b, c, c / b))
    return rows


def read_eval(path):
    """(pair, prior) → mean error in % from a `genflow eval` table."""
    try:
        with open(path, encoding="utf-8") as file:
            lines = file.read().splitlines()
    except OSError as error:
        fail("%s: cannot read (%s)" % (path, error))
    rows = {}
    for line in lines:
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if len(cells) >= 3 and cells[2].endswith("%") and cells[0] != "pair":
            try:
                rows[(cells[0], cells[1])] = float(cells[2].rstrip(" %"))
            except ValueError:
                fail("%s: '%s' is not a mean error" % (path, cells[2]))
    if not rows:
        fail(path + " holds no rows of genflow eval")
    return rows


def eval_rows(base_path, candidate_path):
    base, candidate = read_eval(base_path), read_eval(candidate_path)
    keys = [k for k in base if k in candidate]
    if not keys:
        fail("%s and %s share no (pair, prior) row" % (base_path, candidate_path))
    rows = ["| pair | prior | base | candidate | change |", "|---|---|---:|---:|---:|"]
    rows += ["| %s | %s | %.2f %% | %.2f %% | %+.2f |" % (k[0], k[1], base[k], candidate[k],
                                                          candidate[k] - base[k]) for k in keys]
    b = statistics.fmean(base[k] for k in keys)
    c = statistics.fmean(candidate[k] for k in keys)
    rows.append("| mean (%d rows; %d better, %d worse) | | %.3f %% | %.3f %% | %+.3f |"
                % (len(keys), sum(candidate[k] < base[k] for k in keys),
                   sum(candidate[k] > base[k] for k in keys), b, c, c - b))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("base")
    parser.add_argument("candidate")
    parser.add_argument("--eval", nargs=2, metavar=("BASE_EVAL", "CANDIDATE_EVAL"))
    parser.add_argument("--resamples", type=int, default=10000)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if args.resamples < 100:
        fail("--resamples needs at least 100, got %d" % args.resamples)
    base, candidate = load_pairs(args.base), load_pairs(args.candidate)
    names = sorted(set(base) & set(candidate))
    if not names:
        fail("%s and %s share no pair" % (args.base, args.candidate))
    print("%d pairs matched by both (%d only in the base, %d only in the candidate)\n"
          % (len(names), len(base) - len(names), len(candidate) - len(names)))
    print("\n".join(summary_rows(base, candidate, names, args.resamples, args.seed)))
    print()
    print("\n".join(stage_rows(base, candidate, names)))
    if args.eval:
        print()
        print("\n".join(eval_rows(*args.eval)))


if __name__ == "__main__":
    main()

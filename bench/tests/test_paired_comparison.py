# SPDX-License-Identifier: MIT
"""bench/paired_comparison.py on made-up runs whose figures are known."""

import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "paired_comparison.py")


def write_run(directory, errors, seconds, within=lambda k: k % 2 == 0):
    """Pair files of one run: pair k has error errors[k] (×100) and seconds[k]."""
    os.makedirs(directory)
    for k, (error, time) in enumerate(zip(errors, seconds)):
        pair = {"mean": error / 100, "within_subject": within(k), "mirrored": error > 20,
                "processor_seconds": time,
                "details": {"stage_times": [{"stage": "guided rounds",
                                             "processor_seconds": time / 2}]}}
        with open(os.path.join(directory, "p%03d.json" % k), "w", encoding="utf-8") as file:
            json.dump(pair, file)


def run(*arguments):
    return subprocess.run([sys.executable, SCRIPT, *arguments], capture_output=True, text=True,
                          check=False)


def cell(output, label):
    """The last cell of the row whose first cell starts with `label`."""
    for line in output.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells[0].startswith(label):
            return cells[-1]
    raise AssertionError("no row " + label + " in\n" + output)


class PairedComparison(unittest.TestCase):
    def setUp(self):
        self.directory = tempfile.TemporaryDirectory()
        self.base = os.path.join(self.directory.name, "base")
        self.candidate = os.path.join(self.directory.name, "candidate")

    def tearDown(self):
        self.directory.cleanup()

    def test_a_uniform_change_has_an_interval_of_one_point(self):
        write_run(self.base, [2.0, 3.0, 4.0, 5.0], [10, 10, 20, 20])
        write_run(self.candidate, [2.5, 3.5, 4.5, 5.5], [5, 5, 10, 10])
        result = run(self.base, self.candidate)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cell(result.stdout, "error ×100, all"), "+0.500")
        # Within: pairs 0 and 2 (2.0, 4.0 → 2.5, 4.5); across: 1 and 3.
        self.assertIn("| 3.000 | 3.500 |", result.stdout)
        self.assertIn("| 4.000 | 4.500 |", result.stdout)
        self.assertEqual(cell(result.stdout, "per pair change: mean"), "+0.500 (+0.500 to +0.500)")
        self.assertEqual(cell(result.stdout, "per pair change: median"), "+0.500; 0 / 4")
        self.assertEqual(cell(result.stdout, "processor time a pair"), "0.50×")
        self.assertEqual(cell(result.stdout, "guided rounds"), "0.50×")

    def test_the_interval_holds_the_mean_and_counts_only_notable_changes(self):
        base = [2.0 + 0.1 * k for k in range(40)]
        # No change near 0.1, where rounding would decide the count.
        changes = [(-1) ** k * 0.04 * (k % 7) for k in range(40)]
        write_run(self.base, base, [10] * 40)
        write_run(self.candidate, [b + c for b, c in zip(base, changes)], [10] * 40)
        result = run(self.base, self.candidate)
        self.assertEqual(result.returncode, 0, result.stderr)
        mean = sum(changes) / len(changes)
        interval = cell(result.stdout, "per pair change: mean")
        low, high = (float(x) for x in interval.split("(")[1].rstrip(")").split(" to "))
        self.assertLess(low, mean)
        self.assertGreater(high, mean)
        better = sum(c < -0.1 for c in changes)
        worse = sum(c > 0.1 for c in changes)
        self.assertGreater(better, 0)
        self.assertGreater(worse, 0)
        self.assertTrue(cell(result.stdout, "per pair change: median").endswith(
            "%d / %d" % (better, worse)))

    def test_only_the_pairs_of_both_runs_are_compared(self):
        write_run(self.base, [2.0, 3.0, 4.0], [10, 10, 10])
        write_run(self.candidate, [2.0, 3.0], [10, 10])
        result = run(self.base, self.candidate)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("2 pairs matched by both (1 only in the base", result.stdout)

    def test_held_out_tables_are_compared_row_by_row(self):
        write_run(self.base, [2.0], [10])
        write_run(self.candidate, [2.0], [10])
        tables = []
        for name, errors in (("base.md", (0.83, 0.60)), ("candidate.md", (19.70, 0.50))):
            path = os.path.join(self.directory.name, name)
            with open(path, "w", encoding="utf-8") as file:
                file.write("| pair | prior | mean error | time |\n|---|---|---:|---:|\n")
                file.write("| a | articulated | %.2f %% | 1 s |\n" % errors[0])
                file.write("| b | articulated | %.2f %% | 1 s |\n" % errors[1])
            tables.append(path)
        result = run(self.base, self.candidate, "--eval", *tables)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cell(result.stdout, "a"), "+18.87")
        self.assertEqual(cell(result.stdout, "mean (2 rows; 1 better, 1 worse)"), "+9.385")

    def test_bad_input_is_one_line_and_exit_2(self):
        write_run(self.base, [2.0], [10])
        os.makedirs(self.candidate)
        with open(os.path.join(self.candidate, "p000.json"), "w", encoding="utf-8") as file:
            file.write("{\"mean\": ")
        for arguments in ((self.base, self.candidate),
                          (self.base, os.path.join(self.directory.name, "missing")),
                          (self.base, self.base, "--resamples", "5")):
            result = run(*arguments)
            self.assertEqual(result.returncode, 2, arguments)
            self.assertEqual(result.stdout, "")
            self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
            self.assertTrue(result.stderr.startswith("paired_comparison.py: "), result.stderr)


if __name__ == "__main__":
    unittest.main()

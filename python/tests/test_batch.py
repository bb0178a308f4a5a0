# SPDX-License-Identifier: MIT
"""genflow.batch: a Dask LocalCluster of two worker processes writes the same bytes as the
serial batch, and a broken target is recorded without stopping either."""

import os
import tempfile
import unittest

import numpy as np

import genflow
import genflow.batch
from test_genflow import sphere


class Batch(unittest.TestCase):
    def setUp(self):
        self.directory = tempfile.TemporaryDirectory()
        root = self.directory.name
        V, F = sphere(2)
        self.template = os.path.join(root, "template.ply")
        genflow.write_mesh(self.template, V, F)
        self.targets = []
        fine, fine_faces = sphere(3)
        for k, stretch in enumerate(([1.3, 1.0, 0.8], [0.9, 1.2, 1.0], [1.0, 1.0, 1.4])):
            path = os.path.join(root, "target%d.ply" % k)
            genflow.write_mesh(path, fine * np.array(stretch) + k, fine_faces)
            self.targets.append(path)
        broken = os.path.join(root, "broken.off")
        with open(broken, "w") as file:
            file.write("OFF\n3 1 0\n0 0 0\n")
        self.targets.append(broken)

    def tearDown(self):
        self.directory.cleanup()

    def outputs(self, directory):
        """The bytes of every output but the records (whose times differ)."""
        written = {}
        for name in sorted(os.listdir(directory)):
            if not name.endswith(".json"):
                with open(os.path.join(directory, name), "rb") as file:
                    written[name] = file.read()
        return written

    def test_dask_on_two_worker_processes_writes_what_the_serial_batch_writes(self):
        from dask.distributed import Client, LocalCluster

        serial_dir = os.path.join(self.directory.name, "serial")
        dask_dir = os.path.join(self.directory.name, "dask")
        serial = genflow.batch.run_serial(self.template, self.targets, serial_dir, iterations=40)
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            spread = genflow.batch.run_dask(client, self.template, self.targets, dask_dir,
                                            iterations=40)
        self.assertEqual([r["status"] for r in serial], ["matched"] * 3 + ["failed"])
        self.assertIn("broken.off", serial[3]["error"])
        self.assertEqual([r["status"] for r in spread], [r["status"] for r in serial])
        written = self.outputs(serial_dir)
        self.assertEqual(len(written), 6)  # mesh and correspondence of the three matched ones
        rows = np.load(os.path.join(serial_dir, "target0.correspondence.npy"))
        self.assertEqual(rows.shape[1], 4)
        np.testing.assert_allclose(rows[:, 1:].sum(axis=1), 1.0, atol=1e-9)
        self.assertEqual(self.outputs(dask_dir), written)

    def test_resume_skips_what_an_earlier_run_finished_and_shards_share_the_targets(self):
        out = os.path.join(self.directory.name, "out")
        first = genflow.batch.run_serial(self.template, self.targets, out, iterations=20)
        written = self.outputs(out)
        again = genflow.batch.run_serial(self.template, self.targets, out, iterations=20,
                                         resume=True)
        self.assertEqual([r["status"] for r in again], ["done before"] * 3 + ["failed"])
        self.assertEqual(self.outputs(out), written)
        self.assertEqual([r["status"] for r in first], ["matched"] * 3 + ["failed"])
        shares = [genflow.batch.shard(self.targets, i, 3) for i in range(3)]
        self.assertEqual(sorted(sum(shares, [])), sorted(self.targets))
        with self.assertRaises(ValueError):
            genflow.batch.shard(self.targets, 3, 3)

    def test_the_part_model_and_the_template_are_read_once_per_process(self):
        V, _ = sphere(2)
        tree = os.path.join(self.directory.name, "parts.json")
        with open(tree, "w") as file:
            file.write('{"parts": [{"name": "lower", "parent": null, "joint_center": [0, 0, 0]},'
                       ' {"name": "upper", "parent": "lower", "joint_center": [0, 0, 0]}]}')
        labels = os.path.join(self.directory.name, "labels.txt")
        with open(labels, "w") as file:
            file.write("".join("%d\n" % (z > 0) for z in V[:, 2]))
        out = os.path.join(self.directory.name, "parts")
        parts = {"tree": tree, "labels": labels}
        records = genflow.batch.run_serial(self.template, self.targets[:2], out,
                                           prior="articulated", parts=parts, iterations=20)
        self.assertEqual([r["status"] for r in records], ["matched"] * 2)
        self.assertEqual(records[0]["parts"], parts)
        # The second target found the template's analyses the first one left.
        _, _, model, cache = genflow.batch._prepared_template(self.template, parts)
        self.assertEqual(model.names, ["lower", "upper"])
        self.assertGreater(len(cache), 0)
        missing = genflow.batch.run_serial(os.path.join(self.directory.name, "none.ply"),
                                           self.targets[:1], out, iterations=20)
        self.assertEqual(missing[0]["status"], "failed")
        self.assertIn("none.ply", missing[0]["error"])


if __name__ == "__main__":
    unittest.main()

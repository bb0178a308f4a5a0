# SPDX-License-Identifier: MIT
"""The Python package on meshes it makes: numpy round trips, the operators' defining
properties, smoothing, distances against analytic values, the gradient against finite
differences, and the exceptions."""

import os
import signal
import tempfile
import threading
import time
import unittest

import numpy as np

import genflow


def octahedron(radius=1.0):
    V = radius * np.array(
        [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    F = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
                  [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]], dtype=np.int32)
    return V, F


def sphere(subdivisions=3, radius=1.0):
    """An octahedron subdivided and pushed onto the sphere."""
    V, F = octahedron()
    for _ in range(subdivisions):
        edges = {}
        vertices = list(V)
        faces = []

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in edges:
                edges[key] = len(vertices)
                vertices.append((V[a] + V[b]) / 2)
            return edges[key]

        for a, b, c in F:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            faces += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
        V = np.array(vertices)
        F = np.array(faces, dtype=np.int32)
    V = radius * V / np.linalg.norm(V, axis=1)[:, None]
    return V, F


class MeshFiles(unittest.TestCase):
    def test_a_mesh_and_its_attributes_come_back_from_every_format(self):
        V, F = sphere(2)
        colors = (255 * (V > 0)).astype(np.uint8)
        height = V[:, 2].copy()
        with tempfile.TemporaryDirectory() as directory:
            for name in ("a.ply", "a.obj", "a.off"):
                path = os.path.join(directory, name)
                genflow.write_mesh(path, V, F, {"colors": colors, "values": {"height": height}})
                V2, F2, attributes = genflow.read_mesh(path, attributes=True)
                np.testing.assert_array_equal(F2, F)
                np.testing.assert_array_equal(V2, V)
                np.testing.assert_array_equal(attributes["colors"], colors)
                if name == "a.ply":
                    np.testing.assert_array_equal(attributes["values"]["height"], height)
            warnings = genflow.write_mesh(os.path.join(directory, "a.stl"), V, F,
                                          {"colors": colors})
            self.assertEqual(len(warnings), 1)
            V2, F2 = genflow.read_mesh(os.path.join(directory, "a.stl"))
            self.assertEqual(V2.dtype, np.float64)
            self.assertEqual(F2.dtype, np.int32)
            self.assertEqual(V2.shape, V.shape)

    def test_arrays_of_any_layout_and_integer_type_are_taken(self):
        V, F = sphere(1)
        expected = genflow.vertex_normals(V, F)
        np.testing.assert_allclose(genflow.vertex_normals(np.asfortranarray(V), F.astype(np.int64)),
                                   expected)
        np.testing.assert_allclose(np.linalg.norm(expected, axis=1), 1.0)
        np.testing.assert_allclose(np.sum(expected * V, axis=1), 1.0, atol=0.05)

    def test_validate_reports_a_closed_sphere_and_an_index_out_of_range(self):
        V, F = sphere(1)
        report = genflow.validate(V, F)
        self.assertTrue(report["ok"])
        self.assertTrue(report["closed"])
        self.assertEqual(report["genus"], 0)
        F[0, 0] = len(V)
        report = genflow.validate(V, F)
        self.assertFalse(report["ok"])
        self.assertIn("error", [severity for severity, _ in report["issues"]])


class Errors(unittest.TestCase):
    def test_each_kind_is_raised_as_its_python_kind(self):
        with self.assertRaises(genflow.IoError) as raised:
            genflow.read_mesh("/nonexistent/mesh.ply")
        self.assertIsInstance(raised.exception, OSError)
        self.assertIn("/nonexistent/mesh.ply", str(raised.exception))
        V, F = sphere(1)
        with self.assertRaises(genflow.InvalidInput) as raised:
            genflow.smooth(V, F, method="nonsense")
        self.assertIsInstance(raised.exception, ValueError)
        with self.assertRaises(genflow.OutputError) as raised:
            genflow.write_mesh("/nonexistent/out.ply", V, F)
        self.assertIsInstance(raised.exception, genflow.IoError)
        with self.assertRaises(TypeError):  # not #V x 3: no such function
            genflow.vertex_normals(V[:, :2], F)
        V[0, 0] = np.nan
        with self.assertRaises(genflow.InvalidInput):
            genflow.cotan_stiffness(V, F)


class Operators(unittest.TestCase):
    def test_stiffness_is_symmetric_annihilates_constants_and_gives_the_area_gradient(self):
        V, F = sphere(2)
        K = genflow.cotan_stiffness(V, F)
        self.assertEqual(K.shape, (len(V), len(V)))
        self.assertLess(abs(K - K.T).max(), 1e-12)
        np.testing.assert_allclose(K @ np.ones(len(V)), 0, atol=1e-10)
        # The area's gradient is K V; on a sphere of radius r it points outward with |dA/dx| =
        # 2 m / r per vertex, m the vertex's mass.
        masses = genflow.mass_matrix(V, F, "voronoi").diagonal()
        gradient = K @ V
        ratio = np.sum(gradient * V, axis=1) / masses
        np.testing.assert_allclose(ratio, 2.0, rtol=0.05)

    def test_masses_sum_to_the_area_for_every_type(self):
        V, F = sphere(2)
        areas = [genflow.mass_matrix(V, F, kind).sum() for kind in ("full", "barycentric", "voronoi")]
        corners = V[F]
        area = 0.5 * np.linalg.norm(
            np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1).sum()
        np.testing.assert_allclose(areas, area, rtol=1e-12)
        with self.assertRaises(genflow.InvalidInput):
            genflow.mass_matrix(V, F, "lumpy")


class Smoothing(unittest.TestCase):
    def test_volume_fairing_removes_noise_without_shrinking(self):
        V, F = sphere(3)
        noisy = V + 0.02 * np.random.default_rng(7).standard_normal(V.shape)
        smoothed, info = genflow.smooth(noisy, F, method="volume-fairing", steps=5)
        self.assertEqual(info["steps"], 5)
        self.assertEqual(len(info["energy"]), 6)
        self.assertLess(info["energy"][-1], info["energy"][0])
        radii = np.linalg.norm(smoothed, axis=1)
        self.assertLess(radii.std(), np.linalg.norm(noisy, axis=1).std() / 2)
        self.assertLess(abs(radii.mean() - 1), 0.02)

    def test_a_frozen_metric_takes_the_same_first_step_and_another_flow_after(self):
        V, F = sphere(3)
        noisy = V + 0.02 * np.random.default_rng(7).standard_normal(V.shape)
        one, _ = genflow.smooth(noisy, F, method="fairing", steps=1)
        frozen_one, _ = genflow.smooth(noisy, F, method="fairing", steps=1, freeze_metric=True)
        np.testing.assert_array_equal(frozen_one, one)
        five, _ = genflow.smooth(noisy, F, method="fairing", steps=5)
        frozen_five, info = genflow.smooth(noisy, F, method="fairing", steps=5, freeze_metric=True)
        self.assertGreater(np.abs(frozen_five - five).max(), 0)
        self.assertLess(info["energy"][-1], info["energy"][0])

    def test_ctrl_c_stops_a_long_flow(self):
        V, F = sphere(3)
        timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        try:
            with self.assertRaises(KeyboardInterrupt):
                # Steps so small that the sphere never degenerates: only Ctrl-C ends it.
                genflow.smooth(V, F, method="fairing", steps=10**7, time_step=1e-9)
        finally:
            timer.cancel()
            timer.join()
        self.assertLess(time.monotonic() - start, 30)


class Threads(unittest.TestCase):
    def test_the_count_is_set_and_results_do_not_depend_on_it(self):
        V, F = sphere(3)
        before = genflow.thread_count()
        values = []
        for count in (1, 2):
            genflow.set_thread_count(count)
            self.assertEqual(genflow.thread_count(), count)
            values.append(genflow.pseudo_hausdorff(V, F, 1.1 * V, F)[0])
        genflow.set_thread_count(before)
        self.assertEqual(values[0], values[1])
        with self.assertRaises(genflow.InvalidInput):
            genflow.set_thread_count(0)


class Distances(unittest.TestCase):
    def test_concentric_spheres_are_the_difference_of_their_radii_apart(self):
        V, F = sphere(3)
        d = genflow.surface_distances(V, F, 1.5 * V, F)
        # The inner sphere's faces lie inside the unit sphere: distances up to 0.5 + sagitta.
        self.assertAlmostEqual(d["b_to_a"]["hausdorff"], 0.5, delta=0.02)
        self.assertGreaterEqual(d["hausdorff_upper_bound"], d["hausdorff"])
        self.assertAlmostEqual(d["mean"], 0.5, delta=0.03)
        alone = genflow.surface_distances(V, F, 1.5 * V, F, mean_and_rms=False)
        self.assertEqual(alone["hausdorff"], d["hausdorff"])
        self.assertNotIn("mean", alone)
        self.assertNotIn("rms", alone["a_to_b"])

    def test_the_pseudo_hausdorff_gradient_matches_finite_differences(self):
        V, F = sphere(1)
        target = 1.2 * V
        value, gradient = genflow.pseudo_hausdorff(V, F, target, F, alpha=4.0, epsilon=0.1)
        self.assertGreater(value, 0)
        self.assertEqual(gradient.shape, V.shape)
        step = 1e-6
        for vertex, axis in ((0, 0), (5, 1), (11, 2)):
            moved = V.copy()
            moved[vertex, axis] += step
            ahead, _ = genflow.pseudo_hausdorff(moved, F, target, F, alpha=4.0, epsilon=0.1)
            moved[vertex, axis] -= 2 * step
            behind, _ = genflow.pseudo_hausdorff(moved, F, target, F, alpha=4.0, epsilon=0.1)
            # The gradient holds the vertex masses fixed, which moving a vertex changes: a few
            # per cent of it (docs/formulas.md, section 8).
            self.assertAlmostEqual(gradient[vertex, axis], (ahead - behind) / (2 * step),
                                   delta=0.1 * abs(gradient[vertex, axis]) + 1e-9)


class Matching(unittest.TestCase):
    """A sphere matched onto an ellipsoid sampled more finely and moved: the deformed template
    lies on the target, and the match reports its progress and stops when asked."""

    def setUp(self):
        self.V, self.F = sphere(2)
        target, self.FT = sphere(3)
        self.VT = target * np.array([1.3, 1.0, 0.8]) + np.array([0.5, -0.2, 0.1])

    def test_the_deformed_template_lies_on_the_target(self):
        steps = []
        result = genflow.match(self.V, self.F, self.VT, self.FT, prior="h1", iterations=60,
                               progress=lambda p: steps.append(p["step"]) or True)
        self.assertEqual(result["V"].shape, self.V.shape)
        self.assertGreater(len(steps), 0)
        self.assertGreater(len(result["levels"]), 0)
        d = genflow.surface_distances(result["V"], self.F, self.VT, self.FT)
        diagonal = np.linalg.norm(self.VT.max(axis=0) - self.VT.min(axis=0))
        self.assertLess(d["mean"], 0.01 * diagonal)
        correspondence = result["correspondence"]
        self.assertEqual(correspondence["faces"].shape, (len(self.V),))
        self.assertTrue(np.all((0 <= correspondence["faces"]) & (correspondence["faces"] < len(self.FT))))
        np.testing.assert_allclose(correspondence["barycentric"].sum(axis=1), 1.0, atol=1e-9)

    def test_progress_returning_false_stops_the_match(self):
        calls = []
        genflow.match(self.V, self.F, self.VT, self.FT, iterations=60,
                      progress=lambda p: calls.append(p) or len(calls) < 3)
        self.assertEqual(len(calls), 3)

    def test_ctrl_c_and_errors_in_progress_stop_it_and_are_raised(self):
        def interrupt(p):
            if p["step"] == 2:
                os.kill(os.getpid(), signal.SIGINT)
            return True

        with self.assertRaises(KeyboardInterrupt):
            genflow.match(self.V, self.F, self.VT, self.FT, iterations=60, progress=interrupt)

        def fail(p):
            raise RuntimeError("stop here")

        with self.assertRaisesRegex(RuntimeError, "stop here"):
            genflow.match(self.V, self.F, self.VT, self.FT, progress=fail)
        with self.assertRaises(genflow.InvalidInput):
            genflow.match(self.V, self.F, self.VT, self.FT, prior="stiff")

    def test_the_options_reach_the_match(self):
        one = genflow.match(self.V, self.F, self.VT, self.FT, levels=1, iterations=20,
                            align=False, target_extent="complete")
        self.assertEqual(len(one["levels"]), 1)
        self.assertFalse(one["partial_target"])
        two = genflow.match(self.V, self.F, self.VT, self.FT, levels=2, coarse_vertices=100,
                            iterations=20, fine_iterations=3)
        self.assertEqual(len(two["levels"]), 2)
        with self.assertRaisesRegex(genflow.InvalidInput, "target_extent"):
            genflow.match(self.V, self.F, self.VT, self.FT, target_extent="most")
        with self.assertRaisesRegex(genflow.InvalidInput, "max_step"):
            genflow.match(self.V, self.F, self.VT, self.FT, max_step=0.0)

    def test_a_template_cache_gives_the_same_match_and_is_filled_once(self):
        alone = genflow.match(self.V, self.F, self.VT, self.FT, iterations=30)
        cache = genflow.TemplateCache()
        other = self.VT[:, [1, 2, 0]]  # another target: the template's analyses are the same
        genflow.match(self.V, self.F, other, self.FT, iterations=30, template_cache=cache)
        kept = len(cache)
        self.assertGreater(kept, 0)
        cached = genflow.match(self.V, self.F, self.VT, self.FT, iterations=30,
                               template_cache=cache)
        np.testing.assert_array_equal(cached["V"], alone["V"])
        self.assertEqual(len(cache), kept)


class PartModels(unittest.TestCase):
    """The articulated prior from Python: a part model made from arrays or read from files, and
    a match under it."""

    def setUp(self):
        self.V, self.F = sphere(2)
        # Two parts: the upper half hangs from the lower one at the equator's centre.
        labels = (self.V[:, 2] > 0).astype(int)
        self.weights = np.eye(2)[labels]
        self.labels = labels

    def test_a_model_from_arrays_is_checked_and_drives_an_articulated_match(self):
        model = genflow.PartModel(["lower", "upper"], [-1, 0], np.zeros((2, 3)), self.weights)
        self.assertEqual(model.names, ["lower", "upper"])
        self.assertEqual(model.parents, [-1, 0])
        np.testing.assert_array_equal(model.weights, self.weights)
        target = self.V * np.array([1.2, 1.0, 0.9]) + np.array([0.3, 0.0, -0.1])
        result = genflow.match(self.V, self.F, target, self.F, prior="articulated",
                               iterations=60, parts=model)
        d = genflow.surface_distances(result["V"], self.F, target, self.F)
        diagonal = np.linalg.norm(target.max(axis=0) - target.min(axis=0))
        self.assertLess(d["mean"], 0.01 * diagonal)
        with self.assertRaises(genflow.InvalidInput):
            genflow.match(self.V, self.F, target, self.F, prior="articulated")
        with self.assertRaises(genflow.InvalidInput):  # rows must sum to 1
            genflow.PartModel(["lower", "upper"], [-1, 0], np.zeros((2, 3)), 2 * self.weights)
        with self.assertRaises(genflow.InvalidInput):
            genflow.PartModel(["lower"], [-1, 0], np.zeros((2, 3)), self.weights)

    def test_a_model_is_read_from_a_tree_and_labels(self):
        with tempfile.TemporaryDirectory() as directory:
            tree = os.path.join(directory, "parts.json")
            with open(tree, "w") as file:
                file.write('{"parts": [{"name": "lower", "parent": null, "joint_center": [0, 0, 0]},'
                           ' {"name": "upper", "parent": "lower", "joint_center": [0, 0, 0]}]}')
            labels = os.path.join(directory, "labels.txt")
            with open(labels, "w") as file:
                file.write("".join("%d\n" % label for label in self.labels))
            model = genflow.read_part_model(tree, len(self.V), labels=labels)
            self.assertEqual(model.names, ["lower", "upper"])
            np.testing.assert_array_equal(model.weights, self.weights)
            with self.assertRaisesRegex(genflow.IoError, "labels.txt"):
                genflow.read_part_model(tree, len(self.V) + 1, labels=labels)


if __name__ == "__main__":
    unittest.main()

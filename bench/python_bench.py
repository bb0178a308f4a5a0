# SPDX-License-Identifier: MIT
"""Time of numpy arrays through the Python bindings: a mesh of about 100,000 vertices (a 317 x 317
grid) in and out of genflow, as vertex_normals takes V and F and returns #V x 3 normals, and the
normals alone in C++ for comparison (genflow_bench's BM_VertexNormals). Median of 50 calls.

Usage: PYTHONPATH=build/release/python /usr/bin/python3 bench/python_bench.py
"""

import statistics
import time

import numpy as np

import genflow


def grid(n):
    """An n x n grid of vertices in the plane z = 0, two triangles a cell."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    V = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    cells = np.arange(n * n).reshape(n, n)[:-1, :-1].ravel()
    F = np.concatenate([np.column_stack([cells, cells + 1, cells + n + 1]),
                        np.column_stack([cells, cells + n + 1, cells + n])]).astype(np.int32)
    return V, F


def median_ms(call, runs=50):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return 1000 * statistics.median(times)


def main():
    V, F = grid(317)
    genflow.set_thread_count(1)
    print("vertices %d, faces %d" % (len(V), len(F)))
    print("vertex_normals, arrays in and out: %.2f ms" % median_ms(lambda: genflow.vertex_normals(V, F)))
    Vf = np.asfortranarray(V)
    print("the same from column-major V: %.2f ms" % median_ms(lambda: genflow.vertex_normals(Vf, F)))


if __name__ == "__main__":
    main()

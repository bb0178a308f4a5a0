# SPDX-License-Identifier: MIT
"""One template matched onto many targets from Python, serially or spread over a Dask cluster.

Each target's result goes to OUTPUT_DIR as NAME.ply (the deformed template),
NAME.correspondence.npy (per template vertex a row: the target face, and the barycentric
coordinates on its corners) and NAME.json (the record), NAME the target's file name without its
extension. Every target is matched by
the same function wherever it runs, so a Dask run writes the same bytes as a serial one. Each
process reads the template once and keeps its analyses (genflow.TemplateCache) for every target
it matches.

    from dask.distributed import Client, LocalCluster
    import genflow.batch
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        records = genflow.batch.run_dask(client, "template.ply", targets, "out", prior="rigid")
"""

import io
import json
import os
import time

import numpy as np

from . import _core


def _name(target):
    return os.path.splitext(os.path.basename(target))[0]


def _write_atomically(path, data):
    temporary = path + ".tmp-%d" % os.getpid()
    with open(temporary, "wb") as file:
        file.write(data)
    os.replace(temporary, path)


def shard(targets, index, count):
    """Every count-th target from the index-th, as genflow batch --shard index/count takes them:
    the count shards take every target once."""
    if not 0 <= index < count:
        raise ValueError("shard: expected 0 <= index < count, got %d/%d" % (index, count))
    return targets[index::count]


def _finished(output_dir, name):
    """Whether an earlier run left all of the target's outputs (written whole, each atomically;
    the record last)."""
    return all(os.path.exists(os.path.join(output_dir, name + suffix))
               for suffix in (".ply", ".correspondence.npy", ".json"))


# This process's template: its file's identity and the part files, and what was made of them.
_template = {}


def _prepared_template(template, parts):
    """The template's V, F, part model (or None) and TemplateCache, made once per process and
    template file (a cache keeps everything it is given, so one template at a time)."""
    status = os.stat(template)
    key = (os.path.abspath(template), status.st_mtime_ns, status.st_size,
           json.dumps(parts, sort_keys=True))
    if _template.get("key") != key:
        _template.clear()
        V, F = _core.read_mesh(template)
        model = _core.read_part_model(vertices=len(V), **parts) if parts else None
        _template.update(key=key, value=(V, F, model, _core.TemplateCache()))
    return _template["value"]


def match_one(template, target, output_dir, threads=1, resume=False, parts=None, **options):
    """Matches the template file onto the target file with genflow.match(**options), writes the
    target's outputs and returns its record (name, target, status, seconds, error if failed).
    parts: genflow.read_part_model's arguments but `vertices` (a dict), for the articulated
    prior. A failure is recorded, not raised, so that a batch goes on. With resume, a target an
    earlier run finished is not matched again (status "done before")."""
    name = _name(target)
    record = {"name": name, "target": target, "genflow": _core.__version__, "options": options}
    if parts:
        record["parts"] = parts
    if resume and _finished(output_dir, name):
        record["status"] = "done before"
        return record
    _core.set_thread_count(threads)
    start = time.monotonic()
    try:
        V, F, model, cache = _prepared_template(template, parts)
        VT, FT = _core.read_mesh(target)
        result = _core.match(V, F, VT, FT, parts=model, template_cache=cache, **options)
        _core.write_mesh(os.path.join(output_dir, name + ".ply"), result["V"], F)
        # .npy holds no time stamp (unlike .npz): the same result gives the same bytes.
        rows = np.column_stack([result["correspondence"]["faces"].astype(np.float64),
                                result["correspondence"]["barycentric"]])
        correspondence = io.BytesIO()
        np.save(correspondence, rows)
        _write_atomically(os.path.join(output_dir, name + ".correspondence.npy"),
                          correspondence.getvalue())
        record.update(status="matched", pseudo_hausdorff=result["pseudo_hausdorff"],
                      converged=result["converged"])
    except (_core.InvalidInput, OSError, _core.SolverError) as error:  # IoError is an OSError
        record.update(status="failed", error=str(error))
    record["seconds"] = time.monotonic() - start
    _write_atomically(os.path.join(output_dir, name + ".json"),
                      (json.dumps(record, sort_keys=True) + "\n").encode())
    return record


def run_serial(template, targets, output_dir, **options):
    """match_one on every target in turn; the records in the targets' order."""
    os.makedirs(output_dir, exist_ok=True)
    return [match_one(template, target, output_dir, **options) for target in targets]


def run_dask(client, template, targets, output_dir, **options):
    """match_one on every target as a task of the Dask client's cluster; the records in the
    targets' order. The output directory must be one the workers share (one machine, or a
    shared file system)."""
    os.makedirs(output_dir, exist_ok=True)
    futures = client.map(match_one, [template] * len(targets), targets,
                         [output_dir] * len(targets), pure=False, **options)
    return client.gather(futures)

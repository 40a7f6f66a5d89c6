#!/usr/bin/env python3
"""Steadyray's CPU ray casting against Embree's, side by side, on the same rays, in one run.

Runs `steadyray raybench --dump-rays` once to get the triangles and the exact rays it traces
(primary and diffuse-bounce; the format is in crates/experiment/src/ray_dump.rs),
checks that Embree finds the same hits on them, then alternates: a `steadyray raybench`
run, an Embree run over the dumped rays, `--runs` times. Each run times every ray set
`--reps` times and keeps the median, as raybench does. Prints one JSON line: both ray
tracers' rays/s per set (median and range over the runs), their ratio (steadyray /
Embree) and the hit check. Exits with status 1 when the hits disagree.

Embree is reached through the `embreex` package (requirements.txt), whose only trace call,
`EmbreeScene.run`, takes arrays of rays and calls Embree's single-ray `rtcIntersect1` once
per ray in a loop that releases the GIL. The threaded loop below is raybench's: a pool of
`--threads` workers, each taking the next chunk of rays until none is left, timed by the
wall clock around one pass over all rays. See README.md beside this file for how that
differs from raybench's loop and by how much.
"""

import argparse
import itertools
import json
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from importlib.metadata import version
from pathlib import Path

import numpy as np
from embreex import mesh_construction, rtcore_scene

MAGIC = b"SRAYDUMP"
NO_HIT = 0xFFFF_FFFF
RAY = np.dtype(
    [
        ("origin", "<f4", 3),
        ("dir", "<f4", 3),
        ("t_min", "<f4"),
        ("t_max", "<f4"),
        ("hit_t", "<f4"),
        ("hit_triangle", "<u4"),
    ]
)
# Distances agree when they differ by at most this much relative to the larger. The two
# triangle tests compute t differently (Embree's and the watertight test); on the bunny
# 99.98 % of common hits agree within 1e-6, and grazing hits, where t is ill-conditioned,
# within 2e-5.
T_TOLERANCE = 1e-4
# Hits agree when at most this fraction of a set's rays hit in one tracer and miss (or hit
# at another distance) in the other: rays grazing an edge or a silhouette may tip either
# way under different rounding.
DISAGREE_TOLERANCE = 1e-4


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--steadyray", default="target/release/steadyray", help="the steadyray binary")
    p.add_argument("--mesh", required=True, help="the mesh file, as raybench takes it")
    p.add_argument("--camera", default="auto", help="raybench's --camera")
    p.add_argument("--width", type=int, default=1920)
    p.add_argument("--height", type=int, default=1080)
    p.add_argument("--subdivide", type=int, default=0)
    p.add_argument("--seed", type=int, default=1, help="raybench's bounce seed")
    p.add_argument("--threads", type=int, required=True, help="worker threads of both tracers")
    p.add_argument("--reps", type=int, default=9, help="timed passes per set per run (median)")
    p.add_argument("--runs", type=int, default=5, help="alternating runs of each tracer")
    p.add_argument(
        "--chunk",
        type=int,
        default=1024,
        help="rays per embreex call and per task, as raybench's (each call costs about a "
        "microsecond of Python, reported as embree_call_share)",
    )
    p.add_argument(
        "--robust",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="Embree's RTC_SCENE_FLAG_ROBUST (embreex's default)",
    )
    args = p.parse_args()
    for name in ("width", "height", "threads", "reps", "runs", "chunk"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be at least 1")
    return args


def raybench(args, dump=None):
    """One `steadyray raybench` run; its report."""
    command = [
        args.steadyray, "raybench", "--backend", "cpu",
        "--mesh", args.mesh, "--camera", args.camera,
        "--width", str(args.width), "--height", str(args.height),
        "--subdivide", str(args.subdivide), "--seed", str(args.seed),
        "--threads", str(args.threads), "--reps", str(args.reps),
    ]  # fmt: skip
    if dump is not None:
        command += ["--dump-rays", str(dump)]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"steadyray raybench failed:\n{done.stderr}")
    return json.loads(done.stdout)


def read_dump(path):
    """The triangles (N, 3, 3) and the ray sets {name: structured array} of a ray dump."""
    data = Path(path).read_bytes()
    if data[:8] != MAGIC:
        sys.exit(f"{path}: not a steadyray ray dump")
    ver, n_tris, n_sets, _ = np.frombuffer(data, "<u4", 4, 8)
    if ver != 1:
        sys.exit(f"{path}: ray dump version {ver}, this script reads version 1")
    at = 24
    tris = np.frombuffer(data, "<f4", 9 * n_tris, at).reshape(n_tris, 3, 3)
    at += 36 * int(n_tris)
    sets = {}
    for _ in range(n_sets):
        name = data[at : at + 16].rstrip(b"\0").decode("ascii")
        count = int(np.frombuffer(data, "<u8", 1, at + 16)[0])
        at += 24
        sets[name] = np.frombuffer(data, RAY, count, at)
        at += RAY.itemsize * count
    if at != len(data):
        sys.exit(f"{path}: {len(data) - at} bytes after the last ray set")
    return tris, sets


class EmbreeTracer:
    """The triangles in an Embree scene, traced by a pool of worker threads."""

    def __init__(self, tris, threads, chunk, robust):
        self.scene = rtcore_scene.EmbreeScene(robust=robust)
        mesh_construction.TriangleMesh(self.scene, np.ascontiguousarray(tris, np.float32))
        none = np.zeros((0, 3), np.float32)
        start = time.perf_counter()
        self.scene.run(none, none)  # the first call commits (builds) the scene
        self.build_s = time.perf_counter() - start
        self.pool = ThreadPoolExecutor(threads)
        self.threads, self.chunk = threads, chunk
        calls = 2000
        start = time.perf_counter()
        for _ in range(calls):
            self.scene.run(none, none)
        self.call_s = (time.perf_counter() - start) / calls

    def trace(self, origins, dirs, t_max):
        """One pass over all rays; their rays per second."""
        n, chunk = len(origins), self.chunk
        chunks = itertools.count()  # next() is atomic under the GIL

        def worker():
            while (a := next(chunks) * chunk) < n:
                b = a + chunk
                self.scene.run(origins[a:b], dirs[a:b], dists=t_max[a:b])

        start = time.perf_counter()
        for f in [self.pool.submit(worker) for _ in range(self.threads)]:
            f.result()
        return n / (time.perf_counter() - start)

    def closest(self, origins, dirs, t_max):
        """Every ray's closest hit: (t, triangle), triangle -1 for a miss."""
        out = self.scene.run(origins, dirs, dists=t_max.copy(), output=1)
        return out["tfar"], out["primID"]


def check_hits(rays, t, tri):
    """How Embree's hits (t, tri) compare with steadyray's, which are in the dump."""
    s_hit = rays["hit_triangle"] != NO_HIT
    e_hit = tri >= 0
    # embreex sets tnear = 0 on every ray, where steadyray's rays start at t_min: an Embree
    # hit on (0, t_min] lies outside steadyray's range, so that ray is counted apart.
    short = e_hit & (t <= rays["t_min"])
    both = s_hit & e_hit & ~short
    s_t, e_t = rays["hit_t"][both], t[both]
    rel = np.abs(s_t - e_t) / np.maximum(np.abs(s_t), np.abs(e_t))
    far = rel > T_TOLERANCE
    differ = (s_hit != e_hit) & ~short
    n = len(rays)
    return {
        "steadyray_hit_fraction": float(s_hit.mean()) if n else 0.0,
        "embree_hit_fraction": float(e_hit.mean()) if n else 0.0,
        "hit_only_steadyray": int(np.count_nonzero(differ & s_hit)),
        "hit_only_embree": int(np.count_nonzero(differ & e_hit)),
        "embree_hits_before_t_min": int(np.count_nonzero(short)),
        "t_beyond_tolerance": int(np.count_nonzero(far)),
        "t_max_relative_difference": float(rel.max()) if rel.size else 0.0,
        "other_triangle": int(np.count_nonzero(rays["hit_triangle"][both] != tri[both])),
        "agree": bool(np.count_nonzero(differ) + np.count_nonzero(far) <= DISAGREE_TOLERANCE * n),
    }


def spread(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values)}


def cpu_model():
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return platform.processor()


def main():
    args = parse_args()
    with tempfile.TemporaryDirectory(prefix="steadyray-embree-") as tmp:
        dump = Path(tmp) / "rays.bin"
        reports = [raybench(args, dump)]
        tris, sets = read_dump(dump)
    rays = {
        name: (
            np.ascontiguousarray(r["origin"]),
            np.ascontiguousarray(r["dir"]),
            np.ascontiguousarray(r["t_max"]),
        )
        for name, r in sets.items()
    }
    embree = EmbreeTracer(tris, args.threads, args.chunk, args.robust)
    hits = {name: check_hits(sets[name], *embree.closest(*rays[name])) for name in sets}

    embree_runs = {name: [] for name in sets}
    for run in range(args.runs):
        if run > 0:
            reports.append(raybench(args))
        for name, r in rays.items():
            embree_runs[name].append(statistics.median(embree.trace(*r) for _ in range(args.reps)))

    result = {
        "cpu": cpu_model(),
        "threads": args.threads,
        "runs": args.runs,
        "reps": args.reps,
        "mesh": args.mesh,
        "triangles": int(len(tris)),
        "steadyray_simd": reports[0]["simd"],
        "embree": {
            "embreex": version("embreex"),
            "robust": args.robust,
            "call": "EmbreeScene.run: rtcIntersect1 per ray, tnear 0",
            "rays_per_call": args.chunk,
            "seconds_per_call": embree.call_s,
            "build_s": embree.build_s,
        },
    }
    for name in sets:
        s = [rep[f"{name}_rays_per_s"] for rep in reports]
        e = embree_runs[name]
        n_calls = -(-len(sets[name]) // args.chunk)
        result[name] = {
            "rays": int(len(sets[name])),
            "steadyray_rays_per_s": spread(s),
            "embree_rays_per_s": spread(e),
            "ratio": statistics.median(s) / statistics.median(e),
            "ratio_per_run": spread([a / b for a, b in zip(s, e)]),
            # About the share of Embree's median pass its threads spend entering embreex
            # calls (an empty call's time, times the calls), which raybench does not pay.
            "embree_call_share": n_calls * embree.call_s * statistics.median(e)
            / (len(sets[name]) * args.threads),
            "hits": hits[name],
        }
    print(json.dumps(result))
    if not all(h["agree"] for h in hits.values()):
        sys.exit(1)


if __name__ == "__main__":
    main()

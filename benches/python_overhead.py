"""The Python package's cost over the library's own run, and over what a
Python user does without it (JSON through the command line).

    python benches/python_overhead.py [--receivers 1000000] [--runs 3] [--cli target/release/softshadow]

1. Overhead: for every setting of the default run (the `default` scene's
   sphere light, and `oess` on `linear-light`) and `exact`, the wall time of
   `scene.timed_visibility` (arrays in, the receivers checked and built,
   the run on a thread of its own with the GIL released, the result handed
   to numpy) against (a) the seconds the library reports for its own run
   (`method::run` on a ready frame: checks, stages, the method) and (b)
   that plus the seconds the receivers took to build from the arrays
   (`scene::file::receiver_from` per row, what a Rust caller holding the
   same arrays does too). Medians of --runs calls.
2. `hard` end to end: the numpy call against writing the points as a JSON
   points file, running `softshadow visibility` and parsing its JSON answer
   (median of --runs each, alternated).

Receivers: the floor (y = 1e-3, normal up, object 0) under the scene's
occluders, random non-dyadic positions, a fixed seed.
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import numpy as np

import softshadow

ROOT = pathlib.Path(__file__).resolve().parents[1]


def floor(n, seed=1, half=3.0):
    rng = np.random.default_rng(seed)
    p = np.column_stack([rng.uniform(-half, half, n), np.full(n, 1e-3), rng.uniform(-half, half, n)])
    normals = np.tile([0.0, 1.0, 0.0], (n, 1))
    objects = np.zeros(n, np.int64)
    return p, normals, objects


def overhead(scene_name, method, p, nrm, obj, runs):
    scene = softshadow.Scene.builtin(scene_name)
    rows = []
    for _ in range(runs):
        t = time.perf_counter()
        _, run, build = scene.timed_visibility(p, nrm, obj, method=method)
        rows.append((time.perf_counter() - t, run, build))
    med = lambda xs: statistics.median(xs)
    wall, run, build = (med([r[k] for r in rows]) for k in range(3))
    # Over the library's run on a ready frame, and over the run plus the
    # receivers built from the arrays (what a Rust caller does too).
    over_run = med([(w - r) / r for w, r, _ in rows])
    over_rust = med([(w - r - b) / (r + b) for w, r, b in rows])
    return wall, run, build, over_run, over_rust


def through_cli(cli, scene_name, p, nrm, obj, method):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "points.json")
        t = time.perf_counter()
        points = [{"p": list(a), "normal": list(b), "object": int(c)} for a, b, c in zip(p.tolist(), nrm.tolist(), obj)]
        with open(path, "w") as f:
            json.dump({"points": points}, f)
        out = subprocess.run(
            [str(cli), "visibility", "--scene", scene_name, "--points", path, "--method", method],
            check=True, capture_output=True, text=True,
        ).stdout
        v = np.array(json.loads(out)["visibility"])
        return time.perf_counter() - t, v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--receivers", type=int, default=1_000_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--cli", default=str(ROOT / "target" / "release" / "softshadow"))
    ap.add_argument("--only", help="one method (for a quick look)")
    args = ap.parse_args()
    n = args.receivers
    p, nrm, obj = floor(n)
    print(f"{n} receivers, median of {args.runs} runs, {os.cpu_count()} cores, numpy {np.__version__}")
    print("| scene | method | Python call (s) | method::run (s) | receivers built (s) | over method::run | over receivers + run |")
    print("|---|---|---:|---:|---:|---:|---:|")
    settings = [s for e in softshadow.methods() if "sphere" in e["lights"] for s in e["default_run"]]
    cases = [("default", m) for m in dict.fromkeys(["exact"] + settings)]
    cases.append(("linear-light", "oess"))
    for scene_name, method in cases:
        if args.only and method != args.only:
            continue
        wall, run, build, over_run, over_rust = overhead(scene_name, method, p, nrm, obj, args.runs)
        print(f"| {scene_name} | {method} | {wall:.3f} | {run:.3f} | {build:.3f} | {100 * over_run:+.1f} % | {100 * over_rust:+.1f} % |", flush=True)
    if args.only and args.only != "hard":
        return
    scene = softshadow.Scene.builtin("default")
    numpy_s, cli_s = [], []
    for _ in range(args.runs):
        t = time.perf_counter()
        v = scene.visibility(p, nrm, obj, method="hard")
        numpy_s.append(time.perf_counter() - t)
        s, w = through_cli(args.cli, "default", p, nrm, obj, "hard")
        cli_s.append(s)
    assert np.array_equal(v, w), "the two paths disagree"
    a, b = statistics.median(numpy_s), statistics.median(cli_s)
    print(f"\nhard, end to end: numpy call {a:.3f} s, JSON + CLI + parse {b:.3f} s: {b / a:.1f}x")


if __name__ == "__main__":
    main()

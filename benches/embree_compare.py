#!/usr/bin/env python3
"""Embree 4 half of the opt-in occlusion-ray comparison (not part of CI).

    /work/venv-embree/bin/python benches/embree_compare.py [outdir] [--reps N] [--threads N]

Run `benches/compare_embree.sh` for both halves side by side. This script
reads the corpora that `examples/ray_corpus.rs` wrote to `outdir` (default
`target/ray_corpus`; file format documented there), builds an Embree scene
of the same triangles, and times occlusion queries for exactly the same rays.

Setup: a Python venv with PyPI `embreex` (Embree 4 bundled in the wheel) and
numpy:

    python3 -m venv /work/venv-embree
    /work/venv-embree/bin/pip install embreex numpy

Mapping of the open segment (p, x) to an Embree ray:

- origin p and the triangle corners are passed as f32; the corpus rounds
  every coordinate to f32 before use, so these are the very same values our
  exact f64 test sees;
- direction d = x - p, computed in f64 and rounded once to f32;
- tnear = 0 (embreex fixes it) and tfar = 1 - 2^-20, i.e. slightly below 1
  so that the end x itself is excluded as in the open segment. In this
  corpus both ends lie on planes (z = -0.5 floor, z = 1.5 light) that no
  triangle comes near (all geometry lies in 0.05 <= z <= 0.95), so the
  precise tnear/tfar do not change any answer; the script checks that
  tfar = 1 gives the same hits.

What is timed: `EmbreeScene.run(origins, dirs, dists=tfar, query='OCCLUDED')`,
which in embreex 4.4 is a Cython loop over rtcOccluded1 (single rays, no
packets or streams) that releases the GIL. Embree itself has no per-query
thread pool (its TBB threads are used for the BVH build only), so 2-thread
throughput comes from 2 Python threads each calling `run` on chunks of 65,536
rays (like rayon's par_chunks on the Rust side). The 1-thread figure is
printed too; the speedup shows whether the GIL really was released. Warm-up
run first (it also commits the scene, i.e. builds the BVH, timed
separately), then the median of --reps repetitions (default 7).

Two Embree scene configurations are timed: the default one (the headline
figure) and RTC_SCENE_FLAG_ROBUST (`EmbreeScene(robust=True)`, watertight
mode). For each, the per-ray answers are compared with ours
(`<scene>.ours.occluded`, if present): the disagreements are rays whose
answer differs between f32 Embree and the exact f64 test.

Output: human-readable lines, plus one `RESULT key=value ...` line per scene
and configuration for scripts.
"""

import argparse
import os
import struct
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import embreex
import embreex.mesh_construction as mesh_construction
import embreex.rtcore as rtcore
import embreex.rtcore_scene as rtcore_scene

MAGIC = b"SSRAYC1\0"
HEADER = 64
CHUNK = 65536
TFAR = np.float32(1.0 - 2.0**-20)


def embree_version():
    """The version of the Embree library embreex was built against, e.g. '4.4.0'."""
    text = repr(rtcore.EmbreeDevice())  # 'Embree version:  4.4.0'
    return text.split(":")[-1].strip()


def load(path):
    with open(path, "rb") as f:
        header = f.read(HEADER)
    if header[:8] != MAGIC:
        sys.exit(f"{path}: not a ray corpus (bad magic)")
    version, _reserved, seed, ntri, nray = struct.unpack_from("<IIQQQ", header, 8)
    if version != 1:
        sys.exit(f"{path}: unsupported corpus version {version}")
    name = header[48:64].rstrip(b"\0").decode("ascii")
    data = np.fromfile(path, dtype="<f8", offset=HEADER)
    if data.size != 9 * ntri + 6 * nray:
        sys.exit(f"{path}: truncated ({data.size} values)")
    tris = data[: 9 * ntri].reshape(ntri, 3, 3)
    p = data[9 * ntri : 9 * ntri + 3 * nray].reshape(nray, 3)
    x = data[9 * ntri + 3 * nray :].reshape(nray, 3)
    return name, seed, tris, p, x


def occluded(scene, origins, dirs, tfar):
    """1 where the ray [0, tfar] is occluded. embreex returns 0 (the hit
    geometry id, Embree 4 `tfar = -inf` convention) for occluded rays and -1
    for unoccluded ones."""
    ids = scene.run(origins, dirs, dists=tfar.copy(), query="OCCLUDED")
    return (ids != -1).astype(np.uint8)


def run_threads(scene, origins, dirs, tfar, threads, pool):
    if threads == 1:
        return occluded(scene, origins, dirs, tfar)
    n = len(origins)
    slices = [slice(i, min(i + CHUNK, n)) for i in range(0, n, CHUNK)]
    parts = pool.map(lambda s: occluded(scene, origins[s], dirs[s], tfar[s]), slices)
    return np.concatenate(list(parts))


def timed(f, reps):
    f()  # warm-up
    times = []
    for _ in range(reps):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return float(np.median(times)), min(times), max(times), out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", nargs="?", default="target/ray_corpus")
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scenes", nargs="+", default=["soup", "sphere"])
    args = ap.parse_args()

    version = embree_version()
    print(f"embreex {embreex.__version__}, Embree {version}, numpy {np.__version__}")
    if not version.startswith("4."):
        sys.exit(f"expected Embree 4.x, found {version}")
    print(f"EMBREE_VERSION {version}")

    pool = ThreadPoolExecutor(args.threads)
    for scene_name in args.scenes:
        path = os.path.join(args.outdir, f"{scene_name}.rays")
        name, seed, tris, p, x = load(path)
        n = len(p)
        origins = np.ascontiguousarray(p.astype(np.float32))
        dirs = np.ascontiguousarray((x - p).astype(np.float32))
        tfar = np.full(n, TFAR, dtype=np.float32)
        ours_path = os.path.join(args.outdir, f"{scene_name}.ours.occluded")
        ours = np.fromfile(ours_path, dtype=np.uint8) if os.path.exists(ours_path) else None
        if ours is not None and len(ours) != n:
            sys.exit(f"{ours_path}: {len(ours)} results for {n} rays")
        print(f"{name}: {len(tris)} triangles, {n} rays (seed {seed})")

        for mode in ["default", "robust"]:
            scene = rtcore_scene.EmbreeScene(robust=(mode == "robust"))
            mesh_construction.TriangleMesh(scene, np.ascontiguousarray(tris.astype(np.float32)))
            t = time.perf_counter()
            occluded(scene, origins[:1], dirs[:1], tfar[:1])  # commits: builds the BVH
            build = time.perf_counter() - t

            one, _, _, hits_1t = timed(lambda: run_threads(scene, origins, dirs, tfar, 1, pool), args.reps)
            med, lo, hi, hit = timed(
                lambda: run_threads(scene, origins, dirs, tfar, args.threads, pool), args.reps
            )
            assert (hit == hits_1t).all()
            full = occluded(scene, origins, dirs, np.ones(n, dtype=np.float32))
            if (full != hit).any():
                print(f"  note: tfar = 1 changes {int((full != hit).sum())} answers")
            hits = int(hit.sum())
            rate = n / med
            line = (
                f"  Embree {mode}: build {build * 1e3:.1f} ms; occluded {hits} of {n} "
                f"({100 * hits / n:.2f}%); {args.threads} threads median {med * 1e3:.1f} ms "
                f"(min {lo * 1e3:.1f}, max {hi * 1e3:.1f}) = {rate / 1e6:.3f} Mrays/s; "
                f"1 thread {n / one / 1e6:.3f} Mrays/s (speedup {one / med:.2f})"
            )
            print(line)
            result = (
                f"RESULT scene={name} mode={mode} rays={n} hits={hits} median_s={med:.6f} "
                f"rays_per_s={rate:.0f} rays_per_s_1t={n / one:.0f} threads={args.threads}"
            )
            if ours is not None:
                ours_only = int(((ours == 1) & (hit == 0)).sum())
                embree_only = int(((ours == 0) & (hit == 1)).sum())
                print(
                    f"    vs ours: ours {int(ours.sum())} hits; {ours_only + embree_only} rays disagree "
                    f"({ours_only} occluded only for ours, {embree_only} only for Embree)"
                )
                result += f" ours_hits={int(ours.sum())} disagree={ours_only + embree_only}"
                result += f" ours_only={ours_only} embree_only={embree_only}"
            print(result)
            del scene
    pool.shutdown()


if __name__ == "__main__":
    main()

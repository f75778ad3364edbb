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
packets or streams). Embree itself has no per-query thread pool (its TBB
threads are used for the BVH build only), and 2 Python threads calling `run`
were measured to give no speedup (embreex does not keep the GIL released
across the loop), so 2-way parallelism comes from 2 worker *processes*
(multiprocessing, spawn), each holding its own copy of the scene and the
rays, fed chunks of 65,536 rays in order (like rayon's par_chunks on the Rust
side); the timed wall clock covers dispatch and gathering the answers into
one array. The 1-thread figure (in-process) is printed too. Warm-up run first
(committing the scene, i.e. building the BVH, is timed separately), then the
median of --reps repetitions (default 7). The workers' CPU time
(time.thread_time around each chunk) is summed per repetition: rays per
CPU-second is the less noisy measure of per-ray cost on a shared machine.

Two Embree scene configurations are timed: the default one (the headline
figure) and RTC_SCENE_FLAG_ROBUST (`EmbreeScene(robust=True)`, watertight
mode). For each, the per-ray answers are compared with ours
(`<scene>.ours.occluded`, if present): the disagreements are rays whose
answer differs between f32 Embree and the exact f64 test.

Output: human-readable lines, plus one `RESULT key=value ...` line per scene
and configuration for scripts.
"""

import argparse
import multiprocessing
import os
import struct
import sys
import time

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
    """1 where the ray [0, tfar] is occluded. embreex 4.4 returns 0 for an
    occluded ray (Embree 4 sets its tfar to -inf) and -1 for an unoccluded
    one; older embreex returned the geometry id (also 0 here) or -1."""
    ids = scene.run(origins, dirs, dists=tfar.copy(), query="OCCLUDED")
    return (ids != -1).astype(np.uint8)


# Per worker process: the scene and rays of the current configuration.
_WORKER = {}


def _worker_init(path, robust):
    _, _, tris, p, x = load(path)
    scene, origins, dirs, tfar, _ = build(tris, p, x, robust)
    _WORKER.update(scene=scene, origins=origins, dirs=dirs, tfar=tfar)


def _worker_chunk(bounds):
    lo, hi = bounds
    w = _WORKER
    cpu = time.thread_time()
    out = occluded(w["scene"], w["origins"][lo:hi], w["dirs"][lo:hi], w["tfar"][lo:hi])
    return lo, out.tobytes(), time.thread_time() - cpu


def build(tris, p, x, robust):
    """The Embree scene (committed), the f32 rays, and the commit time."""
    scene = rtcore_scene.EmbreeScene(robust=robust)
    mesh_construction.TriangleMesh(scene, np.ascontiguousarray(tris.astype(np.float32)))
    origins = np.ascontiguousarray(p.astype(np.float32))
    dirs = np.ascontiguousarray((x - p).astype(np.float32))
    tfar = np.full(len(p), TFAR, dtype=np.float32)
    t = time.perf_counter()
    occluded(scene, origins[:1], dirs[:1], tfar[:1])  # commits: builds the BVH
    return scene, origins, dirs, tfar, time.perf_counter() - t


def run_pool(pool, n):
    """The answers, and the CPU time the workers spent on them."""
    out = np.empty(n, dtype=np.uint8)
    cpu = 0.0
    chunks = [(i, min(i + CHUNK, n)) for i in range(0, n, CHUNK)]
    for lo, data, chunk_cpu in pool.imap_unordered(_worker_chunk, chunks):
        out[lo : lo + len(data)] = np.frombuffer(data, dtype=np.uint8)
        cpu += chunk_cpu
    return out, cpu


def run_here(scene, origins, dirs, tfar):
    cpu = time.thread_time()
    out = occluded(scene, origins, dirs, tfar)
    return out, time.thread_time() - cpu


def timed(f, reps):
    """Median, min and max wall time, median CPU time, and the answers."""
    f()  # warm-up
    times, cpus = [], []
    for _ in range(reps):
        t = time.perf_counter()
        out, cpu = f()
        times.append(time.perf_counter() - t)
        cpus.append(cpu)
    return float(np.median(times)), min(times), max(times), float(np.median(cpus)), out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", nargs="?", default="target/ray_corpus")
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--threads", type=int, default=2, help="worker processes")
    ap.add_argument("--scenes", nargs="+", default=["soup", "sphere"])
    args = ap.parse_args()

    version = embree_version()
    print(f"embreex {embreex.__version__}, Embree {version}, numpy {np.__version__}")
    if not version.startswith("4."):
        sys.exit(f"expected Embree 4.x, found {version}")
    print(f"EMBREE_VERSION {version}")

    ctx = multiprocessing.get_context("spawn")
    for scene_name in args.scenes:
        path = os.path.join(args.outdir, f"{scene_name}.rays")
        name, seed, tris, p, x = load(path)
        n = len(p)
        ours_path = os.path.join(args.outdir, f"{scene_name}.ours.occluded")
        ours = np.fromfile(ours_path, dtype=np.uint8) if os.path.exists(ours_path) else None
        if ours is not None and len(ours) != n:
            sys.exit(f"{ours_path}: {len(ours)} results for {n} rays")
        print(f"{name}: {len(tris)} triangles, {n} rays (seed {seed})")

        for mode in ["default", "robust"]:
            robust = mode == "robust"
            scene, origins, dirs, tfar, build_s = build(tris, p, x, robust)
            one, _, _, _, hit_1t = timed(lambda: run_here(scene, origins, dirs, tfar), args.reps)
            full = occluded(scene, origins, dirs, np.ones(n, dtype=np.float32))
            if (full != hit_1t).any():
                print(f"  note: tfar = 1 changes {int((full != hit_1t).sum())} answers")
            del scene
            with ctx.Pool(args.threads, _worker_init, (path, robust)) as pool:
                med, lo, hi, cpu, hit = timed(lambda: run_pool(pool, n), args.reps)
            assert (hit == hit_1t).all(), "answers differ between 1 and N processes"
            hits = int(hit.sum())
            rate = n / med
            line = (
                f"  Embree {mode}: build {build_s * 1e3:.1f} ms; occluded {hits} of {n} "
                f"({100 * hits / n:.2f}%); {args.threads} processes median {med * 1e3:.1f} ms "
                f"(min {lo * 1e3:.1f}, max {hi * 1e3:.1f}) = {rate / 1e6:.3f} Mrays/s; "
                f"1 thread {n / one / 1e6:.3f} Mrays/s (speedup {one / med:.2f}); "
                f"CPU time {cpu * 1e3:.1f} ms: {n / cpu / 1e6:.3f} Mrays per CPU-second"
            )
            print(line)
            result = (
                f"RESULT scene={name} mode={mode} rays={n} hits={hits} median_s={med:.6f} "
                f"min_s={lo:.6f} rays_per_s={rate:.0f} rays_per_s_1t={n / one:.0f} "
                f"cpu_s={cpu:.6f} rays_per_cpu_s={n / cpu:.0f} "
                f"threads={args.threads}"
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
            print(result, flush=True)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Embree 4 half of the opt-in closest-hit (primary ray) comparison (not CI).

    /work/venv-embree/bin/python benches/embree_primary.py [outdir] [--reps N] [--threads N]

Run `benches/compare_embree_primary.sh` for both halves side by side. This
script reads `primary.rays`, which `examples/primary_corpus.rs` wrote to
`outdir` (default `target/ray_corpus`; format documented there: the default
scene's triangles and one camera ray per pixel, 512 x 512), builds an Embree
scene of the same triangles (one triangle mesh, so Embree's primID is our
triangle index) and times closest-hit queries for exactly the same rays.

Mapping: origins, directions and corners are passed as f32 (the corpus holds
f32 values, so these are the very values our f64 code sees); tnear = 0
(embreex fixes it), tfar = +inf (embreex's default, 1e37).

What is timed: `EmbreeScene.run(origins, dirs, query='INTERSECT',
output=True)`, a Cython loop over rtcIntersect1 that returns, per ray, t,
primID, geomID, the barycentrics and the geometric normal (what our `Hit`
holds); `output=False` (primID only) is timed too, and the headline Embree
figure is the faster of the two. As in `embree_compare.py` (whose helpers
this script imports), 2-way parallelism comes from 2 worker processes
(spawn), each holding its own scene and rays, fed chunks of 16 image rows in
order; the wall clock covers dispatch and gathering. Warm-up first, then the
median of --reps repetitions (default 7), wall and CPU time (time.thread_time
around each chunk in the workers).

Per-ray comparison with ours (`primary.ours.hits`, if present): rays on which
hit/miss differs, rays hitting different triangles, and for rays both hit the
relative difference of t (f32 against exact-decision f64).

Output: human-readable lines and one `RESULT key=value ...` line per Embree
mode for scripts.
"""

import argparse
import multiprocessing
import os
import struct
import sys
import time

import numpy as np

import embreex.mesh_construction as mesh_construction
import embreex.rtcore_scene as rtcore_scene

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from embree_compare import embree_version, timed  # noqa: E402

MAGIC = b"SSPRIM1\0"
HEADER = 64
ROWS_PER_CHUNK = 16


def load(path):
    with open(path, "rb") as f:
        header = f.read(HEADER)
    if header[:8] != MAGIC:
        sys.exit(f"{path}: not a primary-ray corpus (bad magic)")
    version, _reserved, width, height, ntri, nray = struct.unpack_from("<IIIIQQ", header, 8)
    if version != 1:
        sys.exit(f"{path}: unsupported corpus version {version}")
    if nray != width * height:
        sys.exit(f"{path}: {nray} rays for {width} x {height}")
    data = np.fromfile(path, dtype="<f8", offset=HEADER)
    if data.size != 9 * ntri + 6 * nray:
        sys.exit(f"{path}: truncated ({data.size} values)")
    tris = data[: 9 * ntri].reshape(ntri, 3, 3)
    o = data[9 * ntri : 9 * ntri + 3 * nray].reshape(nray, 3)
    d = data[9 * ntri + 3 * nray :].reshape(nray, 3)
    return width, height, tris, o, d


def build(tris, o, d):
    scene = rtcore_scene.EmbreeScene()
    t = time.perf_counter()
    mesh_construction.TriangleMesh(scene, tris.astype(np.float32))
    # Committing happens on the first query: time one ray.
    scene.run(o[:1].astype(np.float32), d[:1].astype(np.float32))
    build_s = time.perf_counter() - t
    return scene, o.astype(np.float32), d.astype(np.float32), build_s


def intersect(scene, origins, dirs, output):
    """(t, primID) per ray: t = inf and primID = -1 for a miss."""
    if output:
        r = scene.run(origins, dirs, query="INTERSECT", output=True)
        prim = r["primID"].astype(np.int64)
        t = np.where(prim >= 0, r["tfar"].astype(np.float64), np.inf)
        return t, prim
    prim = scene.run(origins, dirs, query="INTERSECT").astype(np.int64)
    return None, prim


_WORKER = {}


def _worker_init(path, output):
    _, _, tris, o, d = load(path)
    scene, origins, dirs, _ = build(tris, o, d)
    _WORKER.update(scene=scene, origins=origins, dirs=dirs, output=output)


def _worker_chunk(bounds):
    lo, hi = bounds
    w = _WORKER
    cpu = time.thread_time()
    t, prim = intersect(w["scene"], w["origins"][lo:hi], w["dirs"][lo:hi], w["output"])
    cpu = time.thread_time() - cpu
    return lo, (None if t is None else t.tobytes()), prim.tobytes(), cpu


def run_pool(pool, n, width):
    t_all = np.full(n, np.inf)
    prim_all = np.full(n, -1, dtype=np.int64)
    cpu = 0.0
    step = ROWS_PER_CHUNK * width
    chunks = [(i, min(i + step, n)) for i in range(0, n, step)]
    for lo, t, prim, chunk_cpu in pool.imap_unordered(_worker_chunk, chunks):
        p = np.frombuffer(prim, dtype=np.int64)
        prim_all[lo : lo + len(p)] = p
        if t is not None:
            t_all[lo : lo + len(p)] = np.frombuffer(t, dtype=np.float64)
        cpu += chunk_cpu
    return (t_all, prim_all), cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", nargs="?", default="target/ray_corpus")
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--threads", type=int, default=2, help="worker processes")
    args = ap.parse_args()

    version = embree_version()
    print(f"Embree {version}, numpy {np.__version__}")
    if not version.startswith("4."):
        sys.exit(f"expected Embree 4.x, found {version}")
    print(f"EMBREE_VERSION {version}")

    path = os.path.join(args.outdir, "primary.rays")
    width, height, tris, o, d = load(path)
    n = len(o)
    ours_path = os.path.join(args.outdir, "primary.ours.hits")
    ours = None
    if os.path.exists(ours_path):
        raw = np.fromfile(ours_path, dtype=np.uint8)
        if raw.size != 12 * n:
            sys.exit(f"{ours_path}: {raw.size} bytes for {n} rays")
        ours_t = np.frombuffer(raw[: 8 * n].tobytes(), dtype="<f8")
        ours_prim = np.frombuffer(raw[8 * n :].tobytes(), dtype="<u4").astype(np.int64)
        ours_prim[ours_prim == 0xFFFFFFFF] = -1
        ours = (ours_t, ours_prim)
    print(f"default: {len(tris)} triangles, {width} x {height} = {n} primary rays")

    ctx = multiprocessing.get_context("spawn")
    scene, origins, dirs, build_s = build(tris, o, d)
    for output in [True, False]:
        mode = "output" if output else "primid"
        # In-process, one thread (its CPU time is not used).
        one_med, _, _, _, _ = timed(
            lambda: (intersect(scene, origins, dirs, output), 0.0), args.reps
        )
        with ctx.Pool(args.threads, _worker_init, (path, output)) as pool:
            med, lo, hi, cpu, (t, prim) = timed(lambda: run_pool(pool, n, width), args.reps)
        hits = int((prim >= 0).sum())
        rate = n / med
        print(
            f"  Embree INTERSECT ({mode}): build {build_s * 1e3:.1f} ms; hit {hits} of {n}; "
            f"{args.threads} processes median {med * 1e3:.1f} ms (min {lo * 1e3:.1f}, "
            f"max {hi * 1e3:.1f}) = {rate / 1e6:.3f} Mrays/s; 1 process {n / one_med / 1e6:.3f} "
            f"Mrays/s; CPU time {cpu * 1e3:.1f} ms: {n / cpu / 1e6:.3f} Mrays per CPU-second"
        )
        result = (
            f"RESULT scene=primary mode={mode} rays={n} hits={hits} median_s={med:.6f} "
            f"min_s={lo:.6f} rays_per_s={rate:.0f} rays_per_s_1t={n / one_med:.0f} "
            f"cpu_s={cpu:.6f} rays_per_cpu_s={n / cpu:.0f} threads={args.threads}"
        )
        if ours is not None:
            ours_t, ours_prim = ours
            ours_hit, emb_hit = ours_prim >= 0, prim >= 0
            hit_miss = int((ours_hit != emb_hit).sum())
            both = ours_hit & emb_hit
            other_tri = int((both & (ours_prim != prim)).sum())
            print(
                f"    vs ours: ours hit {int(ours_hit.sum())}; hit/miss differs on {hit_miss} "
                f"rays ({int((ours_hit & ~emb_hit).sum())} hit only for ours); "
                f"{other_tri} of {int(both.sum())} rays both hit meet different triangles"
            )
            result += f" ours_hits={int(ours_hit.sum())} hit_miss_disagree={hit_miss}"
            result += f" other_triangle={other_tri}"
            if output:
                rel = np.abs(t[both] - ours_t[both]) / ours_t[both]
                within6 = int((rel <= 1e-6).sum())
                within4 = int((rel <= 1e-4).sum())
                print(
                    f"    t: {within6} of {int(both.sum())} within 1e-6 relative, {within4} "
                    f"within 1e-4, max {rel.max():.2e}, median {np.median(rel):.2e}"
                )
                result += f" t_within_1e-6={within6} t_within_1e-4={within4} t_max_rel={rel.max():.3e}"
        print(result, flush=True)


if __name__ == "__main__":
    main()

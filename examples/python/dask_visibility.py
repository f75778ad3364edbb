"""V for a receiver set split into chunks over a dask.distributed cluster.

    python examples/python/dask_visibility.py [--scene default] [--method exact]
        [--receivers 200000] [--chunk 20000] [--scheduler ADDRESS]

Without --scheduler it starts a LocalCluster on this machine (one worker
process per core). To use a real cluster, start a scheduler and workers
that have the softshadow package installed (`pip install ./python`) and
pass the scheduler's address, or make the cluster in Python, e.g. on Slurm
with dask-jobqueue:

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(cores=32, memory="64GB", walltime="01:00:00")
    cluster.scale(jobs=8)
    client = Client(cluster)

Each chunk is computed by a worker that builds the scene from its name
(a built-in scene or a scene file path every worker can read): a
softshadow.Scene is not sent between processes. The answer is checked to
be bit-identical to one process's: `exact`, `hard` and `mc:N` are
per-receiver computations (Monte Carlo's samples are keyed by the seed
and the receiver's position), so splitting the receivers changes no bit.
Methods that fit light-view maps to the frame's receivers (pcss, sism,
ssoc, ...) depend on which receivers share a frame, and are refused here.
"""

import argparse
import sys
import time

import numpy as np
from dask.distributed import wait

import softshadow

# Methods whose value at a receiver does not depend on the other receivers
# of the call.
PER_RECEIVER = ("exact", "hard", "mc")


def scene_of(name):
    """The scene called `name`: a built-in scene, else a scene file."""
    if name in softshadow.builtin_names():
        return softshadow.Scene.builtin(name)
    return softshadow.Scene.from_file(name)


def chunk_visibility(points, scene, method, seed):
    """One chunk's V, on a worker."""
    return scene_of(scene).visibility(points, method=method, seed=seed)


def receivers(scene, n, seed=1):
    """n receivers on the floor y = 0 under a built-in scene's occluders
    (random, non-dyadic positions)."""
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(-3, 3, n), np.full(n, 1e-3), rng.uniform(-3, 3, n)])


def distributed_visibility(client, scene, points, method="exact", seed=None, chunk=20000, timeout=None):
    """V of every row of `points`, the rows split into chunks of `chunk`
    computed on the cluster of `client`, gathered in order (waiting at most
    `timeout` seconds, if given)."""
    base = method.split(":")[0]
    if base not in PER_RECEIVER:
        raise ValueError(
            f"method {base}: its values depend on the frame's receivers; "
            f"chunking is bit-identical only for {', '.join(PER_RECEIVER)}"
        )
    chunks = [points[i : i + chunk] for i in range(0, len(points), chunk)]
    futures = client.map(chunk_visibility, chunks, scene=scene, method=method, seed=seed, pure=False)
    if timeout is not None:
        wait(futures, timeout=timeout)
    return np.concatenate(client.gather(futures)) if chunks else np.empty(0)


def main(argv=None):
    from dask.distributed import Client, LocalCluster

    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="default")
    ap.add_argument("--method", default="exact")
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--receivers", type=int, default=200_000)
    ap.add_argument("--chunk", type=int, default=20_000)
    ap.add_argument("--scheduler", help="a running scheduler's address (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes")
    args = ap.parse_args(argv)

    points = receivers(args.scene, args.receivers)
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=":0")
        client = Client(cluster)
    with client:
        t = time.perf_counter()
        v = distributed_visibility(client, args.scene, points, args.method, args.seed, args.chunk)
        cluster_s = time.perf_counter() - t
    t = time.perf_counter()
    one = scene_of(args.scene).visibility(points, method=args.method, seed=args.seed)
    one_s = time.perf_counter() - t
    same = np.array_equal(v.view(np.uint64), one.view(np.uint64))
    print(
        f"{len(points)} receivers, {args.scene}, {args.method}: cluster {cluster_s:.2f} s "
        f"in {-(-len(points) // args.chunk)} chunks, one process {one_s:.2f} s; "
        f"mean V {v.mean():.6f}; bit-identical: {same}"
    )
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())

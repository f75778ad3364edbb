"""The Dask example: V over a LocalCluster of worker processes, in chunks,
equals one process's bit for bit."""

import importlib
import os
import pathlib
import sys

import numpy as np
import pytest

import softshadow

distributed = pytest.importorskip("dask.distributed")

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "dask_visibility.py"


@pytest.fixture(scope="module")
def example():
    """The example, imported by name here and on the workers (which start
    with this environment: PYTHONPATH names its folder)."""
    folder = str(EXAMPLE.parent)
    old = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = folder + (os.pathsep + old if old else "")
    sys.path.insert(0, folder)
    try:
        yield importlib.import_module("dask_visibility")
    finally:
        sys.path.remove(folder)
        if old is None:
            del os.environ["PYTHONPATH"]
        else:
            os.environ["PYTHONPATH"] = old


@pytest.fixture(scope="module")
def client(example):
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0")
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


@pytest.mark.parametrize("method,seed", [("exact", None), ("mc:64", 9), ("hard", None)])
def test_chunks_on_a_cluster_equal_one_process(example, client, method, seed):
    points = example.receivers("default", 5000, seed=4)
    v = example.distributed_visibility(client, "default", points, method, seed, chunk=700, timeout=120)
    one = softshadow.Scene.builtin("default").visibility(points, method=method, seed=seed)
    assert v.shape == one.shape
    assert np.array_equal(v.view(np.uint64), one.view(np.uint64))
    assert 0 < np.mean(v) < 1  # the receivers see shadow and light


def test_frame_dependent_methods_are_refused(example, client):
    with pytest.raises(ValueError, match="pcss: its values depend on the frame's receivers"):
        example.distributed_visibility(client, "default", np.zeros((4, 3)), "pcss")


def test_the_example_runs(example):
    assert example.main(["--receivers", "3000", "--chunk", "1000", "--workers", "2"]) == 0

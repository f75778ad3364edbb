"""Shared fixtures: the command-line program (the independent path the
package's answers are compared with) and scenes with closed-form answers."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import softshadow

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    """The `softshadow` program: $SOFTSHADOW_CLI, else the workspace's
    release build (built here if missing)."""
    path = os.environ.get("SOFTSHADOW_CLI")
    if path:
        path = pathlib.Path(path)
        assert path.is_file(), f"SOFTSHADOW_CLI={path}: no such program"
        return path
    path = ROOT / "target" / "release" / "softshadow"
    subprocess.run(
        ["cargo", "build", "--release", "--quiet", "-p", "softshadow-cli"],
        cwd=ROOT,
        check=True,
    )
    return path


def run_cli(cli, *args):
    """Runs the program; its stdout, failing the test on a non-zero exit."""
    r = subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True)
    assert r.returncode == 0, f"softshadow {' '.join(map(str, args))}: {r.stderr}"
    return r.stdout


def cli_visibility(cli, tmp_path, scene, points, normals, objects, method, seed=None):
    """V by `softshadow visibility` on .npy points, read back from its .npy."""
    pts = tmp_path / "points.npy"
    obj = tmp_path / "objects.npy"
    out = tmp_path / "v.npy"
    np.save(pts, np.hstack([points, normals]))
    np.save(obj, objects.astype(np.int64))
    args = ["visibility", "--scene", scene, "--points", pts, "--objects", obj,
            "--method", method, "--out", out]
    if seed is not None:
        args += ["--seed", seed]
    run_cli(cli, *args)
    v = np.load(out)
    stderr = tmp_path / "v.stderr.npy"
    return v, (np.load(stderr) if stderr.exists() else None)


def camera_receivers(scene, width, height):
    """The receivers a scene's camera sees: positions, normals, object ids
    and the exact V, each over the surface pixels."""
    g = scene.gbuffer(width, height)
    hit = g["object"] >= 0
    return g["position"][hit], g["normal"][hit], g["object"][hit], g["exact"][hit]


def default_methods(kind):
    """Every setting of the default run for a light kind, from the registry."""
    return [s for m in softshadow.methods() if kind in m["lights"] for s in m["default_run"]]


class HalfPlane:
    """A light at height H above the floor y = 0 and an opaque half-plane
    x < e at height Y (0 < Y < H): from a receiver p on the floor, the light
    point (x, H, z) is hidden exactly when x < x* = p_x + (e - p_x)·H/Y, so
    V is the share of the light beyond x* — a closed form for a segment
    along x (its length), a rect (its area) and a disk facing the floor
    (a circular segment's area)."""

    def __init__(self, rng):
        self.H = 3.0 + rng.uniform(0.1, 0.9)
        self.Y = self.H * rng.uniform(0.3, 0.7)
        self.e = rng.uniform(-0.3, 0.3)
        self.cx, self.cz = rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)
        big = 1e3
        e, Y = self.e, self.Y
        self.mesh = (
            np.array([[-big, Y, -big], [e, Y, -big], [e, Y, big], [-big, Y, big]]),
            np.array([[0, 1, 2], [0, 2, 3]]),
        )

    def threshold(self, px):
        return px + (self.e - px) * self.H / self.Y

    def receivers(self, rng, n, reach):
        """n floor receivers whose x* falls within ±reach of the light's
        centre (so V spans (0, 1))."""
        # x* = px (1 - H/Y) + e H/Y, solved for px.
        k = self.H / self.Y
        xs = self.cx + rng.uniform(-reach, reach, n)
        px = (xs - self.e * k) / (1.0 - k)
        pz = self.cz + rng.uniform(-1e-3, 1e-3, n)
        return np.column_stack([px, np.zeros(n), pz])

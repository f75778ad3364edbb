"""The package's answers equal the command line's bit for bit: on every
built-in scene, for `exact` and every setting of the default run, on the
receivers the scene's camera sees; the G-buffer's arrays and the score's
fields likewise."""

import json

import numpy as np
import pytest

import softshadow
from conftest import camera_receivers, cli_visibility, default_methods, run_cli

SCENES = softshadow.builtin_names()


@pytest.mark.parametrize("name", SCENES)
def test_visibility_equals_the_cli(cli, tmp_path, name):
    scene = softshadow.Scene.builtin(name)
    p, n, o, exact = camera_receivers(scene, 40, 30)
    assert len(p) > 100
    methods = ["exact"] + default_methods(scene.light_kind)
    assert len(methods) >= 3, methods
    for method in methods:
        want, want_se = cli_visibility(cli, tmp_path, name, p, n, o, method)
        got = scene.visibility(p, normals=n, objects=o, method=method)
        assert got.dtype == np.float64 and got.shape == want.shape
        assert np.array_equal(got.view(np.uint64), want.view(np.uint64)), (name, method)
        if method.startswith("mc:"):
            samples = int(method[3:].split(",")[0])
            v, se = scene.monte_carlo(p, samples, normals=n)
            assert np.array_equal(v, want) and np.array_equal(se, want_se), (name, method)
    # The exact values equal the G-buffer's (one computation path each).
    assert np.array_equal(scene.visibility(p, n, o), exact)


def test_seeded_monte_carlo_equals_the_cli(cli, tmp_path):
    scene = softshadow.Scene.builtin("rect-light")
    p, n, o, _ = camera_receivers(scene, 32, 24)
    want, want_se = cli_visibility(cli, tmp_path, "rect-light", p, n, o, "mc:48", seed=977)
    v, se = scene.monte_carlo(p, 48, seed=977)
    assert np.array_equal(v, want) and np.array_equal(se, want_se)


@pytest.mark.parametrize("name", ["default", "linear-light"])
def test_gbuffer_and_score_equal_the_cli(cli, tmp_path, name):
    w, h = 48, 36
    scene = softshadow.Scene.builtin(name)
    g = scene.gbuffer(w, h)
    run_cli(cli, "gbuffer", "--scene", name, "--width", w, "--height", h, "--out", tmp_path)
    for key in ["position", "normal", "object", "exact"]:
        want = np.load(tmp_path / f"{key}.npy")
        assert g[key].shape == want.shape and g[key].dtype == want.dtype, key
        assert np.array_equal(g[key], want, equal_nan=key != "object"), key
    assert g["camera"] == json.loads((tmp_path / "camera.json").read_text())
    # An image made elsewhere: the exact values with noise and a NaN pixel.
    rng = np.random.default_rng(7)
    image = np.clip(g["exact"] + rng.normal(0, 0.05, (h, w)), 0, 1)
    image[np.isnan(image)] = 0.5
    hit = g["object"] >= 0
    row, col = np.argwhere(hit)[len(np.argwhere(hit)) // 2]
    image[row, col] = np.nan
    np.save(tmp_path / "image.npy", image)
    want = json.loads(run_cli(cli, "score", "--scene", name, "--image", tmp_path / "image.npy", "--json"))
    assert softshadow.score(scene, image) == want
    want = json.loads(run_cli(cli, "score", "--scene", name, "--image", tmp_path / "image.npy",
                              "--gbuffer", tmp_path, "--json"))
    assert softshadow.score(scene, image, gbuffer=g) == want
    # The exact image scores zero error; the noisy one its own RMSE.
    assert softshadow.score(scene, np.nan_to_num(g["exact"]))["rmse"] == 0.0
    ok = hit & ~np.isnan(image)
    rmse = np.sqrt(np.mean((image[ok] - g["exact"][ok]) ** 2))
    assert abs(want["rmse"] - rmse) < 1e-12 and want["nan_pixels"] == 1
    assert want["first_nan"] == [row, col]

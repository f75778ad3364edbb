"""Every bad input raises a Python exception (ValueError, OSError) with the
library's one-line message: never a crash, never a panic escaping."""

import numpy as np
import pytest

import softshadow


@pytest.fixture(scope="module")
def scene():
    return softshadow.Scene.builtin("default")


@pytest.fixture(scope="module")
def points():
    rng = np.random.default_rng(3)
    return np.column_stack([rng.uniform(-2, 2, 50), np.full(50, 1e-3), rng.uniform(-2, 2, 50)])


def raises(exc, match, f, *args, **kwargs):
    with pytest.raises(exc, match=match) as info:
        f(*args, **kwargs)
    message = str(info.value)
    assert "\n" not in message and "panic" not in message.lower(), message
    return message


def test_arrays(scene, points):
    vis = scene.visibility
    raises(ValueError, r"points: shape \[50, 2\], expected \(n, 3\)", vis, points[:, :2])
    raises(ValueError, r"points: shape \[150\]", vis, points.ravel())
    raises(ValueError, r"points: dtype int64, expected float64", vis, points.astype(np.int64))
    raises(ValueError, r"points: dtype complex128", vis, points.astype(complex))
    raises(ValueError, r"points: the array is not C-contiguous", vis, points[::2])
    raises(ValueError, r"points: the array is not C-contiguous", vis, np.asfortranarray(points))
    for bad, word in [(np.nan, "NaN"), (np.inf, "inf"), (-np.inf, "-inf"), (3e30, "3000000000000000000000000000000")]:
        p = points.copy()
        p[7, 1] = bad
        raises(ValueError, rf"points: row 7: {word} is not a finite number within ±1e30", vis, p)
    raises(ValueError, r"points: shape \[\], expected \(n, 3\)", vis, "nope")
    raises(ValueError, r"points: not an array|points: shape", vis, [[1, 2, 3], [4, 5]])
    n = np.tile([0.0, 1.0, 0.0], (50, 1))
    raises(ValueError, r"normals: shape \[49, 3\], points has 50 rows", vis, points, normals=n[:49])
    z = n.copy()
    z[4] = 0
    raises(ValueError, r"normals: row 4: the normal has zero length", vis, points, normals=z)
    o = np.zeros(50, np.int64)
    raises(ValueError, r"objects: shape \[49\]", vis, points, objects=o[:49])
    raises(ValueError, r"objects: dtype float64, expected integers", vis, points, objects=o.astype(float))
    o[9] = 2
    raises(ValueError, r"objects: row 9: object id 2, the scene has meshes 0 to 1", vis, points, objects=o)
    o[9] = -1
    raises(ValueError, r"objects: row 9: object id -1", vis, points, objects=o)
    # Lists are arrays too; wrong lists are refused the same way.
    assert scene.visibility(points.tolist()).shape == (50,)


def test_methods_and_seeds(scene, points):
    vis = scene.visibility
    m = raises(ValueError, r"unknown method 'nope'; available: hard, pcss", vis, points, method="nope")
    assert "exact" in m
    raises(ValueError, r"method oess does not handle a sphere light", vis, points, method="oess")
    raises(ValueError, r"pcss", vis, points, method="pcss:map=0")
    raises(ValueError, r"seed=3: method hard has no seed \(methods with one: mc:N\)", vis, points, method="hard", seed=3)
    raises(ValueError, r"seed=3: method mc:8,seed=2 sets seed= already", vis, points, method="mc:8,seed=2", seed=3)
    raises(ValueError, r"needs receiver normals; receiver 0 has none", vis, points, method="sism:horizon")
    raises(ValueError, r"needs receiver object ids", vis, points, normals=np.tile([0.0, 1, 0], (50, 1)), method="single-sample")
    raises(ValueError, r"'mc:1': N must be an integer from 2 to 4294967295, got '1'", scene.monte_carlo, points, 1)
    raises(ValueError, r"samples=-4: expected an integer from 2 to 4294967295", scene.monte_carlo, points, -4)
    raises(ValueError, r"seed=-1: expected an integer from 0 to 18446744073709551615", vis, points, method="mc:8", seed=-1)
    raises(ValueError, r"seed=18446744073709551616: expected", vis, points, method="mc:8", seed=2**64)
    raises(ValueError, r"seed=1.5: expected", vis, points, method="mc:8", seed=1.5)


def test_receiver_the_light_cannot_be_seen_from():
    scene = softshadow.Scene([], softshadow.SphereLight([0.1, 2.3, -0.2], 0.5))
    p = np.array([[5.0, 0.0, 0.0], [0.1, 2.4, -0.2]])
    raises(ValueError, r"points: row 1: ", scene.visibility, p)
    disk = softshadow.Scene([], softshadow.DiskLight([0, 2, 0], [0, 1, 0], 0.5))
    raises(ValueError, r"points: row 0: ", disk.visibility, np.array([[3.0, 2.0, 0.0]]))


def test_lights():
    raises(ValueError, r"radius", softshadow.SphereLight, [0, 0, 0], -1)
    raises(ValueError, r"radius", softshadow.SphereLight, [0, 0, 0], float("nan"))
    raises(ValueError, r"light field `center` is not finite", softshadow.SphereLight, [0, float("inf"), 0], 1)
    raises(ValueError, r"disk light normal is zero", softshadow.DiskLight, [0, 0, 0], [0, 0, 0], 1)
    raises(ValueError, r"rect light half-axes span no area", softshadow.RectLight, [0, 0, 0], [1, 0, 0], [1, 0, 0])
    raises(ValueError, r"segment light endpoints coincide", softshadow.SegmentLight, [1, 2, 3], [1, 2, 3])
    raises(ValueError, r"light field `position` is not finite", softshadow.PointLight, [float("nan"), 0, 0])
    with pytest.raises(ValueError, match="expected a sequence of length 3"):
        softshadow.SphereLight([0, 0], 1)


def test_meshes():
    light = softshadow.PointLight([0, 3, 0])
    pos = np.array([[0.0, 1, 0], [1, 1, 0], [0, 1, 1]])
    tri = np.array([[0, 1, 2]])
    assert softshadow.Scene([(pos, tri)], light).triangle_count == 1
    named = softshadow.Scene(meshes=[(pos, tri)], light=light, names=["card"])
    assert named.mesh_names == ["card"] and named.light_kind == "point"
    assert softshadow.Scene([(pos, tri.astype(np.uint32))], light).triangle_count == 1
    raises(ValueError, r"meshes\[0\]: triangle 0 refers to vertex 3, but there are 3 vertices", softshadow.Scene, [(pos, tri + 1)], light)
    raises(ValueError, r"meshes\[0\] triangles: row 0: vertex index -1", softshadow.Scene, [(pos, tri - 1)], light)
    raises(ValueError, r"meshes\[0\] triangles: dtype float64", softshadow.Scene, [(pos, tri.astype(float))], light)
    raises(ValueError, r"meshes\[0\] triangles: shape \[3\]", softshadow.Scene, [(pos, tri[0])], light)
    bad = pos.copy()
    bad[1, 2] = np.nan
    raises(ValueError, r"meshes\[0\] positions: row 1: NaN is not a finite number", softshadow.Scene, [(bad, tri)], light)
    raises(ValueError, r"meshes\[0\]: expected a \(positions, triangles\) pair", softshadow.Scene, [pos], light)
    raises(ValueError, r"names: 2 names for 1 meshes", softshadow.Scene, [(pos, tri)], light, names=["a", "b"])
    with pytest.raises(TypeError):
        softshadow.Scene([(pos, tri)], "a light")


def test_files(tmp_path):
    raises(FileNotFoundError, r"nope\.json: cannot read", softshadow.Scene.from_file, tmp_path / "nope.json")
    raises(IsADirectoryError, r"not a regular file", softshadow.Scene.from_file, tmp_path)
    f = tmp_path / "bad.json"
    f.write_text('{"light": {"sphere": {"center": [0, 1, 0], "radius": -2}}}')
    raises(ValueError, r"bad\.json: ", softshadow.Scene.from_file, f)
    f.write_text('{"light": ')
    raises(ValueError, r"bad\.json:1:", softshadow.Scene.from_file, f)
    raises(ValueError, r'no built-in scene "nope" \(built-in: default, ', softshadow.Scene.builtin, "nope")


def test_gbuffer_and_score(scene):
    raises(ValueError, r"0×10 pixels; an image is 1 to 16384 pixels a side", scene.gbuffer, 0, 10)
    raises(ValueError, r"an image is 1 to 16384", scene.gbuffer, 10, 20000)
    raises(ValueError, r"width=-3: expected an integer from 1 to 16384", scene.gbuffer, -3, 10)
    no_camera = softshadow.Scene([], softshadow.PointLight([0, 1, 0]))
    raises(ValueError, r"the scene has no camera", no_camera.gbuffer, 4, 4)
    raises(ValueError, r"the scene has no camera", softshadow.score, no_camera, np.zeros((4, 4)))
    raises(ValueError, r"image: shape \[16\], expected \(height, width\)", softshadow.score, scene, np.zeros(16))
    raises(ValueError, r"image: dtype int64", softshadow.score, scene, np.zeros((4, 4), np.int64))
    g = scene.gbuffer(8, 6)
    raises(ValueError, r"gbuffer\['position'\]: shape \[6, 8, 3\], the image is 9×6", softshadow.score, scene, np.zeros((6, 9)), gbuffer=g)
    raises(ValueError, r"gbuffer: no 'normal' array", softshadow.score, scene, np.zeros((6, 8)), gbuffer={"position": g["position"]})
    bad = dict(g)
    bad["object"] = g["object"].copy()
    bad["object"][2, 3] = 7
    raises(ValueError, r"gbuffer\['object'\]: pixel \(row 2, column 3\)", softshadow.score, scene, np.zeros((6, 8)), gbuffer=bad)

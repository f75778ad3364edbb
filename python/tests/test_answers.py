"""The package's answers against independent ones: closed forms for the
exact reference and the point light, Monte Carlo within tolerances derived
from its sample count, and its standard error's honesty."""

import math

import numpy as np
import pytest

import softshadow
from conftest import HalfPlane


def share_beyond(t):
    """The share of a unit disk's area at signed distance > t from a
    diameter (a circular segment), t clamped to [-1, 1]."""
    t = np.clip(t, -1.0, 1.0)
    return (np.arccos(t) - t * np.sqrt(1.0 - t * t)) / math.pi


def disk_visibility(h, centre, normal, radius, p):
    """V of a disk (centre, unit normal, radius) from floor receivers p
    behind the half-plane h: the light point x is hidden exactly when
    w·x < c, w = (Y, p_x − e, 0), c = Y p_x (the ray from p crosses y = Y at
    x < e); the hidden part of the disk is a circular segment."""
    centre = np.asarray(centre, float)
    out = []
    for q in p:
        n = np.asarray(normal(q) if callable(normal) else normal, float)
        n = n / np.linalg.norm(n)
        w = np.array([h.Y, q[0] - h.e, 0.0])
        c = h.Y * q[0]
        wt = w - (w @ n) * n
        t = (c - w @ centre) / (np.linalg.norm(wt) * radius)
        out.append(share_beyond(t))
    return np.array(out)


@pytest.fixture
def rng():
    return np.random.default_rng(0x5EED_44)


def test_segment_rect_disk_sphere_point_closed_forms(rng):
    h = HalfPlane(rng)
    L = rng.uniform(0.4, 0.9)
    c = np.array([h.cx, h.H, h.cz])
    p = h.receivers(rng, 300, reach=1.2 * L)
    xs = h.threshold(p[:, 0])
    up = np.array([0.0, 1.0, 0.0])
    cases = {
        # A segment along x: the length beyond x*.
        "segment": (softshadow.SegmentLight(c - [L, 0, 0], c + [L, 0, 0]),
                    np.clip((h.cx + L - xs) / (2 * L), 0, 1)),
        # A rect with half-axes along x and z: the area beyond x*, a strip.
        "rect": (softshadow.RectLight(c, [L, 0, 0], [0, 0, 0.7 * L]),
                 np.clip((h.cx + L - xs) / (2 * L), 0, 1)),
        "disk": (softshadow.DiskLight(c, up, L), share_beyond((xs - h.cx) / L)),
        # A sphere: its facing disk, normal (c − p)/|c − p|.
        "sphere": (softshadow.SphereLight(c, L),
                   disk_visibility(h, c, lambda q: c - q, L, p)),
        "point": (softshadow.PointLight(c), (xs <= h.cx).astype(float)),
    }
    for kind, (light, want) in cases.items():
        scene = softshadow.Scene([h.mesh], light)
        assert scene.light_kind == kind
        v = scene.visibility(p)
        assert v.shape == (len(p),) and v.dtype == np.float64
        # The exact reference's own tolerance against closed forms
        # (docs/accuracy/references.md: every case < 1e-9).
        if kind == "point":
            # No receiver within 1e-9 of the shadow's edge decides it.
            keep = np.abs(xs - h.cx) > 1e-9
            assert np.array_equal(v[keep], want[keep]), kind
        else:
            assert np.max(np.abs(v - want)) < 1e-9, kind
            assert 0.1 < np.mean((v > 0) & (v < 1)), kind  # the penumbra is tested


def test_monte_carlo_within_its_sample_count_tolerance(rng):
    """mc:N on the closed-form disk: |V̂ − V| within 5 standard deviations
    for every receiver. The library's N samples are 16 replicates of a
    scrambled (0, 2)-sequence; a scrambled net's variance is at most e
    times that of as many independent samples (Owen 1997), so the standard
    deviation is at most sqrt(e · V(1 − V) / N)."""
    h = HalfPlane(rng)
    L = 0.6
    c = np.array([h.cx, h.H, h.cz])
    p = h.receivers(rng, 400, reach=1.0)
    want = share_beyond((h.threshold(p[:, 0]) - h.cx) / L)
    scene = softshadow.Scene([h.mesh], softshadow.DiskLight(c, [0, 1, 0], L))
    n = 256
    v, stderr = scene.monte_carlo(p, n, seed=11)
    assert v.shape == stderr.shape == (len(p),)
    bound = 5 * np.sqrt(math.e * want * (1 - want) / n) + 1e-12
    assert np.all(np.abs(v - want) <= bound)
    # The method name's form gives the same numbers.
    assert np.array_equal(scene.visibility(p, method="mc:256", seed=11), v)
    assert np.array_equal(scene.visibility(p, method="mc:256,seed=11"), v)
    assert not np.array_equal(scene.monte_carlo(p, n, seed=12)[0], v)


def test_monte_carlo_stderr_is_honest():
    """(V̂ − V_exact)/stderr over many seeds and penumbra receivers of a
    built-in scene: the share of |t| > 2 is Student's t with K − 1 = 15
    degrees of freedom's, P(|t₁₅| > 2) = 0.0639 (the library's estimator
    has 16 independent replicates), within 5 binomial standard deviations
    of the count. Errors at different receivers and seeds are independent
    (the sample patterns are keyed by seed and position)."""
    scene = softshadow.Scene.builtin("overlapping-penumbrae")
    g = scene.gbuffer(96, 72)
    hit = (g["object"] >= 0) & (g["exact"] > 0.05) & (g["exact"] < 0.95)
    p, exact = g["position"][hit], g["exact"][hit]
    assert len(p) >= 200
    p, exact = p[:300], exact[:300]
    t = []
    for seed in range(40):
        v, se = scene.monte_carlo(p, 64, seed=seed)
        ok = se > 0
        t.append((v[ok] - exact[ok]) / se[ok])
    t = np.concatenate(t)
    share = np.mean(np.abs(t) > 2)
    p15 = 0.0639
    sd = math.sqrt(p15 * (1 - p15) / len(t))
    print(f"share of |t| > 2: {share:.4f} of {len(t)} (t15: {p15})")
    assert abs(share - p15) < 5 * sd, (share, len(t))


def test_far_from_the_origin(rng):
    """The closed-form rect at an offset of 1e6: the inputs are rounded to
    ulp(1e6) = 1.2e-10, which moves x* by at most a few times that (H/Y ≤
    3.4): V within 1e-8."""
    h = HalfPlane(rng)
    off = np.array([1e6 + 0.37, 0.0, -1e6 + 0.61])
    L = 0.5
    c = np.array([h.cx, h.H, h.cz])
    p = h.receivers(rng, 200, reach=0.6)
    pos, tri = h.mesh
    scene = softshadow.Scene([(pos + off, tri)], softshadow.RectLight(c + off, [L, 0, 0], [0, 0, L]))
    v = scene.visibility(p + off)
    xs = h.threshold(p[:, 0])
    assert np.max(np.abs(v - np.clip((h.cx + L - xs) / (2 * L), 0, 1))) < 1e-8

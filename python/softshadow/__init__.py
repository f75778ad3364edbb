"""softshadow: soft-shadow references, methods and scoring on numpy arrays.

The Python package of the softshadow Rust library (built by maturin with
PyO3 and rust-numpy). Everything computes in Rust with the GIL released;
Ctrl-C interrupts a long call (``KeyboardInterrupt``) within a second.

- ``Scene.from_file(path)``, ``Scene.builtin(name)``,
  ``Scene(meshes=[(positions, triangles), ...], light=...)`` with the
  lights ``SphereLight``, ``DiskLight``, ``RectLight``, ``SegmentLight``,
  ``PointLight``;
- ``scene.visibility(points, normals=None, objects=None, method="exact",
  seed=None)`` for every method of the registry (``methods()``);
- ``scene.monte_carlo(points, samples, seed=None, normals=None)`` ->
  ``(V, stderr)``;
- ``scene.gbuffer(width, height)`` and ``score(scene, image,
  gbuffer=None)``.

Bad input raises ``ValueError`` (``OSError`` for a file that cannot be
read) with the library's one-line message. See docs/python.md.
"""

from ._native import (
    DiskLight,
    Light,
    PointLight,
    RectLight,
    Scene,
    SegmentLight,
    SphereLight,
    __version__,
    builtin_names,
    methods,
    score,
)

__all__ = [
    "DiskLight",
    "Light",
    "PointLight",
    "RectLight",
    "Scene",
    "SegmentLight",
    "SphereLight",
    "__version__",
    "builtin_names",
    "methods",
    "score",
]

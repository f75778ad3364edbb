"""Type stubs of the softshadow package (the binding's docstrings, typed)."""

from os import PathLike
from typing import Any, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

Vec3 = Union[Sequence[float], npt.NDArray[np.floating[Any]]]
FloatArray = npt.NDArray[np.float64]

class Light:
    """A light: one of SphereLight, DiskLight, RectLight, SegmentLight,
    PointLight."""

    @property
    def kind(self) -> str:
        """The light's kind: "sphere", "disk", "rect", "segment" or "point"."""
    @property
    def center(self) -> list[float]:
        """The light's centre."""

class SphereLight(Light):
    """A sphere light; V is the visible share of its facing disk (centre,
    radius, normal towards the receiver). ValueError for a non-finite
    centre or a radius not positive and finite."""

    def __init__(self, center: Vec3, radius: float) -> None: ...

class DiskLight(Light):
    """A disk light, emitting on both sides. ValueError for a zero normal
    or a radius not positive."""

    def __init__(self, center: Vec3, normal: Vec3, radius: float) -> None: ...

class RectLight(Light):
    """A rectangle light with perpendicular half-extent vectors u and v,
    emitting on both sides. ValueError for degenerate or
    non-perpendicular half-extents."""

    def __init__(self, center: Vec3, u: Vec3, v: Vec3) -> None: ...

class SegmentLight(Light):
    """A segment (linear) light from a to b, uniform along its length.
    ValueError for coincident ends."""

    def __init__(self, a: Vec3, b: Vec3) -> None: ...

class PointLight(Light):
    """A point light: V is 0 or 1."""

    def __init__(self, position: Vec3) -> None: ...

class Method(TypedDict):
    name: str
    usage: str
    summary: str
    lights: list[str]
    options: list[str]
    default_run: list[str]
    compare: list[str]

class GBuffer(TypedDict):
    position: FloatArray
    normal: FloatArray
    object: npt.NDArray[np.int32]
    exact: FloatArray
    camera: dict[str, Any]

class Scene:
    """Occluder meshes and one light (and a camera for a built-in scene or
    a scene file with one). Immutable; safe to share between threads."""

    def __init__(
        self,
        meshes: Sequence[Tuple[npt.ArrayLike, npt.ArrayLike]],
        light: Light,
        names: Optional[Sequence[str]] = None,
    ) -> None:
        """meshes: (positions (n, 3) float, triangles (m, 3) integer) pairs.
        ValueError for a non-finite or out-of-domain (beyond ±1e30)
        position, an index out of range, a wrong shape or dtype."""
    @staticmethod
    def from_file(path: Union[str, PathLike[str]]) -> Scene:
        """A scene file (JSON; the OBJ meshes it names relative to it).
        FileNotFoundError/OSError when it cannot be read, ValueError for
        its content, with the library's one-line message."""
    @staticmethod
    def builtin(name: str) -> Scene:
        """A built-in scene (builtin_names()). ValueError for an unknown name."""
    @property
    def light_kind(self) -> str: ...
    @property
    def mesh_names(self) -> list[str]: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def camera_resolution(self) -> Optional[Tuple[int, int]]: ...
    def visibility(
        self,
        points: npt.ArrayLike,
        normals: Optional[npt.ArrayLike] = None,
        objects: Optional[npt.ArrayLike] = None,
        method: str = "exact",
        seed: Optional[int] = None,
    ) -> FloatArray:
        """V at each receiver by a method of the registry ("exact",
        "mc:256", "sism:horizon", ...): an (n,) float64 array. points (n, 3)
        float64 (float32 widened), read in place when C-contiguous;
        normals (n, 3) (normalised; some methods need them); objects (n,)
        integer mesh ids (some methods need them); seed: the Monte Carlo
        seed. ValueError for bad input, an unknown method, a method that
        does not serve the light; KeyboardInterrupt on Ctrl-C."""
    def timed_visibility(
        self,
        points: npt.ArrayLike,
        normals: Optional[npt.ArrayLike] = None,
        objects: Optional[npt.ArrayLike] = None,
        method: str = "exact",
        seed: Optional[int] = None,
    ) -> Tuple[FloatArray, float, float]:
        """visibility(), the seconds the library's run took (method::run)
        and the seconds the receivers took to build from the arrays (for
        measuring the binding's overhead)."""
    def monte_carlo(
        self,
        points: npt.ArrayLike,
        samples: int,
        seed: Optional[int] = None,
        normals: Optional[npt.ArrayLike] = None,
    ) -> Tuple[FloatArray, FloatArray]:
        """Monte Carlo light sampling (method mc:samples): (V, stderr)."""
    def gbuffer(self, width: int, height: int) -> GBuffer:
        """The receivers the scene's camera sees at width × height, row 0 at
        the top: position (h, w, 3), normal (h, w, 3), object (h, w) int32
        (-1 where no surface), exact (h, w) (NaN where no surface), camera."""

def score(scene: Scene, image: npt.ArrayLike, gbuffer: Optional[dict[str, Any]] = None) -> dict[str, Any]:
    """An image of V made elsewhere, (h, w) float, scored against the exact
    answer on our camera's receivers at its size, or those of gbuffer
    (position, normal, object arrays): the fields of
    `softshadow score --json`."""

def methods() -> list[Method]:
    """The registry: per method its name, usage, summary, lights served,
    options, default-run and report settings."""

def builtin_names() -> list[str]:
    """The names of the built-in scenes."""

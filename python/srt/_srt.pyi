"""Type stubs of srt._srt, the Rust extension behind the srt package (python/src)."""

from __future__ import annotations

import os
from typing import Literal, Sequence, overload

import numpy as np
import numpy.typing as npt

__version__: str

Vector = Sequence[float]
EffectsName = Literal["geometry", "doppler", "searchlight"]
ColourName = Literal["paper", "spectral"]
SettingValue = bool | int | float | str | Sequence["SettingValue"] | dict[str, "SettingValue"]
"""A scene file key's value in `set=`: as TOML holds it (a list is an array, a dict a table)."""

class SceneError(ValueError):
    """A scene or value srt refuses; the message is srt's own one line."""

class SceneFileError(OSError):
    """A scene, model, texture or star file that cannot be found, read or imported."""

class GpuError(RuntimeError):
    """No GPU adapter where one was asked for, or the GPU failed."""

def scenes() -> list[str]:
    """The built-in scenes' names."""

class Scene:
    """A scene description (what a scene file holds) that Python reads and edits."""

    @staticmethod
    def builtin(name: str) -> Scene:
        """The built-in scene ``name`` (see :func:`scenes`)."""
    @staticmethod
    def load(path: str | os.PathLike[str], *, beta: Vector | None = None) -> Scene:
        """A scene file (.toml) or model (.gltf, .glb, .obj, .ply, .stl); a bare model moves
        with ``beta`` or approaches the observer at 0.9c."""
    @staticmethod
    def from_toml(text: str) -> Scene:
        """A scene from scene-file text (docs/scene-format.md)."""
    def to_toml(self) -> str:
        """The description as scene-file text that :meth:`from_toml` reads back."""
    @property
    def name(self) -> str | None: ...
    effects: EffectsName
    colour: ColourName
    exposure: float
    time: float
    """The observation time: the observer's own clock when it looks (`observer.time`)."""
    @property
    def light(self) -> tuple[list[float], float] | None:
        """The lamp's position and temperature in kelvin."""
    @property
    def observer(self) -> Observer:
        """The observer (a view: setting its fields edits the scene)."""
    @property
    def objects(self) -> list[SceneObject]:
        """The objects (views: setting their fields edits the scene)."""

class Observer:
    """The observer of a :class:`Scene`; setting a field edits the scene (validated)."""

    position: Vector
    beta: Vector
    look_at: Vector | None
    direction: Vector | None
    up: Vector
    fov_y_deg: float
    ct: float
    """W's time at which the observer is at `position` (its clock reads `ct` there)."""

class SceneObject:
    """One object of a :class:`Scene`; setting a field edits the scene (validated)."""

    @property
    def name(self) -> str: ...
    beta: Vector
    offset: Vector

@overload
def render(
    scene: str | Scene,
    *,
    width: int = 1280,
    height: int = 720,
    time: float | None = None,
    beta: Vector | None = None,
    observer_beta: Vector | None = None,
    effects: EffectsName | None = None,
    colour: ColourName | None = None,
    exposure: float | None = None,
    projection: str | None = None,
    set: dict[str, SettingValue] | None = None,
    samples: int = 1,
    backend: Literal["auto", "cpu", "gpu"] = "auto",
    method: Literal["auto", "lrt", "rt", "polygon", "image-based"] = "auto",
    view: Literal["seen", "measured", "newtonian"] = "seen",
    aov: Literal[False] = False,
) -> npt.NDArray[np.float32]: ...
@overload
def render(
    scene: str | Scene,
    *,
    width: int = 1280,
    height: int = 720,
    time: float | None = None,
    beta: Vector | None = None,
    observer_beta: Vector | None = None,
    effects: EffectsName | None = None,
    colour: ColourName | None = None,
    exposure: float | None = None,
    projection: str | None = None,
    set: dict[str, SettingValue] | None = None,
    samples: int = 1,
    backend: Literal["auto", "cpu", "gpu"] = "auto",
    method: Literal["auto", "lrt", "rt", "polygon", "image-based"] = "auto",
    view: Literal["seen", "measured", "newtonian"] = "seen",
    aov: Literal[True],
) -> dict[str, npt.NDArray[np.float32] | npt.NDArray[np.int32]]:
    """With aov=True: "radiance" and "display" (height, width, 3), and the (height, width)
    channels "emission_ct", "proper_time", "distance", "doppler" (float32) and "object" (int32,
    -1: no object). `projection`: "perspective", "equirectangular", "fisheye" or
    "fisheye:FOV"."""
class Renderer:
    """A renderer kept for a loop of frames: the GPU device is made once and a scene uploaded
    again only when its structure changes. `render` takes `srt.render`'s per-frame arguments and
    returns what `srt.render` returns for them."""

    def __init__(
        self,
        *,
        width: int = 1280,
        height: int = 720,
        samples: int = 1,
        backend: Literal["auto", "cpu", "gpu"] = "auto",
        method: Literal["auto", "lrt", "rt", "polygon", "image-based"] = "auto",
    ) -> None: ...
    def render(
        self,
        scene: str | Scene,
        *,
        time: float | None = None,
        beta: Vector | None = None,
        observer_beta: Vector | None = None,
        effects: EffectsName | None = None,
        colour: ColourName | None = None,
        exposure: float | None = None,
        projection: str | None = None,
        set: dict[str, SettingValue] | None = None,
        view: Literal["seen", "measured", "newtonian"] = "seen",
        aov: bool = False,
    ) -> npt.NDArray[np.float32] | dict[str, npt.NDArray[np.float32] | npt.NDArray[np.int32]]: ...
    @property
    def devices_opened(self) -> int:
        """GPU devices opened: 1 after any number of GPU frames, 0 on the CPU."""
    @property
    def scene_uploads(self) -> int:
        """Scenes uploaded to the GPU: once, and again at each change of structure."""
    @property
    def adapter(self) -> dict[str, str] | None:
        """The last frame's GPU adapter: "name", "backend", "driver", "driver_info"; None on CPU."""

def to_srgb8(linear: npt.NDArray[np.float64]) -> npt.NDArray[np.uint8]: ...
def lorentz_boost(beta: Vector) -> npt.NDArray[np.float64]: ...
def apparent_positions(
    points: npt.NDArray[np.float64], beta: Vector, offset: Vector, observer: Vector, ct: float
) -> npt.NDArray[np.float64]: ...
def doppler_factors(beta: Vector, directions: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
def aberrate_directions(
    directions: npt.NDArray[np.float64], beta: Vector
) -> npt.NDArray[np.float64]: ...
def blackbody_colours(
    temperatures: npt.NDArray[np.float64], tone_map: str
) -> npt.NDArray[np.float64]: ...

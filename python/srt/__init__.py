"""srt: what an observer really sees of objects flying at near light speed.

Special-relativistic rendering of triangle meshes (aberration, light travel time, Doppler colour
shift and the searchlight effect, per pixel and exact), after Müller, Grottel and Weiskopf,
"Special Relativistic Visualization by Local Ray Tracing" (IEEE TVCG 2010), and the physics
behind it (:mod:`srt.physics`). Images are numpy arrays; docs/python.md is the guide.

>>> import srt
>>> img = srt.render("fig7", width=64, height=64, backend="cpu")
>>> img.shape
(64, 64, 3)
"""

from __future__ import annotations

import atexit as _atexit
import os as _os
import shutil as _shutil
import sys as _sys
import tempfile as _tempfile

import numpy as _np


def _ensure_runtime_dir() -> None:
    """Gives the process a private XDG_RUNTIME_DIR when it has no valid one, as the `srt`
    command does: Mesa's Vulkan device-selection layer connects to Wayland while listing GPU
    adapters, and libwayland prints "XDG_RUNTIME_DIR is invalid or not set" on every GPU render
    otherwise (bare containers, CI jobs, sudo). The folder is private (0700), empty, and removed
    when the interpreter exits; a valid variable is left alone."""
    if not _sys.platform.startswith("linux"):
        return
    current = _os.environ.get("XDG_RUNTIME_DIR", "")
    if _os.path.isabs(current) and _os.path.isdir(current):
        return
    folder = _tempfile.mkdtemp(prefix="srt-runtime-")
    _os.environ["XDG_RUNTIME_DIR"] = folder
    _atexit.register(_shutil.rmtree, folder, ignore_errors=True)


_ensure_runtime_dir()

from . import physics
from ._srt import (
    GpuError,
    Observer,
    Renderer,
    Scene,
    SceneError,
    SceneFileError,
    SceneObject,
    __version__,
    render,
    scenes,
)
from ._srt import to_srgb8 as _to_srgb8

__all__ = [
    "GpuError",
    "Observer",
    "Renderer",
    "Scene",
    "SceneError",
    "SceneFileError",
    "SceneObject",
    "__version__",
    "physics",
    "render",
    "scenes",
    "to_srgb8",
]


def to_srgb8(image: _np.typing.ArrayLike) -> _np.ndarray:
    """Linear light as an 8-bit sRGB image, as srt's PNGs are encoded.

    Each value is clamped to [0, 1], sRGB-encoded (IEC 61966-2-1) and rounded to 0..255; the
    array keeps its shape. ``srt.to_srgb8(srt.render(s, aov=True)["display"])`` is the image
    ``srt render`` writes to a PNG. Radiance (``srt.render``'s default output) is not tone
    mapped: values above 1 are clipped, so scale it (or use the display layer) first.
    """
    array = _np.asarray(image, dtype=_np.float64)
    return _to_srgb8(_np.ascontiguousarray(array.reshape(-1))).reshape(array.shape)

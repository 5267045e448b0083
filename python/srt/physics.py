"""Special relativity as srt computes it, vectorised over numpy arrays.

Units with c = 1; an event is (ct, x, y, z). S is the observer's frame; an object rests in its own
frame S' moving with velocity ``beta`` (|beta| < 1) relative to S, whose origin is at ``offset``
(the paper's **a**, Fig. 2) at t = t' = 0. Light directions are *propagation* directions (from
the emitter to the receiver). A Doppler factor D = omega_received / omega_emitted, so D > 1 is a
blue shift. Equation numbers are those of Müller, Grottel and Weiskopf (2010).

Every function runs the same f64 code the renderers use (the Rust crates srt-physics and
srt-color); a velocity with |beta| >= 1 or a non-finite component raises
:class:`srt.SceneError` (a ``ValueError``).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from . import _srt

__all__ = [
    "aberrate",
    "apparent_position",
    "blackbody_srgb",
    "doppler_factor",
    "lorentz_boost",
]

Vector = Sequence[float]


def _rows(vectors: np.typing.ArrayLike, name: str) -> tuple[np.ndarray, bool]:
    """``vectors`` as a C-contiguous float64 (N, 3) array, and whether it was one vector."""
    array = np.ascontiguousarray(vectors, dtype=np.float64)
    if array.shape == (3,):
        return array.reshape(1, 3), True
    if array.ndim != 2 or array.shape[1] != 3:
        raise _srt.SceneError(f"{name} must have shape (3,) or (N, 3), got {array.shape}")
    return array, False


def lorentz_boost(beta: Vector) -> np.ndarray:
    """The Lorentz matrix Lambda_beta of Eq. 2 as a 4x4 array acting on column vectors
    (ct, x, y, z).

    As in the paper's Eq. 1 (x = Lambda_beta x' + a), it takes an event's coordinates in the frame
    S' moving with ``beta`` relative to S to its coordinates in S (up to the offset a);
    ``lorentz_boost(-beta)`` is its inverse, from S to S'.
    """
    return _srt.lorentz_boost(beta)


def apparent_position(
    points: np.typing.ArrayLike,
    beta: Vector,
    offset: Vector,
    observer: Vector = (0.0, 0.0, 0.0),
    ct: float = 0.0,
) -> np.ndarray:
    """Where an observer sees points of a moving object (Eqs. 5-8, the paper's photo-object).

    ``points`` (shape (3,) or (N, 3)) rest in the frame S' moving with ``beta`` whose origin is at
    ``offset`` at t = t' = 0. The observer is at ``observer`` in S at time ``ct``. Each point is
    seen where it was when the light that reaches the observer now left it: the intersection of
    its worldline with the observer's backward light cone (Eq. 6), returned in S with the same
    shape as ``points``.
    """
    rows, single = _rows(points, "points")
    seen = _srt.apparent_positions(rows, beta, offset, observer, float(ct))
    return seen[0] if single else seen


def doppler_factor(beta: Vector, directions: np.typing.ArrayLike) -> np.ndarray | float:
    """Doppler factors D = 1 / (gamma (1 - beta . n)) of a source moving with ``beta`` (Eq. 4).

    ``directions`` (shape (3,) or (N, 3)) are the directions n in S in which the light
    propagates towards the observer (normalised here; non-zero and finite). A source approaching head-on at speed b
    gives sqrt((1 + b) / (1 - b)).
    """
    rows, single = _rows(directions, "directions")
    factors = _srt.doppler_factors(beta, rows)
    return float(factors[0]) if single else factors


def aberrate(directions: np.typing.ArrayLike, beta: Vector) -> np.ndarray:
    """Aberration (Eq. 4): the propagation directions in S of light that propagates along
    ``directions`` (shape (3,) or (N, 3), normalised here; non-zero and finite) in S', where S'
    moves with ``beta``.

    ``aberrate(aberrate(n, beta), -beta)`` gives ``n`` back.
    """
    rows, single = _rows(directions, "directions")
    seen = _srt.aberrate_directions(rows, beta)
    return seen[0] if single else seen


def blackbody_srgb(temperatures: np.typing.ArrayLike, tone_map: str = "luminance") -> np.ndarray:
    """The display colour of black bodies (sRGB-encoded, in [0, 1]), shape ``temperatures.shape
    + (3,)``.

    ``tone_map="luminance"`` scales every spectrum to the same luminance (Fig. 6 left, the colour
    of the Doppler effect); ``"searchlight"`` scales all by the luminance of a 1500 K black body
    and applies 0.6 log10(C + 1) (Fig. 6 right, the searchlight effect's: dark red at 1500 K,
    white above about 3600 K). Temperatures in kelvin, positive and finite.
    """
    array = np.asarray(temperatures, dtype=np.float64)
    colours = _srt.blackbody_colours(np.ascontiguousarray(array.reshape(-1)), tone_map)
    return colours.reshape(array.shape + (3,))

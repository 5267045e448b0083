"""srt.physics against independent formulas and the paper's numbers."""

from __future__ import annotations

import numpy as np
import pytest

import srt
from srt import physics

RNG = np.random.default_rng(7)


def gamma(beta):
    return 1.0 / np.sqrt(1.0 - np.dot(beta, beta))


def test_the_boost_is_eq_2():
    beta = np.array([0.3, -0.4, 0.5])
    g = gamma(beta)
    b2 = beta @ beta
    expected = np.eye(4)
    expected[0, 0] = g
    expected[0, 1:] = expected[1:, 0] = g * beta
    expected[1:, 1:] += (g - 1.0) * np.outer(beta, beta) / b2
    assert np.allclose(physics.lorentz_boost(beta), expected, atol=1e-14)
    assert np.allclose(physics.lorentz_boost(beta) @ physics.lorentz_boost(-beta), np.eye(4))
    # Eq. 1: a clock at rest at the origin of S' ticks slowly and moves with beta in S
    event = physics.lorentz_boost(beta) @ np.array([1.0, 0.0, 0.0, 0.0])
    assert np.allclose(event, g * np.array([1.0, *beta]))


def test_apparent_positions_lie_on_the_backward_light_cone():
    """Eq. 6: the seen point is where the worldline meets the observer's backward light cone."""
    beta = np.array([0.0, 0.95, 0.0])
    offset = np.array([-2.0, -5.0, -0.2])
    points = RNG.uniform(-0.5, 0.5, size=(50, 3))
    observer, ct = np.zeros(3), 5.12
    seen = physics.apparent_position(points, beta, offset, observer, ct)
    assert seen.shape == (50, 3)
    distance = np.linalg.norm(seen - observer, axis=1)
    emitted = ct - distance  # the emission time in S
    # where the frame's point is at time `emitted` (Lorentz-contracted along beta, Eqs. 7-8)
    b = beta / np.linalg.norm(beta)
    g = gamma(beta)
    contracted = points + (1.0 / g - 1.0) * np.outer(points @ b, b)
    expected = offset + contracted + np.outer(emitted, beta)
    assert np.allclose(seen, expected, atol=1e-9)
    single = physics.apparent_position(points[0], beta, offset, observer, ct)
    assert np.array_equal(single, seen[0])


def test_doppler_factors_match_the_head_on_formula():
    for b in (0.2, 0.5, 0.9, 0.99):
        d = physics.doppler_factor((0.0, 0.0, b), (0.0, 0.0, 1.0))
        assert d == pytest.approx(np.sqrt((1 + b) / (1 - b)), rel=1e-12)
        receding = physics.doppler_factor((0.0, 0.0, -b), (0.0, 0.0, 1.0))
        assert receding == pytest.approx(np.sqrt((1 - b) / (1 + b)), rel=1e-12)
    directions = RNG.normal(size=(20, 3))
    factors = physics.doppler_factor((0.1, 0.2, 0.3), directions)
    n = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    beta = np.array([0.1, 0.2, 0.3])
    assert np.allclose(factors, 1.0 / (gamma(beta) * (1.0 - n @ beta)), rtol=1e-12)


def test_aberration_is_undone_by_the_opposite_velocity():
    directions = RNG.normal(size=(30, 3))
    beta = (0.0, 0.6, 0.7)
    there = physics.aberrate(directions, beta)
    assert np.allclose(np.linalg.norm(there, axis=1), 1.0)
    back = physics.aberrate(there, tuple(-c for c in beta))
    n = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    assert np.allclose(back, n, atol=1e-12)
    # light crossing the motion at right angles in S' leans forward by arcsin(beta) in S
    forward = physics.aberrate((1.0, 0.0, 0.0), (0.0, 0.0, 0.8))
    assert forward[2] == pytest.approx(0.8, abs=1e-12)


def test_black_body_colours_are_the_papers_fig_6():
    temperatures = np.array([1500.0, 6500.0, 26000.0])
    luminance = physics.blackbody_srgb(temperatures, "luminance")
    assert luminance.shape == (3, 3)
    assert luminance[0, 0] > luminance[0, 2], "1500 K is red"
    assert np.allclose(luminance[1], luminance[1].mean(), atol=0.08), "6500 K is near white"
    assert luminance[2, 2] > luminance[2, 0], "26000 K is blue"
    searchlight = physics.blackbody_srgb(temperatures, "searchlight")
    red = searchlight[0]
    # the paper: 1500 K is dark red under the searchlight tone map
    assert red[0] > 1.5 * red[1] and red[0] < 0.4
    assert np.all(searchlight[1:] > 0.9), "above about 3600 K everything is white"
    grid = physics.blackbody_srgb(np.full((4, 5), 3000.0))
    assert grid.shape == (4, 5, 3)
    assert physics.blackbody_srgb(1500.0).shape == (3,)
    assert np.array_equal(physics.blackbody_srgb(1500.0), luminance[0])


@pytest.mark.parametrize(
    "call",
    [
        lambda: physics.lorentz_boost((0.0, 0.0, 1.0)),
        lambda: physics.doppler_factor((0.6, 0.6, 0.6), (1.0, 0.0, 0.0)),
        lambda: physics.aberrate((1.0, 0.0, 0.0), (float("nan"), 0.0, 0.0)),
        lambda: physics.apparent_position((0, 0, 0), (0, 0, 1.5), (0, 0, 0)),
    ],
)
def test_speeds_of_light_and_beyond_raise_value_errors(call):
    with pytest.raises(srt.SceneError, match="is not a valid velocity"):
        call()


def test_bad_shapes_and_temperatures_raise_value_errors():
    with pytest.raises(ValueError, match=r"shape \(3,\) or \(N, 3\)"):
        physics.aberrate(np.zeros((4, 2)), (0.0, 0.0, 0.5))
    with pytest.raises(ValueError, match=r"non-zero and finite, got \[0.0, 0.0, 0.0\] in row 1"):
        physics.doppler_factor((0.5, 0.0, 0.0), [(1.0, 0.0, 0.0), (0.0, 0.0, 0.0)])
    with pytest.raises(ValueError, match="non-zero and finite"):
        physics.aberrate((float("inf"), 0.0, 0.0), (0.5, 0.0, 0.0))
    with pytest.raises(ValueError, match="positive and finite"):
        physics.blackbody_srgb([1000.0, -5.0])
    with pytest.raises(ValueError, match="tone_map"):
        physics.blackbody_srgb([1000.0], tone_map="filmic")

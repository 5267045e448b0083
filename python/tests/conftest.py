"""Shared helpers of srt's Python tests: the `srt` command to compare with, EXR reading, and the
project's rule for tests that need a GPU (SKIPPED without one, a failure under SRT_REQUIRE_GPU)."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

REPOSITORY = Path(__file__).resolve().parents[2]

#: The per-pixel channels `srt render --aov` writes and `srt.render(aov=True)` returns.
AOV_CHANNELS = ("emission_ct", "proper_time", "distance", "doppler", "object")


def srt_command() -> str:
    """The `srt` binary: $SRT_BIN, else the repository's release or debug build, else PATH."""
    candidates = [os.environ.get("SRT_BIN")]
    candidates += [str(REPOSITORY / "target" / p / "srt") for p in ("release", "debug")]
    candidates.append(shutil.which("srt"))
    for candidate in candidates:
        if candidate and Path(candidate).is_file():
            return candidate
    raise AssertionError(
        "no srt command to compare with: build it (cargo build --release) or set SRT_BIN"
    )


def run_srt(*args: str) -> subprocess.CompletedProcess[str]:
    """Runs `srt ARGS`, failing the test with its output if it fails."""
    done = subprocess.run([srt_command(), *args], capture_output=True, text=True, check=False)
    assert done.returncode == 0, f"srt {' '.join(args)} failed:\n{done.stderr}"
    return done


def read_exr(path: Path) -> dict[str, np.ndarray]:
    """The channels of an EXR srt wrote, as float32 (height, width) arrays by name."""
    import OpenEXR  # the test extra

    with OpenEXR.File(str(path)) as exr:
        channels = exr.channels()
        return {name: np.asarray(channels[name].pixels, dtype=np.float32) for name in channels}


def cli_render(tmp_path: Path, scene: str, *args: str) -> dict[str, np.ndarray]:
    """`srt render SCENE ARGS -o x.exr` as (height, width, 3) arrays: "radiance" (R, G, B) and
    "display" (display.R, display.G, display.B); and the (height, width) AOV channels the EXR
    holds (with --aov)."""
    out = tmp_path / "cli.exr"
    run_srt("render", scene, *args, "-o", str(out))
    channels = read_exr(out)
    layers = {"radiance": rgb(channels, ""), "display": rgb(channels, "display.")}
    for name in AOV_CHANNELS:
        if name in channels:
            layers[name] = channels[name]
    return layers


def rgb(channels: dict[str, np.ndarray], prefix: str) -> np.ndarray:
    """The (height, width, 3) image of channels PREFIX R, G, B; OpenEXR's reader may group them
    into one channel named "PREFIXRGB" or, with a prefix, "PREFIX" without its dot."""
    for grouped in (f"{prefix}RGB", prefix.rstrip(".")):
        if grouped in channels and channels[grouped].ndim == 3:
            return channels[grouped]
    return np.stack([channels[f"{prefix}{c}"] for c in "RGB"], axis=-1)


def require_gpu(reason: str) -> None:
    """Skips visibly (SKIPPED …) when `reason` says no GPU is there, or fails when CI requires
    one (SRT_REQUIRE_GPU=1), as every GPU test of the project does."""
    if os.environ.get("SRT_REQUIRE_GPU") == "1":
        pytest.fail(f"SRT_REQUIRE_GPU=1 but {reason}")
    skip_visibly(reason)


def skip_visibly(reason: str) -> None:
    """Skips the test, saying so on its output (SKIPPED: `reason`) as well as in pytest's
    summary: a test that cannot tell right from wrong here says why instead of passing."""
    print(f"SKIPPED: {reason}")
    pytest.skip(reason)

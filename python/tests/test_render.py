"""srt.render against the `srt` command: the same arguments give the EXR's pixels to the bit."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest
from conftest import AOV_CHANNELS, cli_render, require_gpu, run_srt, skip_visibly

import srt

SMALL = {"width": 96, "height": 54}


def test_the_readme_example_has_the_shape_it_says():
    img = srt.render("fig7", width=64, height=64, backend="cpu")
    assert img.shape == (64, 64, 3)
    assert img.dtype == np.float32
    assert np.isfinite(img).all()
    assert img.max() > 0.0, "the lit cube is in the picture"


@pytest.mark.parametrize(
    ("scene", "arguments", "cli"),
    [
        ("fig7", {}, []),
        ("teaser", {"effects": "searchlight"}, ["--effects", "searchlight"]),
        ("fig4", {"time": 5.66, "samples": 4}, ["--time", "5.66", "--samples", "4"]),
        ("fig7", {"beta": (0.0, 0.5, 0.0), "colour": "spectral", "exposure": 2.0},
         ["--beta", "0,0.5,0", "--colour", "spectral", "--exposure", "2"]),
        ("flythrough", {"observer_beta": (0.6, 0.0, 0.0)}, ["--observer-beta", "0.6,0,0"]),
        ("fig10-cube50", {"view": "measured"}, ["--view", "measured"]),
    ],
)
def test_cpu_render_equals_the_commands_exr_to_the_bit(tmp_path, scene, arguments, cli):
    size = ["--width", str(SMALL["width"]), "--height", str(SMALL["height"])]
    expected = cli_render(tmp_path, scene, *size, "--backend", "cpu", "--aov", *cli)
    layers = srt.render(scene, **SMALL, backend="cpu", aov=True, **arguments)
    assert sorted(layers) == sorted(["radiance", "display", *AOV_CHANNELS])
    for name in ("radiance", "display", *AOV_CHANNELS):
        assert layers[name].dtype == (np.int32 if name == "object" else np.float32), name
        assert layers[name].shape == expected[name].shape
        assert np.array_equal(layers[name], expected[name]), f"{scene} {arguments}: {name}"
    plain = srt.render(scene, **SMALL, backend="cpu", **arguments)
    assert np.array_equal(plain, expected["radiance"])


def test_the_time_channels_say_what_each_pixel_sees():
    layers = srt.render("fig4", **SMALL, backend="cpu", aov=True)
    seen = layers["object"] >= 0
    assert 0 < seen.sum() < seen.size, "the cube and the background are both in the picture"
    # Fig. 4 is observed at ct = 5.12; light arrives after travelling `distance`.
    assert np.allclose(layers["emission_ct"][seen], 5.12 - layers["distance"][seen], atol=1e-5)
    assert (layers["doppler"][seen] > 1.0).all(), "the cube approaches: every pixel is blue-shifted"
    for name in ("emission_ct", "proper_time", "distance", "doppler"):
        assert (layers[name][~seen] == 0.0).all(), name
    assert (layers["object"][~seen] == -1).all()
    assert layers["object"].dtype == np.int32, "object indices are integers"


@pytest.mark.parametrize(("speed", "start"), [(0.9, 30.0), (-0.9, 3.0)])
def test_a_clock_on_the_axis_is_seen_running_at_the_doppler_rate(speed, start):
    """The centre of a face moving along the line of sight stays in the centre pixel; its
    proper time, seen there, advances D times as fast as the observer's time (D = 4.36
    approaching at 0.9c, 1/4.36 receding)."""
    scene = srt.Scene.from_toml(
        "[observer]\nposition = [0.0, 0.0, 0.0]\ndirection = [0.0, 1.0, 0.0]\n"
        "[[object]]\nshape = { type = 'cube', size = 2.0 }\n"
    )
    scene.objects[0].beta = (0.0, -speed, 0.0)
    scene.objects[0].offset = (0.0, start, 0.0)
    before, after = (
        srt.render(scene, width=33, height=33, backend="cpu", time=t, aov=True) for t in (0.0, 0.5)
    )
    assert before["object"][16, 16] == 0 and after["object"][16, 16] == 0
    rate = (after["proper_time"][16, 16] - before["proper_time"][16, 16]) / 0.5
    expected = np.sqrt((1 + speed) / (1 - speed))
    assert rate == pytest.approx(expected, rel=1e-5)
    assert before["doppler"][16, 16] == pytest.approx(expected, rel=1e-6)


def test_the_searchlight_radiance_goes_beyond_a_white_surfaces(tmp_path):
    layers = srt.render("teaser", **SMALL, backend="cpu", effects="searchlight", aov=True)
    assert layers["radiance"].max() > 1.0, "the searchlight brightens beyond a white surface"
    assert layers["display"].max() <= 1.0


def test_the_display_layer_encodes_to_the_commands_png(tmp_path):
    from PIL import Image

    png = tmp_path / "cli.png"
    size = ["--width", str(SMALL["width"]), "--height", str(SMALL["height"])]
    run_srt("render", "fig7", *size, "--backend", "cpu", "-o", str(png))
    display = srt.render("fig7", **SMALL, backend="cpu", aov=True)["display"]
    ours = srt.to_srgb8(display)
    theirs = np.asarray(Image.open(png).convert("RGB"))
    assert ours.dtype == np.uint8 and ours.shape == theirs.shape
    # The PNG quantises the display colour itself; ours goes through its f32 linear light and
    # back, which can round a value sitting on a step's edge the other way.
    difference = np.abs(ours.astype(int) - theirs.astype(int))
    assert difference.max() <= 1
    assert (difference > 0).mean() < 0.001


def test_to_srgb8_keeps_the_shape_scalars_included():
    assert srt.to_srgb8(0.5).shape == ()
    assert int(srt.to_srgb8(0.5)) == 188  # sRGB encoding of linear 0.5
    assert srt.to_srgb8([[0.0, 1.0, 2.0]]).tolist() == [[0, 255, 255]]


def test_path_objects_name_files(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(srt.Scene.builtin("fig7").to_toml())
    assert np.array_equal(
        srt.render(path, **SMALL, backend="cpu"), srt.render(str(path), **SMALL, backend="cpu")
    )
    messages = []
    for absent in (tmp_path / "absent.toml", str(tmp_path / "absent.toml")):
        with pytest.raises(srt.SceneFileError, match="cannot open .*absent.toml: no such file") as e:
            srt.render(absent, **SMALL, backend="cpu")
        messages.append(str(e.value))
    assert messages[0] == messages[1], "a Path and a str name a missing file alike"


def test_a_scene_object_renders_as_its_name_does():
    by_name = srt.render("fig4", **SMALL, backend="cpu")
    by_scene = srt.render(srt.Scene.builtin("fig4"), **SMALL, backend="cpu")
    assert np.array_equal(by_name, by_scene)


def test_an_edited_scene_renders_as_the_override_does():
    scene = srt.Scene.builtin("fig4")
    scene.time = 4.4
    edited = srt.render(scene, **SMALL, backend="cpu")
    overridden = srt.render("fig4", **SMALL, backend="cpu", time=4.4)
    assert np.array_equal(edited, overridden)
    assert not np.array_equal(edited, srt.render("fig4", **SMALL, backend="cpu"))


# validate's rule (xtask/src/validate.rs): pixels within EDGE_MARGIN pixels of a silhouette of
# the CPU's picture are not compared, and at most MAX_MISMATCH of the others may differ: by more
# than 2/255 in a channel of the 8-bit display colours; by more than 2 % of the pixel's largest
# radiance channel (or of 0.01 where that is smaller); in what the pixel sees of time, by its
# object or by more than 1e-3 of a channel's magnitude (at least 1).
EDGE_MARGIN = 1
MAX_MISMATCH = 0.001
DISPLAY_TOLERANCE = 2
RADIANCE_TOLERANCE, RADIANCE_FLOOR = 0.02, 0.01
SEEN_TOLERANCE = 1e-3


def off_silhouettes(objects: np.ndarray, margin: int = EDGE_MARGIN) -> np.ndarray:
    """The pixels of the (height, width) object indices `objects` that no pixel within `margin`
    (Chebyshev distance, within the picture) sees another object in: those validate compares
    (srt_trace::compare::near_silhouette)."""
    height, width = objects.shape
    padded = np.pad(objects, margin, mode="edge")
    near = np.zeros(objects.shape, dtype=bool)
    for dy in range(2 * margin + 1):
        for dx in range(2 * margin + 1):
            near |= padded[dy : dy + height, dx : dx + width] != objects
    return ~near


def mismatch(differs: np.ndarray, compared: np.ndarray) -> float:
    """The fraction of the `compared` pixels that differ."""
    return float(differs[compared].mean())


def test_off_silhouettes_leaves_out_the_pixels_beside_an_edge():
    objects = np.full((5, 6), -1)
    objects[1:3, 1:3] = 0
    expected = np.ones((5, 6), dtype=bool)
    expected[0:4, 0:4] = False
    assert (off_silhouettes(objects) == expected).all()
    assert mismatch(np.eye(5, 6, dtype=bool), expected) == pytest.approx(1 / 14)


def test_the_gpu_draws_the_display_the_radiance_and_the_time_near_the_cpu():
    try:
        gpu = srt.render("fig7", **SMALL, backend="gpu", aov=True)
    except srt.GpuError as error:
        require_gpu(f"no GPU adapter for srt.render(backend='gpu'): {error}")
    cpu = srt.render("fig7", **SMALL, backend="cpu", aov=True)
    compared = off_silhouettes(cpu["object"])
    assert compared.mean() > 0.5 and (cpu["object"][compared] >= 0).any()
    # The GPU draws the radiance too, not the CPU's own bits.
    assert not np.array_equal(gpu["radiance"], cpu["radiance"])
    scale = np.maximum(np.abs(cpu["radiance"]).max(axis=-1), RADIANCE_FLOOR)
    relative = np.abs(gpu["radiance"] - cpu["radiance"]).max(axis=-1) / scale
    assert mismatch(relative > RADIANCE_TOLERANCE, compared) <= MAX_MISMATCH, "radiance"
    steps = np.abs(srt.to_srgb8(gpu["display"]).astype(int) - srt.to_srgb8(cpu["display"]))
    assert mismatch(steps.max(axis=-1) > DISPLAY_TOLERANCE, compared) <= MAX_MISMATCH, "display"
    # The time channels (the CPU computes them where the GPU's colour target holds half floats).
    differs = gpu["object"] != cpu["object"]
    for name in ("emission_ct", "proper_time", "distance", "doppler"):
        relative = np.abs(gpu[name] - cpu[name]) / np.maximum(np.abs(cpu[name]), 1.0)
        differs |= relative > SEEN_TOLERANCE
    assert mismatch(differs, compared) <= MAX_MISMATCH, "what the pixels see of time"


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        ({"beta": (0.0, 0.0, 1.0)}, "beta 0.0,0.0,1.0 is not a valid velocity"),
        ({"beta": (float("nan"), 0.0, 0.0)}, "beta NaN,0.0,0.0 is not a valid velocity"),
        ({"time": float("inf")}, "time must be a finite number"),
        ({"exposure": 2.0}, "exposure"),
        ({"effects": "glow"}, 'unknown effect mode "glow"; expected "geometry", "doppler" or "searchlight"'),
        ({"colour": "sepia"}, 'unknown surface colour "sepia"; expected "paper" or "spectral"'),
        ({"width": 0}, "width must be 1 to 16384 pixels, got 0"),
        ({"samples": 5000}, "samples must be 1 to 1024, got 5000"),
        ({"backend": "tpu"}, 'unknown backend "tpu"; expected "auto", "cpu" or "gpu"'),
        ({"method": "polygon", "backend": "cpu"}, "the polygon method runs on the GPU only"),
        ({"method": "image-based", "backend": "cpu"}, "the image-based method runs on the GPU only"),
        (
            {"set": {"observer.stereo": {"eye_separation": 0.065}}, "width": 15},
            "fig7: a stereo picture's width is split between the eyes and must be even, got 15x",
        ),
        ({"view": "sideways"}, 'unknown view "sideways"; expected "seen", "measured" or "newtonian"'),
    ],
)
def test_bad_arguments_raise_value_errors_with_srts_message(arguments, message):
    with pytest.raises(srt.SceneError, match=None) as raised:
        srt.render("fig7", **{**SMALL, "backend": "cpu", **arguments})
    assert isinstance(raised.value, ValueError)
    assert message in str(raised.value), str(raised.value)
    assert "\n" not in str(raised.value)


def test_unknown_scenes_and_missing_files_raise_os_errors(tmp_path):
    with pytest.raises(srt.SceneFileError) as raised:
        srt.render(str(tmp_path / "nowhere.glb"), **SMALL, backend="cpu")
    assert isinstance(raised.value, OSError)
    assert "nowhere.glb" in str(raised.value)
    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(srt.SceneFileError) as raised:
        srt.render(str(broken), **SMALL, backend="cpu")
    assert "broken.obj" in str(raised.value)
    with pytest.raises(srt.SceneError, match="must end in .toml"):
        notes = tmp_path / "notes.txt"
        notes.write_text("hello")
        srt.render(str(notes), **SMALL, backend="cpu")


def test_the_gil_is_released_while_rendering():
    """Another Python thread runs while srt.render is rendering. The switch interval is made so
    long that the interpreter never takes the GIL from the main thread itself: the other thread
    runs only where the main thread gives the GIL up, so a step it takes while `rendering` is
    set was taken inside srt.render, however fast or slow the machine."""
    steps = {"rendering": 0, "else": 0}
    rendering = False
    done = threading.Event()

    def count():
        while not done.is_set():
            steps["rendering" if rendering else "else"] += 1
            time.sleep(0.001)  # gives the GIL up

    # A scene already built: srt.render loads no scene file (which it also does without the GIL).
    teaser = srt.Scene.builtin("teaser")
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    counter = threading.Thread(target=count)
    try:
        counter.start()
        rendering = True
        srt.render(teaser, width=480, height=270, backend="cpu")
        rendering = False
    finally:
        done.set()
        counter.join()
        sys.setswitchinterval(interval)
    assert steps["rendering"] >= 1, f"no other Python thread ran while srt rendered: {steps}"


# The Ctrl-C test's render: far more than any machine can finish within the test's bound (1024
# samples of every pixel of 16384 × 16384: 2.7e11 samples, about a day on two cores of 2026),
# stopped within the rows already begun (16384 × 1024 samples each).
ENDLESS = {"width": 16384, "height": 16384, "samples": 1024}
# How long the interrupted render may take in all, start-up included: generous, as a render
# that finished would take far longer.
STOP_BOUND_SECONDS = 600


def test_ctrl_c_stops_a_long_render():
    # Python's own Ctrl-C handler, even where this process was started with SIGINT ignored (a
    # job a non-interactive shell ran in the background inherits that, and Python keeps it).
    # SIGINT is sent once the render has started: by a thread that runs only where the main
    # thread gives the GIL up (the switch interval made too long for the interpreter to take
    # it), which it does inside srt.render.
    script = f"""
import os, signal, sys, threading, time, srt
signal.signal(signal.SIGINT, signal.default_int_handler)
teaser = srt.Scene.builtin("teaser")
sys.setswitchinterval(1000.0)
rendering = False

def interrupt():
    while not rendering:
        time.sleep(0.001)
    os.kill(os.getpid(), signal.SIGINT)

threading.Thread(target=interrupt, daemon=True).start()
try:
    rendering = True
    srt.render(teaser, **{ENDLESS!r}, backend="cpu")
    print("finished")
except KeyboardInterrupt:
    print("interrupted")
"""
    try:
        done = subprocess.run(
            [sys.executable, "-c", script], capture_output=True, text=True,
            timeout=STOP_BOUND_SECONDS, check=False,
        )
    except subprocess.TimeoutExpired as expired:
        pytest.fail(f"Ctrl-C did not stop the render within {STOP_BOUND_SECONDS} s: {expired}")
    assert done.returncode == 0, done.stderr
    assert done.stdout == "interrupted\n", done.stdout + done.stderr


# Prints what `import srt` made of XDG_RUNTIME_DIR: the folder, its permissions and its entries.
RUNTIME_DIR_SCRIPT = """
import os, stat, srt
folder = os.environ.get("XDG_RUNTIME_DIR", "")
print(folder)
print(oct(stat.S_IMODE(os.stat(folder).st_mode)) if os.path.isdir(folder) else "no folder")
print(sorted(os.listdir(folder)) if os.path.isdir(folder) else "no entries")
"""


def run_python(script: str, runtime_dir: str | None) -> subprocess.CompletedProcess[str]:
    """`python -c SCRIPT` with XDG_RUNTIME_DIR set to `runtime_dir` (absent for None); it must
    succeed."""
    environment = {k: v for k, v in os.environ.items() if k != "XDG_RUNTIME_DIR"}
    if runtime_dir is not None:
        environment["XDG_RUNTIME_DIR"] = runtime_dir
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, env=environment,
        timeout=300, check=False,
    )
    assert done.returncode == 0, done.stderr
    return done


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="srt sets it on Linux only")
@pytest.mark.parametrize("given", [None, "", "relative/run", "/nonexistent/srt-run"])
def test_import_gives_a_private_runtime_dir_where_there_is_no_valid_one(given):
    """Without a valid XDG_RUNTIME_DIR (absent, empty, relative, not a folder), `import srt`
    sets it to a new private folder (0700, empty, named srt-runtime-…), removed when the
    interpreter exits, as the `srt` command does."""
    folder, mode, entries = run_python(RUNTIME_DIR_SCRIPT, given).stdout.splitlines()
    assert os.path.isabs(folder) and os.path.basename(folder).startswith("srt-runtime-"), folder
    assert folder != given
    assert (mode, entries) == ("0o700", "[]")
    assert not os.path.exists(folder), "the private folder is removed at exit"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="srt sets it on Linux only")
def test_import_leaves_a_valid_runtime_dir_alone(tmp_path):
    (tmp_path / "socket").write_text("")
    folder, _, entries = run_python(RUNTIME_DIR_SCRIPT, str(tmp_path)).stdout.splitlines()
    assert (folder, entries) == (str(tmp_path), "['socket']")
    assert (tmp_path / "socket").exists(), "the folder and what is in it are kept"


def test_no_runtime_dir_warning_without_xdg_runtime_dir():
    """Mesa's Vulkan layer makes libwayland complain on every GPU render without a valid
    XDG_RUNTIME_DIR; srt gives the process a private one, as the command does: a GPU render
    runs with it and says nothing of it. Only Mesa's Vulkan driver prints the warning: on any
    other adapter (wgpu's GL backend, another vendor's driver) the test cannot tell the fix from
    its absence, so it skips visibly there, as its twin in tests/cli.rs does."""
    script = """
import json, os, srt
renderer = srt.Renderer(width=16, height=16, backend="gpu")
try:
    renderer.render("fig7", aov=True)
    print(json.dumps({"adapter": renderer.adapter, "folder": os.environ.get("XDG_RUNTIME_DIR")}))
except srt.GpuError as error:
    print(json.dumps({"no_gpu": str(error)}))
"""
    done = run_python(script, None)
    result = json.loads(done.stdout.splitlines()[-1])
    if "no_gpu" in result:
        require_gpu(f"no GPU adapter for srt.Renderer(backend='gpu'): {result['no_gpu']}")
    adapter = result["adapter"]
    if adapter["backend"] != "vulkan" or "Mesa" not in adapter["driver_info"]:
        skip_visibly(
            f"the render ran on {adapter['name']} ({adapter['backend']}, {adapter['driver_info']}),"
            " not Mesa's Vulkan driver, which alone prints the warning (WGPU_BACKEND=vulkan"
            " with lavapipe runs this test)"
        )
    assert os.path.basename(result["folder"] or "").startswith("srt-runtime-"), result
    assert "XDG_RUNTIME_DIR" not in done.stderr, done.stderr


def test_projection_draws_the_whole_sky_as_the_command_does(tmp_path):
    size = {"width": 64, "height": 32}
    expected = cli_render(
        tmp_path, "flythrough", "--width", "64", "--height", "32", "--backend", "cpu",
        "--projection", "equirectangular",
    )
    whole_sky = srt.render("flythrough", **size, backend="cpu", projection="equirectangular")
    assert np.array_equal(whole_sky, expected["radiance"])
    assert not np.array_equal(whole_sky, srt.render("flythrough", **size, backend="cpu"))
    with pytest.raises(srt.SceneError, match=r"fisheye's fov_deg must be in \(0, 360\]"):
        srt.render("fig7", width=8, height=8, backend="cpu", projection="fisheye:0")


def test_the_image_based_method_draws_as_the_command_does(tmp_path):
    # The paper's image-based comparison, its cube map's side set by `set` as the command's
    # --cube-map-size sets it: the same picture to the bit, and another at another side.
    size = {"width": 64, "height": 36}
    arguments = {**size, "backend": "gpu", "method": "image-based"}
    try:
        image = srt.render("teaser", **arguments, set={"render.cube_map_size": 128})
    except srt.GpuError as error:
        require_gpu(f"no GPU adapter for the image-based method: {error}")
    expected = cli_render(
        tmp_path, "teaser", "--width", "64", "--height", "36", "--backend", "gpu",
        "--method", "image-based", "--cube-map-size", "128",
    )
    assert np.array_equal(image, expected["radiance"])
    finer = srt.render("teaser", **arguments, set={"render.cube_map_size": 1024})
    assert not np.array_equal(image, finer)


def test_set_gives_scene_keys_as_the_commands_set_does(tmp_path):
    size = ["--width", str(SMALL["width"]), "--height", str(SMALL["height"])]
    expected = cli_render(
        tmp_path, "fig4", *size, "--backend", "cpu",
        "--set", "observer.fov_y_deg=60", "--set", "object.cube.beta=0,0.5,0",
        "--set", "render.colour=spectral",
    )
    image = srt.render(
        "fig4", **SMALL, backend="cpu",
        set={"observer.fov_y_deg": 60, "object.cube.beta": [0, 0.5, 0], "render.colour": "spectral"},
    )
    assert np.array_equal(image, expected["radiance"])
    with pytest.raises(srt.SceneError, match=r"set observer\.fov=60 does not fit the scene file"):
        srt.render("fig4", **SMALL, backend="cpu", set={"observer.fov": 60})
    with pytest.raises(srt.SceneError, match=r"observer\.fov_y_deg must be in \(0, 180\)"):
        srt.render("fig4", **SMALL, backend="cpu", set={"observer.fov_y_deg": 200.0})


def frames_of(renderer, scenes):
    """Each (scene, time) of `scenes` rendered by `renderer`, in order."""
    return [renderer.render(scene, time=t) for scene, t in scenes]


# A loop of frames, each (scene, time; None: the scene's own), and the (devices opened, scenes
# uploaded) a kept GPU renderer has made after each: one device; fig7 uploaded once for its three
# times; fig4, another scene of the same structure (the same cube and texture: its velocity,
# lamp, observer and effects are written with the frame), no upload; fig10-cube50, another mesh
# and texture, an upload; and fig7 again another.
LOOP = [
    ("fig7", 4.0), ("fig7", 4.5), ("fig7", 5.0), ("fig4", 5.12), ("fig10-cube50", None),
    ("fig7", 4.5),
]
LOOP_MADE = [(1, 1), (1, 1), (1, 1), (1, 1), (1, 2), (1, 3)]


def made_by(renderer):
    """What `renderer` has made so far, as srt counts it: (devices opened, scenes uploaded)."""
    return (renderer.devices_opened, renderer.scene_uploads)


def test_a_renderer_gives_each_frame_as_render_does():
    renderer = srt.Renderer(**SMALL, backend="cpu")
    assert repr(renderer) == "Renderer(width=96, height=54, samples=1)"
    for (scene, t), frame in zip(LOOP, frames_of(renderer, LOOP)):
        assert np.array_equal(frame, srt.render(scene, **SMALL, backend="cpu", time=t)), (scene, t)
    assert made_by(renderer) == (0, 0), "the CPU opens no device and uploads nothing"
    assert renderer.adapter is None


def test_a_gpu_renderer_keeps_its_engine_and_gives_each_frame_as_render_does():
    # srt counts where it opens a device and where it uploads a scene: LOOP_MADE.
    try:
        renderer = srt.Renderer(**SMALL, backend="gpu")
        assert made_by(renderer) == (0, 0) and renderer.adapter is None
        frames, made = [], []
        for scene, t in LOOP:
            frames.append(renderer.render(scene, time=t))
            made.append(made_by(renderer))
    except srt.GpuError as error:
        require_gpu(f"no GPU adapter for srt.Renderer(backend='gpu'): {error}")
    assert made == LOOP_MADE, list(zip(LOOP, made))
    assert set(renderer.adapter) == {"name", "backend", "driver", "driver_info"}
    for (scene, t), frame in zip(LOOP, frames):
        alone = srt.render(scene, **SMALL, backend="gpu", time=t)
        assert np.array_equal(frame, alone), (scene, t)
    assert not np.array_equal(frames[0], frames[2]), "time moves the cube"


def test_an_auto_renderer_follows_what_the_gpu_can_draw():
    """A projection the local ray tracer does not draw goes to the CPU within the loop, and the
    next frame back to where auto draws the perspective picture: each frame is what srt.render
    gives on the engine the renderer says it used. Where auto takes the GPU for the perspective
    frames depends on the machine (on a software adapter it weighs the CPU's measured cost,
    src/software.rs), so the test reads where each frame went instead of assuming it."""
    renderer = srt.Renderer(**SMALL, method="lrt")
    drawn_on = []
    for arguments in ({}, {"projection": "equirectangular"}, {}):
        frame = renderer.render("fig7", **arguments)
        backend = "cpu" if renderer.adapter is None else "gpu"
        drawn_on.append(backend)
        alone = srt.render("fig7", **SMALL, method="lrt", backend=backend, **arguments)
        assert np.array_equal(frame, alone), (arguments, backend)
    assert drawn_on[1] == "cpu", drawn_on
    assert drawn_on[0] == drawn_on[2], drawn_on
    print(f"the three frames drawn on {drawn_on}")


def test_a_kept_gpu_renderer_draws_the_whole_sky_as_render_does():
    # The ray tracer traces the wide projections: a kept GPU renderer (method auto) moves between
    # the pinhole and the full sphere, each frame what srt.render gives on the GPU. (Which
    # backend `auto` takes is the machine's: on a software adapter it may weigh the CPU faster.)
    try:
        renderer = srt.Renderer(**SMALL, backend="gpu")
        frames = [
            (arguments, renderer.render("fig7", **arguments))
            for arguments in ({}, {"projection": "equirectangular"}, {})
        ]
    except srt.GpuError as error:
        require_gpu(f"no GPU adapter for srt.Renderer(backend='gpu'): {error}")
    for arguments, frame in frames:
        alone = srt.render("fig7", **SMALL, backend="gpu", **arguments)
        assert np.array_equal(frame, alone), arguments
    assert not np.array_equal(frames[0][1], frames[1][1]), "the full sphere is another picture"

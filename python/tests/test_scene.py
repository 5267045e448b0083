"""srt.Scene: built-in scenes, files and text, edited with the scene file's validation."""

from __future__ import annotations

import pytest

import srt


def test_scenes_lists_the_built_in_scenes():
    names = srt.scenes()
    assert "fig4" in names and "teaser" in names
    for name in names:
        assert srt.Scene.builtin(name).name == name


def test_fields_read_as_the_scene_file_gives_them():
    scene = srt.Scene.builtin("fig4")
    # Fig. 4: a unit cube at beta = (0, 0.95, 0) seen from (2, 5, 0.2) at ct = 5.12.
    assert scene.time == 5.12
    assert list(scene.observer.position) == [2.0, 5.0, 0.2]
    assert scene.observer.fov_y_deg == 35.0
    assert list(scene.objects[0].beta) == [0.0, 0.95, 0.0]
    assert scene.effects in ("geometry", "doppler", "searchlight")
    assert scene.colour == "paper"


def test_edits_are_kept_and_written_to_toml():
    scene = srt.Scene.builtin("fig7")
    scene.effects = "searchlight"
    scene.objects[0].beta = (0.0, 0.5, 0.0)
    scene.objects[0].offset = (1.0, 2.0, 3.0)
    scene.observer.fov_y_deg = 50.0
    scene.observer.direction = (0.0, -1.0, 0.0)
    assert scene.observer.look_at is None
    again = srt.Scene.from_toml(scene.to_toml())
    assert again.effects == "searchlight"
    assert list(again.objects[0].beta) == [0.0, 0.5, 0.0]
    assert list(again.objects[0].offset) == [1.0, 2.0, 3.0]
    assert again.observer.fov_y_deg == 50.0
    assert again.to_toml() == scene.to_toml()


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            lambda s: setattr(s.objects[0], "beta", (0.0, 1.0, 0.0)),
            'object "cube" has an invalid velocity or offset: speed |β| = 1 is not below',
        ),
        (lambda s: setattr(s.observer, "beta", (0.0, float("nan"), 0.0)), "observer.beta"),
        (lambda s: setattr(s.observer, "fov_y_deg", 200.0), "observer.fov_y_deg"),
        (lambda s: setattr(s, "time", float("inf")), "observer.time"),
        (lambda s: setattr(s, "effects", "glow"), 'unknown effect mode "glow"'),
        (lambda s: setattr(s, "colour", "sepia"), 'unknown surface colour "sepia"'),
    ],
)
def test_invalid_edits_raise_and_leave_the_scene_as_it_was(edit, message):
    scene = srt.Scene.builtin("fig7")
    before = scene.to_toml()
    with pytest.raises(srt.SceneError) as raised:
        edit(scene)
    assert message in str(raised.value), str(raised.value)
    assert scene.to_toml() == before


def test_scene_text_errors_name_the_line():
    with pytest.raises(srt.SceneError, match=r"scene text: line 2, column 1: unknown field `colr`"):
        srt.Scene.from_toml("[render]\ncolr = 1\n")


def test_scene_files_and_models_load(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(srt.Scene.builtin("fig7").to_toml())
    assert srt.Scene.load(path).to_toml() == srt.Scene.builtin("fig7").to_toml()
    model = tmp_path / "triangle.obj"
    model.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    scene = srt.Scene.load(model, beta=(0.0, 0.0, 0.5))
    assert list(scene.objects[0].beta) == [0.0, 0.0, 0.5]


def test_missing_and_broken_files_raise_os_errors_naming_them(tmp_path):
    with pytest.raises(srt.SceneFileError, match="cannot open .*absent.toml: no such file"):
        srt.Scene.load(tmp_path / "absent.toml")
    broken = tmp_path / "broken.glb"
    broken.write_bytes(b"not a glb")
    with pytest.raises(srt.SceneFileError, match="broken.glb") as raised:
        srt.Scene.load(broken)
    assert isinstance(raised.value, OSError)
    with pytest.raises(srt.SceneError, match="not a built-in scene"):
        srt.Scene.builtin("fig99")

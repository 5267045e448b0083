//! The one resolver of scene arguments: built-in names first, then paths by extension, with the
//! same messages for `srt render` and `srt view`.

use std::path::{Path, PathBuf};

use glam::DVec3;
use srt_scene::placement::approach_velocity;
use srt_scene::resolve::{DEFAULT_MODEL_SPEED, SceneSource};
use srt_scene::{ResolveError, ShapeDescription};

/// One triangle as an ASCII STL file.
const TRIANGLE_STL: &str = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
                            vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn argument(path: &Path) -> String {
    path.display().to_string()
}

#[test]
fn a_builtin_name_resolves_to_the_builtin_scene_and_loads() {
    let source = SceneSource::resolve("fig7").unwrap();
    assert!(matches!(source, SceneSource::Builtin(b) if b.name == "fig7"));
    let loaded = source.load(None).unwrap();
    assert_eq!(loaded.scene.name, "fig7");
    assert_eq!(loaded.source.base_dir, Path::new("."));
    assert_eq!(
        loaded.scene.objects.len(),
        loaded.source.description.objects.len()
    );
}

#[test]
fn a_picked_file_is_never_taken_for_a_builtin_name() {
    assert!(matches!(
        SceneSource::from_path(Path::new("teaser")),
        Err(ResolveError::Unsupported(_))
    ));
}

#[test]
fn a_bare_model_approaches_at_the_default_speed_unless_given_a_velocity() {
    let dir = tempfile::tempdir().unwrap();
    let model = write(dir.path(), "tri.STL", TRIANGLE_STL);
    let source = SceneSource::resolve(&argument(&model)).unwrap();
    assert_eq!(source, SceneSource::Model(model.clone()));

    let loaded = source.load(None).unwrap();
    let beta = loaded.scene.objects[0].frame.beta();
    assert!((beta - approach_velocity(DEFAULT_MODEL_SPEED)).length() < 1e-12);
    assert_eq!(loaded.scene.name, "tri");

    let given = DVec3::new(0.5, 0.0, 0.0);
    let loaded = source.load(Some(given)).unwrap();
    assert_eq!(loaded.scene.objects[0].frame.beta(), given);
}

#[test]
fn a_scene_file_is_described_without_reading_its_models() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "ship.toml",
        "[observer]\nposition = [0, -5, 0]\nlook_at = [0, 0, 0]\n\
         [[object]]\nshape = { type = \"model\", path = \"missing.glb\" }\n",
    );
    let source = SceneSource::resolve(&argument(&scene)).unwrap();
    assert_eq!(source, SceneSource::SceneFile(scene.clone()));

    let located = source.description(None).unwrap();
    assert_eq!(located.base_dir, dir.path());
    assert!(matches!(
        &located.description.objects[0].shape,
        ShapeDescription::Model { path } if path == "missing.glb"
    ));

    let error = source.load(None).unwrap_err().to_string();
    assert!(
        error.contains("ship.toml") && error.contains("missing.glb"),
        "{error}"
    );
}

#[test]
fn a_loaded_scene_file_is_named_after_its_stem() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "cubes.toml",
        "[observer]\nposition = [0, -5, 0]\nlook_at = [0, 0, 0]\n\
         [[object]]\nshape = { type = \"cube\" }\n",
    );
    let loaded = SceneSource::resolve(&argument(&scene))
        .unwrap()
        .load(None)
        .unwrap();
    assert_eq!(loaded.scene.name, "cubes");
    assert_eq!(loaded.source.base_dir, dir.path());
}

/// A missing scene file or model is refused when resolved with one message, the one every
/// front end gives (a name typed or a path object in Python alike); one that goes missing after
/// is reported when read, naming it.
#[test]
fn missing_scene_and_model_files_are_named_with_one_message() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["absent.toml", "absent.obj"] {
        let path = dir.path().join(name);
        let error = SceneSource::resolve(&argument(&path)).unwrap_err();
        assert!(matches!(error, ResolveError::NoSuchFile(_)), "{error}");
        assert_eq!(
            error.to_string(),
            format!("cannot open {}: no such file or directory", path.display())
        );
        let from_path = SceneSource::from_path(&path).unwrap();
        let error = from_path.load(None).unwrap_err().to_string();
        assert!(error.contains(name), "{error}");
    }
}

#[test]
fn other_files_and_unknown_names_are_refused_with_one_message_each() {
    let dir = tempfile::tempdir().unwrap();
    let notes = write(dir.path(), "notes.txt", "hello");
    let error = SceneSource::resolve(&argument(&notes)).unwrap_err();
    assert!(matches!(error, ResolveError::Unsupported(_)));
    assert_eq!(
        error.to_string(),
        format!(
            "cannot open {:?}: a scene file must end in .toml and a model in one of \
             .gltf, .glb, .obj, .ply, .stl",
            argument(&notes)
        )
    );

    let error = SceneSource::resolve("no-such-scene").unwrap_err();
    assert!(matches!(error, ResolveError::NotFound(_)));
    assert_eq!(
        error.to_string(),
        "\"no-such-scene\" is neither a built-in scene (see `srt scenes`) nor an existing file"
    );
}

#[test]
fn a_model_held_in_memory_is_a_bare_model_scene() {
    let spider = srt_scene::assets::embedded("models/spider.stl")
        .unwrap()
        .to_vec();
    let path = srt_scene::assets::add_memory_file("dropped-spider.stl", spider);
    let source = SceneSource::from_path(Path::new(&path)).unwrap();
    assert!(matches!(source, SceneSource::Model(_)));
    let loaded = source.load(None).unwrap();
    assert_eq!(loaded.scene.name, "dropped-spider");
    assert_eq!(loaded.scene.objects.len(), 1);
    let triangles: usize = loaded.scene.objects[0]
        .parts
        .iter()
        .map(|part| part.mesh.triangles().len())
        .sum();
    assert_eq!(triangles, 1368);
}

//! Imports real models no one here made: every glTF, OBJ, PLY and STL file of Debian's
//! `assimp-testmodels` (/usr/share/assimp/models). Each must load or fail with an error — never
//! panic — and everything in its `invalid/` folder must fail.
//!
//! The corpus is a system package (`apt-get install assimp-testmodels`), so a fresh machine may
//! not have it. Environment variables:
//!
//! - `SRT_ASSIMP_MODELS=DIR`: use another copy of the models folder.
//! - `SRT_REQUIRE_CORPUS=1` (set by CI): a missing corpus fails the tests. Without it they print
//!   a line starting with `SKIPPED ` (naming the folder and how to install it) and pass.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::Instant;

use srt_scene::import::{ImportFailure, Model, SUPPORTED_EXTENSIONS, load_model};

/// The corpus folder, or `None` (after printing a `SKIPPED ` line) when it is missing and not
/// required ([`srt_scene::corpus::for_test`]).
fn corpus(test: &str) -> Option<PathBuf> {
    srt_scene::corpus::for_test(test, "")
}

/// Every file under `dir` (recursively) with a supported extension, sorted.
fn model_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if extension(&path).is_some_and(|e| SUPPORTED_EXTENSIONS.contains(&e.as_str())) {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// The outcome of loading one file.
enum Outcome {
    Loaded(Model),
    Failed(String),
    /// A panic, caught here or (as [`ImportFailure::Crashed`]) by the importer's own guard.
    Panicked(String),
}

fn try_load(path: &Path) -> Outcome {
    match catch_unwind(AssertUnwindSafe(|| load_model(path))) {
        Ok(Ok(model)) => Outcome::Loaded(model),
        Ok(Err(e)) if matches!(e.reason(), ImportFailure::Crashed(_)) => {
            Outcome::Panicked(e.to_string())
        }
        Ok(Err(e)) => {
            let message = e.to_string();
            let name = path.file_name().unwrap().to_string_lossy();
            assert!(
                message.contains(name.as_ref()),
                "error message does not name the file: {message}"
            );
            Outcome::Failed(message)
        }
        Err(_) => Outcome::Panicked(format!("{}: panicked", path.display())),
    }
}

#[test]
fn every_corpus_model_loads_or_fails_cleanly() {
    let Some(root) = corpus("every_corpus_model_loads_or_fails_cleanly") else {
        return;
    };
    let start = Instant::now();
    let mut panicked = Vec::new();
    let mut summary = String::new();
    for folder in ["glTF2", "OBJ", "PLY", "STL"] {
        let files = model_files(&root.join(folder));
        assert!(
            !files.is_empty(),
            "no model files under {}",
            root.join(folder).display()
        );
        let (mut loaded, mut failed) = (0, 0);
        for path in &files {
            let shown = path
                .strip_prefix(&root)
                .unwrap_or(path)
                .display()
                .to_string();
            match try_load(path) {
                Outcome::Loaded(model) => {
                    loaded += 1;
                    summary += &format!(
                        "  loaded {shown}: {} parts ({} textured), {} triangles, {} warnings\n",
                        model.parts.len(),
                        model
                            .parts
                            .iter()
                            .filter(|p| p.material.texture.is_some())
                            .count(),
                        model.triangle_count(),
                        model.warnings.len()
                    );
                    for warning in &model.warnings {
                        summary += &format!("      warning: {warning}\n");
                    }
                }
                Outcome::Failed(message) => {
                    failed += 1;
                    summary += &format!("  FAILED {shown}: {message}\n");
                }
                Outcome::Panicked(message) => {
                    summary += &format!("  PANICKED {shown}: {message}\n");
                    panicked.push(shown);
                }
            }
        }
        summary += &format!(
            "{folder}: {} files, {loaded} loaded, {failed} failed cleanly\n",
            files.len()
        );
    }
    println!("{summary}corpus import took {:.2?}", start.elapsed());
    assert!(
        panicked.is_empty(),
        "the importer panicked on: {panicked:#?}"
    );
}

#[test]
fn invalid_corpus_models_fail_cleanly() {
    let Some(root) = corpus("invalid_corpus_models_fail_cleanly") else {
        return;
    };
    let files = model_files(&root.join("invalid"));
    assert!(
        !files.is_empty(),
        "no model files under {}",
        root.join("invalid").display()
    );
    for path in files {
        match try_load(&path) {
            Outcome::Failed(message) => {
                println!("  FAILED (as it should) {}: {message}", path.display());
            }
            Outcome::Loaded(model) => panic!(
                "{} is invalid but loaded ({} triangles, warnings {:?})",
                path.display(),
                model.triangle_count(),
                model.warnings
            ),
            Outcome::Panicked(message) => {
                panic!("{} made the importer panic: {message}", path.display())
            }
        }
    }
}

/// Loads a corpus model that must load.
fn must_load(root: &Path, relative: &str) -> Model {
    let path = root.join(relative);
    match load_model(&path) {
        Ok(model) => model,
        Err(e) => panic!("{relative} should load: {e}"),
    }
}

#[test]
fn well_known_corpus_models_load_completely() {
    let Some(root) = corpus("well_known_corpus_models_load_completely") else {
        return;
    };

    let engine = must_load(
        &root,
        "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
    );
    println!(
        "2CylinderEngine.glb: {} parts, {} triangles",
        engine.parts.len(),
        engine.triangle_count()
    );
    assert_eq!(engine.triangle_count(), ENGINE_TRIANGLES);

    let box_textured = must_load(&root, "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
    assert_eq!(box_textured.triangle_count(), 12);
    let texture = box_textured.parts[0]
        .material
        .texture
        .as_ref()
        .expect("BoxTextured has a texture");
    assert_eq!((texture.width, texture.height), (211, 211)); // CesiumLogoFlat.png
    assert!(
        box_textured.warnings.is_empty(),
        "{:?}",
        box_textured.warnings
    );

    let wuson = must_load(&root, "OBJ/WusonOBJ.obj");
    println!(
        "WusonOBJ.obj: {} parts, {} triangles",
        wuson.parts.len(),
        wuson.triangle_count()
    );
    assert_eq!(wuson.triangle_count(), WUSON_TRIANGLES);
    assert_eq!(
        obj_face_triangles(&root.join("OBJ/WusonOBJ.obj")),
        WUSON_TRIANGLES
    );
    let (lo, hi) = wuson.bounds().unwrap();
    assert!((hi - lo).min_element() > 0.1, "Wuson is flat? {lo} {hi}");
}

/// Triangles in 2CylinderEngine.glb: its 29 meshes hold 75 730 triangles, and its 67 mesh
/// nodes instance them into 115 parts with 121 496 triangles (counted independently from the
/// file's JSON: index counts / 3 summed over the scene's node tree).
const ENGINE_TRIANGLES: usize = 121_496;
/// Triangles in WusonOBJ.obj: a snapshot of the file in Debian's assimp-testmodels, checked
/// independently of the loader by [`obj_face_triangles`].
const WUSON_TRIANGLES: usize = 3732;

/// The triangles of an OBJ file's faces counted from its text: n − 2 per `f` line of n corners.
fn obj_face_triangles(path: &std::path::Path) -> usize {
    std::fs::read_to_string(path)
        .expect("the OBJ file reads")
        .lines()
        .filter_map(|line| line.strip_prefix("f "))
        .map(|corners| corners.split_whitespace().count().saturating_sub(2))
        .sum()
}

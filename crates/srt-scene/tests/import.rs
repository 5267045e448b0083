//! Model import on the small fixtures in `fixtures/` (written by `fixtures/make_fixtures.py`):
//! the same unit cube in every format, and files broken in one deliberate way each.

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use srt_scene::import::{ImportFailure, Model, load_model};
use srt_scene::{MeshError, Part};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(name)
}

fn load(name: &str) -> Model {
    match load_model(&fixture(name)) {
        Ok(model) => model,
        Err(e) => panic!("{name} should load: {e}"),
    }
}

/// Loads a fixture that must fail; checks that the message names the file.
fn load_err(path: &Path) -> srt_scene::ImportError {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    match load_model(path) {
        Ok(model) => panic!(
            "{name} should fail, but loaded {} triangles",
            model.triangle_count()
        ),
        Err(e) => {
            let message = e.to_string();
            assert!(
                message.contains(&name),
                "message does not name the file: {message}"
            );
            assert!(message.starts_with("cannot load model"), "{message}");
            e
        }
    }
}

fn assert_close(a: DVec3, b: DVec3) {
    assert!((a - b).length() < 1e-6, "{a} != {b}");
}

fn assert_bounds(model: &Model, lo: DVec3, hi: DVec3) {
    let (l, h) = model.bounds().expect("a model with parts");
    assert_close(l, lo);
    assert_close(h, hi);
}

/// Every normal is unit length and points away from the centre of the part's bounds (true for a
/// cube's face normals and its smooth corner normals alike).
fn assert_outward_normals(part: &Part) {
    let (lo, hi) = part.mesh.bounds();
    let centre = (lo + hi) / 2.0;
    for (p, n) in part.mesh.positions().iter().zip(part.mesh.normals()) {
        assert!((n.length() - 1.0).abs() < 1e-9);
        assert!(n.dot(*p - centre) > 0.0, "normal {n} at {p} points inwards");
    }
    // Counter-clockwise triangles seen from outside.
    for i in 0..part.mesh.triangles().len() {
        let [a, b, c] = part.mesh.triangle_positions(i);
        assert!(
            (b - a).cross(c - a).dot(a - centre) > 0.0,
            "triangle {i} is wound inwards"
        );
    }
}

const UNIT_LO: DVec3 = DVec3::splat(-0.5);
const UNIT_HI: DVec3 = DVec3::splat(0.5);

/// sRGB encoding of a linear 0.5.
const SRGB_HALF: f32 = 0.735_357;

#[test]
fn gltf_with_embedded_buffer_applies_node_transforms() {
    let model = load("cube.gltf");
    assert_eq!(model.parts.len(), 1);
    assert_eq!(model.triangle_count(), 12);
    // Child scale 2 inside parent translation (10, 0, 0).
    assert_bounds(
        &model,
        DVec3::new(9.0, -1.0, -1.0),
        DVec3::new(11.0, 1.0, 1.0),
    );
    let part = &model.parts[0];
    assert_outward_normals(part);
    assert_eq!(part.material.name, "grey");
    for (c, expected) in part
        .material
        .base_color
        .iter()
        .zip([SRGB_HALF, SRGB_HALF, SRGB_HALF, 1.0])
    {
        assert!(
            (c - expected).abs() < 1e-4,
            "{:?}",
            part.material.base_color
        );
    }
    assert!(part.material.texture.is_none());
    // The POINTS primitive is skipped with a warning.
    assert_eq!(model.warnings.len(), 1, "{:?}", model.warnings);
    assert!(model.warnings[0].contains("Points"), "{:?}", model.warnings);
}

#[test]
fn glb_reads_the_texture_from_the_binary_chunk() {
    let model = load("cube.glb");
    assert_eq!(model.triangle_count(), 12);
    assert_bounds(
        &model,
        DVec3::new(9.0, -1.0, -1.0),
        DVec3::new(11.0, 1.0, 1.0),
    );
    let material = &model.parts[0].material;
    assert_eq!(material.base_color, [1.0, 0.0, 0.0, 1.0]);
    let texture = material.texture.as_ref().expect("a base-colour texture");
    assert_eq!((texture.width, texture.height), (4, 2));
    assert_eq!(texture.texels[0], [255, 0, 0, 255], "row 0 is the top row");
    assert_eq!(texture.texels[4], [0, 0, 0, 255]);
    let uvs = model.parts[0].mesh.uvs();
    assert!(uvs.contains(&DVec2::new(0.0, 0.0)) && uvs.contains(&DVec2::new(1.0, 1.0)));
}

#[test]
fn gltf_with_external_buffer_warns_about_a_missing_image() {
    let model = load("cube_external.gltf");
    assert_eq!(model.triangle_count(), 12);
    assert_bounds(
        &model,
        DVec3::new(9.0, -1.0, -1.0),
        DVec3::new(11.0, 1.0, 1.0),
    );
    let material = &model.parts[0].material;
    assert!(material.texture.is_none());
    assert!((material.base_color[0] - SRGB_HALF).abs() < 1e-4);
    let warning = model
        .warnings
        .iter()
        .find(|w| w.contains("no_such_texture.png"));
    assert!(warning.is_some(), "{:?}", model.warnings);
}

#[test]
fn gltf_with_a_missing_buffer_is_an_error_naming_both_files() {
    let e = load_err(&fixture("missing_buffer.gltf"));
    assert!(matches!(e.reason(), ImportFailure::Resource { .. }), "{e}");
    assert!(e.to_string().contains("no_such_buffer.bin"), "{e}");
}

#[test]
fn obj_reads_mtl_colour_texture_and_flips_v() {
    let model = load("cube.obj");
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    assert_eq!(model.parts.len(), 1);
    assert_eq!(model.triangle_count(), 12);
    assert_bounds(&model, UNIT_LO, UNIT_HI);
    let part = &model.parts[0];
    assert_outward_normals(part);
    assert_eq!(part.material.name, "painted");
    assert_eq!(part.material.base_color, [0.8, 0.2, 0.1, 1.0]);
    let texture = part.material.texture.as_ref().expect("map_Kd texture");
    assert_eq!((texture.width, texture.height), (4, 2));
    assert!(
        texture.source.ends_with("checker.png"),
        "{}",
        texture.source
    );
    // The +x face's corner (0.5, −0.5, 0.5) is the bottom-left of the image: glTF's (0, 1); the
    // OBJ file stores it as vt 0 0.
    let mesh = &part.mesh;
    let corner = (0..mesh.positions().len())
        .find(|&i| {
            (mesh.positions()[i] - DVec3::new(0.5, -0.5, 0.5)).length() < 1e-9
                && (mesh.normals()[i] - DVec3::X).length() < 1e-9
        })
        .expect("the +x face's corner");
    assert_eq!(mesh.uvs()[corner], DVec2::new(0.0, 1.0));
}

#[test]
fn obj_with_a_missing_texture_loads_with_a_warning() {
    let model = load("cube_missing_texture.obj");
    assert_eq!(model.triangle_count(), 12);
    let material = &model.parts[0].material;
    assert!(material.texture.is_none());
    assert_eq!(material.base_color, [0.8, 0.2, 0.1, 1.0]);
    assert_eq!(model.warnings.len(), 1, "{:?}", model.warnings);
    assert!(
        model.warnings[0].contains("no_such_texture.png"),
        "{:?}",
        model.warnings
    );
}

#[test]
fn ascii_ply_quads_are_triangulated() {
    let model = load("cube_ascii.ply");
    assert_eq!(model.parts.len(), 1);
    assert_eq!(model.triangle_count(), 12);
    assert_eq!(model.vertex_count(), 8);
    assert_bounds(&model, UNIT_LO, UNIT_HI);
    assert_outward_normals(&model.parts[0]);
    assert!(model.parts[0].mesh.colors().is_none());
}

#[test]
fn binary_little_endian_ply_reads_uchar_colours() {
    let model = load("cube_binary_le.ply");
    assert_eq!(model.triangle_count(), 12);
    assert_bounds(&model, UNIT_LO, UNIT_HI);
    let mesh = &model.parts[0].mesh;
    let colors = mesh.colors().expect("vertex colours");
    // Corner i has red 10 i / 255, green 1, blue 0, alpha 128 / 255; corner 1 is (0.5, −0.5, −0.5).
    let i = mesh
        .positions()
        .iter()
        .position(|p| *p == DVec3::new(0.5, -0.5, -0.5))
        .unwrap();
    let expected = [10.0 / 255.0, 1.0, 0.0, 128.0 / 255.0];
    for (c, e) in colors[i].iter().zip(expected) {
        assert!((c - e).abs() < 1e-6, "{:?}", colors[i]);
    }
}

#[test]
fn binary_big_endian_ply_reads_float_colours_and_double_positions() {
    let model = load("cube_binary_be.ply");
    assert_eq!(model.triangle_count(), 12);
    assert_bounds(&model, UNIT_LO, UNIT_HI);
    assert_outward_normals(&model.parts[0]);
    let colors = model.parts[0].mesh.colors().expect("vertex colours");
    assert!(
        colors.iter().all(|c| *c == [0.25, 0.5, 1.0, 1.0]),
        "{colors:?}"
    );
}

#[test]
fn stl_ascii_and_binary_give_flat_facets() {
    for name in ["cube_ascii.stl", "cube_binary.stl"] {
        let model = load(name);
        assert!(model.warnings.is_empty(), "{name}: {:?}", model.warnings);
        assert_eq!(model.triangle_count(), 12, "{name}");
        assert_eq!(
            model.vertex_count(),
            36,
            "{name}: each facet has its own vertices"
        );
        assert_bounds(&model, UNIT_LO, UNIT_HI);
        let mesh = &model.parts[0].mesh;
        for i in 0..12 {
            let [a, b, c] = mesh.triangle_positions(i);
            let face = (b - a).cross(c - a).normalize();
            for &v in &mesh.triangles()[i] {
                assert_close(mesh.normals()[v as usize], face);
            }
        }
        assert_outward_normals(&model.parts[0]);
    }
}

#[test]
fn all_formats_give_the_same_cube() {
    for name in [
        "cube.obj",
        "cube_ascii.ply",
        "cube_binary_le.ply",
        "cube_binary_be.ply",
        "cube_ascii.stl",
        "cube_binary.stl",
    ] {
        let model = load(name);
        assert_bounds(&model, UNIT_LO, UNIT_HI);
        let area: f64 = model
            .parts
            .iter()
            .flat_map(|p| (0..p.mesh.triangles().len()).map(|i| p.mesh.triangle_positions(i)))
            .map(|[a, b, c]| (b - a).cross(c - a).length() / 2.0)
            .sum();
        assert!((area - 6.0).abs() < 1e-9, "{name}: area {area}");
    }
}

#[test]
fn extensions_are_case_insensitive() {
    let dir = temp_dir("case");
    let path = dir.join("CUBE.STL");
    std::fs::copy(fixture("cube_binary.stl"), &path).unwrap();
    assert_eq!(load_model(&path).unwrap().triangle_count(), 12);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn broken_files_are_errors_naming_the_file() {
    let e = load_err(&fixture("empty.obj"));
    assert!(matches!(e.reason(), ImportFailure::Empty { .. }), "{e}");

    let e = load_err(&fixture("truncated.glb"));
    assert!(
        matches!(e.reason(), ImportFailure::Invalid { format: "glTF", .. }),
        "{e}"
    );

    let e = load_err(&fixture("nan_vertex.obj"));
    assert!(
        matches!(
            e.reason(),
            ImportFailure::Mesh {
                error: MeshError::NonFinite {
                    attribute: "position",
                    ..
                },
                ..
            }
        ),
        "{e}"
    );

    let e = load_err(&fixture("bad_index.ply"));
    assert!(
        matches!(
            e.reason(),
            ImportFailure::Mesh {
                error: MeshError::IndexOutOfRange { index: 99, .. },
                ..
            }
        ),
        "{e}"
    );

    let e = load_err(&fixture("cube.xyz"));
    assert!(
        matches!(e.reason(), ImportFailure::UnsupportedExtension { .. }),
        "{e}"
    );
    let message = e.to_string();
    for ext in ["gltf", "glb", "obj", "ply", "stl"] {
        assert!(message.contains(ext), "{message}");
    }

    let e = load_err(&fixture("no_such_model.glb"));
    assert!(matches!(e.reason(), ImportFailure::Io(_)), "{e}");

    let e = load_err(Path::new("no_extension"));
    assert!(
        matches!(e.reason(), ImportFailure::UnsupportedExtension { .. }),
        "{e}"
    );
}

#[test]
fn empty_and_garbage_files_are_errors_in_every_format() {
    let dir = temp_dir("garbage");
    let contents: [&[u8]; 5] = [
        b"",
        b"\0\0\0\0",
        b"solid",
        b"glTF\x02\0\0\0\x05\0\0\0",
        &[0xff; 200],
    ];
    for ext in ["gltf", "glb", "obj", "ply", "stl"] {
        for (i, bytes) in contents.iter().enumerate() {
            let path = dir.join(format!("garbage{i}.{ext}"));
            std::fs::write(&path, bytes).unwrap();
            let e = load_err(&path);
            assert!(!matches!(e.reason(), ImportFailure::Crashed(_)), "{e}");
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// Every prefix of every good fixture (a truncated download, a full disk) loads or fails cleanly;
/// none crashes a parser.
#[test]
fn truncated_fixtures_never_crash() {
    let dir = temp_dir("truncated");
    for name in [
        "cube.gltf",
        "cube_external.gltf",
        "cube.glb",
        "cube.obj",
        "cube_ascii.ply",
        "cube_binary_le.ply",
        "cube_binary_be.ply",
        "cube_ascii.stl",
        "cube_binary.stl",
    ] {
        let bytes = std::fs::read(fixture(name)).unwrap();
        let path = dir.join(name);
        let step = (bytes.len() / 300).max(1);
        for len in (0..bytes.len()).step_by(step) {
            std::fs::write(&path, &bytes[..len]).unwrap();
            if let Err(e) = load_model(&path) {
                assert!(
                    !matches!(e.reason(), ImportFailure::Crashed(_)),
                    "{name} cut at {len}: {e}"
                );
                assert!(e.to_string().contains(name), "{e}");
            }
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A fresh scratch folder for one test.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("srt-import-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

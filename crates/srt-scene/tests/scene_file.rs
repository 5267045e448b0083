//! Scene files: parsing, saving, validation errors and warnings, loading models and textures
//! relative to the scene file, placement.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use srt_color::ToneMap;
use srt_scene::description::{FIT_RADIUS, line_column};
use srt_scene::{
    Effects, ObjectDescription, Scale, SceneDescription, SceneError, SceneErrorKind,
    ShapeDescription, TextureDescription, load_scene_file,
};

/// A scene file using every field of the format.
const FULL: &str = r#"
name = "full"
description = "every field"

[observer]
position = [0.0, -10.0, 2.0]
look_at = [0.0, 0.0, 0.5]
up = [0.0, 0.0, 1.0]
fov_y_deg = 50.0
ct = 1.5

[light]
position = [5.0, -5.0, 10.0]
temperature_k = 5500.0

[render]
effects = "searchlight"
tone_map = "luminance"
background = [0.1, 0.2, 0.3]
ambient = 0.1
diffuse = 0.8
specular = 0.3
shininess = 16.0

[[object]]
name = "box"
shape = { type = "cube", size = 2.0, subdivisions = 3 }
texture = { type = "checker", squares = 6, colors = [[1.0, 0.9, 0.8], [0.1, 0.1, 0.2]] }
color = [1.0, 0.5, 0.25]
wireframe = 0.05
beta = [0.5, 0.0, 0.0]
offset = [-3.0, 0.0, 0.0]
translate = [0.0, 0.0, 1.0]
rotate_deg = [0.0, 0.0, 45.0]
scale = [1.0, 2.0, 0.5]

[[object]]
shape = { type = "sphere", radius = 0.5, segments = 12 }
texture = "checker"
beta = [0.0, -0.3, 0.0]
scale = 2
"#;

fn parse(text: &str) -> Result<SceneDescription, SceneError> {
    SceneDescription::from_toml_str(text, "test.toml")
}

fn build(text: &str) -> Result<(srt_scene::Scene, Vec<String>), SceneError> {
    parse(text)?.build(Path::new("."))
}

/// A minimal valid scene with one unit cube, with `extra` appended to its object table.
fn with_object(extra: &str) -> String {
    format!(
        "[observer]\nposition = [0.0, -5.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\n[[object]]\n\
         name = \"probe\"\nshape = {{ type = \"cube\" }}\n{extra}\n"
    )
}

/// A fresh empty folder under the system's temporary folder.
fn temp_dir() -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "srt-scene-test-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An ASCII STL tetrahedron spanning (10, 10, 10)–(14, 14, 14), far from the origin.
const TETRAHEDRON: &str = "solid t
facet normal 0 0 -1
outer loop
vertex 10 10 10
vertex 10 14 10
vertex 14 10 10
endloop
endfacet
facet normal 0 -1 0
outer loop
vertex 10 10 10
vertex 14 10 10
vertex 10 10 14
endloop
endfacet
facet normal -1 0 0
outer loop
vertex 10 10 10
vertex 10 10 14
vertex 10 14 10
endloop
endfacet
facet normal 1 1 1
outer loop
vertex 14 10 10
vertex 10 14 10
vertex 10 10 14
endloop
endfacet
endsolid t
";

#[test]
fn a_full_scene_parses_and_builds() {
    let description = parse(FULL).unwrap();
    assert_eq!(description.name.as_deref(), Some("full"));
    assert_eq!(description.objects.len(), 2);
    assert_eq!(description.objects[1].scale, Scale::Uniform(2.0));
    assert_eq!(
        description.objects[0].scale,
        Scale::PerAxis([1.0, 2.0, 0.5])
    );
    let (scene, warnings) = description.build(Path::new(".")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(scene.name, "full");
    assert_eq!(scene.effects, Effects::Searchlight);
    assert_eq!(scene.tone_map, ToneMap::Luminance);
    assert_eq!(scene.background, DVec3::new(0.1, 0.2, 0.3));
    assert_eq!(scene.shading.ambient, 0.1);
    assert_eq!(scene.shading.shininess, 16.0);
    assert_eq!(scene.light.temperature_k, 5500.0);
    assert_eq!(scene.observer.time, 1.5);
    assert_eq!(scene.observer.fov_y_deg, 50.0);
    assert!((scene.observer.direction - DVec3::new(0.0, 10.0, -1.5).normalize()).length() < 1e-12);

    let cube = &scene.objects[0];
    assert_eq!(cube.name, "box");
    assert_eq!(cube.triangle_count(), 6 * 2 * 9);
    assert_eq!(cube.wireframe, Some(0.05));
    assert_eq!(cube.frame.beta(), DVec3::new(0.5, 0.0, 0.0));
    assert_eq!(cube.frame.offset(), DVec3::new(-3.0, 0.0, 0.0));
    let material = &cube.parts[0].material;
    assert_eq!(material.base_color, [1.0, 0.5, 0.25, 1.0]);
    let texture = material.texture.as_ref().unwrap();
    assert_eq!(texture.width % 6, 0);
    assert_eq!(texture.texels[0], [255, 230, 204, 255]);
    // Scaled (1, 2, 0.5), turned 45° about z, lifted by 1: z spans 0.5..1.5.
    let (lo, hi) = cube.parts[0].mesh.bounds();
    assert!(
        (lo.z - 0.5).abs() < 1e-12 && (hi.z - 1.5).abs() < 1e-12,
        "{lo} {hi}"
    );
    // The corner (1, −2) of the 2 × 4 footprint turns to x = 3/√2.
    assert!((hi.x - 3.0 / 2.0_f64.sqrt()).abs() < 1e-12, "{hi}");

    let sphere = &scene.objects[1];
    assert_eq!(sphere.name, "object 2");
    let (lo, hi) = sphere.parts[0].mesh.bounds();
    assert!((hi - DVec3::ONE).length() < 1e-9 && (lo + DVec3::ONE).length() < 1e-9);
    assert!(sphere.parts[0].material.texture.is_some());
    assert_eq!(sphere.wireframe, None);
}

#[test]
fn defaults_fill_in_what_is_left_out() {
    let (scene, warnings) =
        build("[observer]\nposition = [1.0, 2.0, 3.0]\ndirection = [0.0, 1.0, 0.0]\n").unwrap();
    assert_eq!(warnings, ["the scene has no objects"]);
    assert_eq!(scene.name, "untitled");
    assert_eq!(scene.observer.up, DVec3::Z);
    assert_eq!(
        scene.observer.fov_y_deg,
        srt_scene::description::DEFAULT_FOV_Y_DEG
    );
    assert_eq!(scene.observer.time, 0.0);
    assert_eq!(scene.light.position, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(
        scene.light.temperature_k,
        srt_scene::description::DEFAULT_LIGHT_TEMPERATURE_K
    );
    assert_eq!(scene.effects, Effects::default());
    assert_eq!(scene.tone_map, Effects::default().default_tone_map());
    assert_eq!(scene.shading, srt_scene::Shading::default());
    assert_eq!(scene.background, DVec3::ZERO);

    // The tone map follows the effect mode unless given.
    let (scene, _) = build(
        "[observer]\nposition = [0.0, 0.0, 0.0]\ndirection = [0.0, 1.0, 0.0]\n\
         [render]\neffects = \"searchlight\"\n",
    )
    .unwrap();
    assert_eq!(scene.tone_map, ToneMap::Searchlight);

    // A bare cube: size 1, two triangles per face, white, at rest at the origin.
    let (scene, _) = build(&with_object("")).unwrap();
    let cube = &scene.objects[0];
    assert_eq!(cube.triangle_count(), 12);
    assert_eq!(cube.frame.beta(), DVec3::ZERO);
    assert_eq!(cube.parts[0].material.base_color, [1.0; 4]);
    assert!(cube.parts[0].material.texture.is_none());
    assert_eq!(cube.parts[0].mesh.bounds().1, DVec3::splat(0.5));
}

#[test]
fn descriptions_round_trip_through_toml() {
    let full = parse(FULL).unwrap();
    let text = full.to_toml_string();
    assert_eq!(parse(&text).unwrap(), full, "{text}");

    let mut model =
        SceneDescription::for_model(Path::new("ships/x wing.glb"), DVec3::new(0.1, -0.7, 0.2));
    model.description = Some("multi\nline \"quoted\" text".to_owned());
    model.light = None;
    model.render.tone_map = Some(ToneMap::Searchlight);
    model.objects[0].texture = Some(TextureDescription::Image {
        path: "checker".to_owned(),
    });
    model.objects[0].scale = Scale::PerAxis([1.0, 1.0, 3.0]);
    model.objects.push(ObjectDescription {
        texture: Some(TextureDescription::checker()),
        wireframe: Some(0.01),
        color: Some([0.5, 0.5, 0.5]),
        ..ObjectDescription::new(ShapeDescription::Sphere {
            radius: 2.0,
            segments: 7,
        })
    });
    let text = model.to_toml_string();
    assert_eq!(parse(&text).unwrap(), model, "{text}");
    // An image called "checker" is not mistaken for the checkerboard.
    assert!(text.contains("type = \"image\""), "{text}");
}

fn syntax_error(text: &str) -> (usize, usize, String, String) {
    let error = parse(text).unwrap_err();
    let shown = error.to_string();
    match error.kind() {
        SceneErrorKind::Syntax {
            line,
            column,
            message,
        } => (*line, *column, message.clone(), shown),
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

#[test]
fn unknown_keys_are_reported_with_line_and_column() {
    let text = "[observer]\nposition = [0.0, 0.0, 0.0]\n  colour = 3\n";
    let (line, column, message, shown) = syntax_error(text);
    assert_eq!((line, column), (3, 3), "{shown}");
    assert!(message.contains("colour"), "{message}");
    assert!(
        shown.contains("test.toml") && shown.contains("line 3, column 3"),
        "{shown}"
    );
    assert!(shown.contains("colour"), "{shown}");

    // Inside an object, its shape and its texture.
    let (line, _, message, _) = syntax_error(&with_object("velocity = [0.0, 0.0, 0.0]"));
    assert_eq!(line, 8);
    assert!(message.contains("velocity"), "{message}");
    let (line, _, message, shown) =
        syntax_error(&with_object("").replace("type = \"cube\"", "type = \"cube\", edge = 2"));
    assert_eq!(line, 7, "{shown}");
    assert!(message.contains("edge"), "{message}");
    let (line, _, message, _) =
        syntax_error(&with_object("texture = { type = \"checker\", tiles = 4 }"));
    assert_eq!(line, 8);
    assert!(message.contains("tiles"), "{message}");
    let (_, _, message, _) =
        syntax_error("title = \"x\"\n[observer]\nposition = [0.0, 0.0, 0.0]\n");
    assert!(message.contains("title"), "{message}");
}

#[test]
fn wrong_types_and_names_are_reported_with_line_and_column() {
    let (line, column, _, shown) =
        syntax_error("[observer]\nposition = [0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n");
    assert_eq!(line, 2, "{shown}");
    assert!(column >= 1);
    let (line, _, message, _) = syntax_error(&with_object("beta = \"fast\""));
    assert_eq!(line, 8);
    assert!(!message.is_empty());
    let (line, _, message, _) =
        syntax_error("[observer]\nposition = [0.0, 0.0, 0.0]\n[render]\neffects = \"colour\"\n");
    assert_eq!(line, 4);
    assert!(
        message.contains("colour") && message.contains("doppler"),
        "{message}"
    );
    let (line, _, message, _) =
        syntax_error("[observer]\nposition = [0.0, 0.0, 0.0]\n[render]\ntone_map = \"filmic\"\n");
    assert_eq!(line, 4);
    assert!(message.contains("filmic"), "{message}");
    let (_, _, message, _) = syntax_error(&with_object("").replace("\"cube\"", "\"torus\""));
    assert!(message.contains("torus"), "{message}");
    let (_, _, message, _) = syntax_error("[observer]\n");
    assert!(message.contains("position"), "{message}");
    let (line, column, _, _) = syntax_error("name = \"a\"\n[observer\n");
    assert_eq!((line, column), (2, 10));
}

#[test]
fn line_and_column_count_characters() {
    let text = "a = \"βγ\"\nbé = 1\n";
    assert_eq!(line_column(text, 0), (1, 1));
    assert_eq!(line_column(text, text.find('\n').unwrap() + 1), (2, 1));
    assert_eq!(line_column(text, text.find('=').unwrap()), (1, 3));
    assert_eq!(line_column(text, text.rfind('=').unwrap()), (2, 4));
    assert_eq!(line_column(text, text.len() + 10), (3, 1));
}

fn value_error(text: &str) -> String {
    let error = build(text).unwrap_err();
    assert!(
        matches!(
            error.kind(),
            SceneErrorKind::Value { .. } | SceneErrorKind::Frame { .. }
        ),
        "{error:?}"
    );
    assert!(parse(text).unwrap().validate().is_err());
    error.to_string()
}

#[test]
fn superluminal_and_invalid_velocities_name_the_object() {
    for beta in [
        "[0.0, 1.0, 0.0]",
        "[0.8, 0.8, 0.0]",
        "[nan, 0.0, 0.0]",
        "[0.0, inf, 0.0]",
    ] {
        let message = value_error(&with_object(&format!("beta = {beta}")));
        assert!(message.contains("object \"probe\""), "{message}");
    }
    let message = value_error(&with_object("beta = [0.0, 1.5, 0.0]"));
    assert!(message.contains("1.5"), "{message}");
    // Unnamed objects are counted.
    let text = with_object("").replace("name = \"probe\"\n", "")
        + "[[object]]\nshape = { type = \"cube\" }\nbeta = [1.0, 0.0, 0.0]\n";
    let message = value_error(&text);
    assert!(message.contains("object 2"), "{message}");
    let message = value_error(&with_object("offset = [nan, 0.0, 0.0]"));
    assert!(message.contains("probe"), "{message}");
}

#[test]
fn observer_errors() {
    let observer = |body: &str| format!("[observer]\nposition = [0.0, 0.0, 0.0]\n{body}\n");
    let message = value_error(&observer(
        "look_at = [1.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]",
    ));
    assert!(
        message.contains("look_at") && message.contains("direction"),
        "{message}"
    );
    let message = value_error(&observer(""));
    assert!(message.contains("neither"), "{message}");
    let message = value_error(&observer("look_at = [0.0, 0.0, 0.0]"));
    assert!(message.contains("zero viewing direction"), "{message}");
    let message = value_error(&observer("direction = [0.0, 0.0, 0.0]"));
    assert!(message.contains("zero viewing direction"), "{message}");
    let message = value_error(&observer("direction = [0.0, 0.0, -2.0]"));
    assert!(
        message.contains("observer.up") && message.contains("parallel"),
        "{message}"
    );
    let message = value_error(&observer(
        "direction = [1.0, 0.0, 0.0]\nup = [0.0, 0.0, 0.0]",
    ));
    assert!(message.contains("observer.up"), "{message}");
    for fov in ["0.0", "180.0", "200.0", "-10.0", "nan"] {
        let message = value_error(&observer(&format!(
            "direction = [1.0, 0.0, 0.0]\nfov_y_deg = {fov}"
        )));
        assert!(message.contains("fov_y_deg"), "{message}");
    }
    let message = value_error(&observer("direction = [1.0, 0.0, 0.0]\nct = inf"));
    assert!(message.contains("observer.ct"), "{message}");
    let message =
        value_error("[observer]\nposition = [nan, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n");
    assert!(message.contains("observer.position"), "{message}");
    // Up may be any vector not parallel to the view.
    assert!(
        build(&observer(
            "direction = [1.0, 0.0, 0.0]\nup = [0.0, 1.0, 1.0]"
        ))
        .is_ok()
    );
}

#[test]
fn light_and_render_errors() {
    let scene = |tables: &str| {
        format!("[observer]\nposition = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n{tables}\n")
    };
    for t in ["0.0", "-300.0", "nan", "inf"] {
        let message = value_error(&scene(&format!(
            "[light]\nposition = [0.0, 0.0, 1.0]\ntemperature_k = {t}"
        )));
        assert!(message.contains("light.temperature_k"), "{message}");
    }
    let message = value_error(&scene("[light]\nposition = [0.0, inf, 1.0]"));
    assert!(message.contains("light.position"), "{message}");
    let message = value_error(&scene("[render]\nbackground = [0.0, 1.5, 0.0]"));
    assert!(message.contains("render.background"), "{message}");
    for field in ["ambient", "diffuse", "specular", "shininess"] {
        let message = value_error(&scene(&format!("[render]\n{field} = -1.0")));
        assert!(message.contains(&format!("render.{field}")), "{message}");
    }
}

#[test]
fn object_errors_name_the_object_and_the_field() {
    let cases = [
        ("shape = { type = \"cube\", size = 0.0 }", "shape.size"),
        ("shape = { type = \"cube\", size = -2.0 }", "shape.size"),
        (
            "shape = { type = \"cube\", subdivisions = 0 }",
            "shape.subdivisions",
        ),
        (
            "shape = { type = \"cube\", subdivisions = 100000 }",
            "shape.subdivisions",
        ),
        (
            "shape = { type = \"sphere\", radius = 0.0 }",
            "shape.radius",
        ),
        (
            "shape = { type = \"sphere\", radius = -1.0 }",
            "shape.radius",
        ),
        (
            "shape = { type = \"sphere\", segments = 2 }",
            "shape.segments",
        ),
        ("shape = { type = \"model\", path = \"\" }", "shape.path"),
    ];
    for (shape, field) in cases {
        let text = with_object("").replace("shape = { type = \"cube\" }", shape);
        let message = value_error(&text);
        assert!(
            message.contains(field) && message.contains("object \"probe\""),
            "{message}"
        );
    }
    let cases = [
        ("scale = 0.0", "scale"),
        ("scale = -1.0", "scale"),
        ("scale = [1.0, 0.0, 1.0]", "scale"),
        ("scale = [1.0, nan, 1.0]", "scale"),
        ("wireframe = 0.0", "wireframe"),
        ("wireframe = -0.1", "wireframe"),
        ("color = [1.0, 1.2, 0.0]", "color"),
        ("translate = [inf, 0.0, 0.0]", "translate"),
        ("rotate_deg = [0.0, nan, 0.0]", "rotate_deg"),
        (
            "texture = { type = \"checker\", squares = 0 }",
            "texture.squares",
        ),
        (
            "texture = { type = \"checker\", colors = [[2.0, 0.0, 0.0], [0.0, 0.0, 0.0]] }",
            "texture.colors",
        ),
        (
            "texture = { type = \"image\", path = \"\" }",
            "texture.path",
        ),
    ];
    for (line, field) in cases {
        let message = value_error(&with_object(line));
        assert!(
            message.contains(field) && message.contains("object \"probe\""),
            "{message}"
        );
    }
    let (_, _, message, _) = syntax_error(&with_object("scale = [1.0, 2.0]"));
    assert!(
        message.contains('2') || message.contains("three"),
        "{message}"
    );
    let (_, _, message, _) = syntax_error(&with_object("texture = \"\""));
    assert!(message.contains("empty"), "{message}");
}

#[test]
fn missing_model_files_are_errors_naming_the_file() {
    let dir = temp_dir();
    let scene = with_object("").replace(
        "shape = { type = \"cube\" }",
        "shape = { type = \"model\", path = \"models/missing-ship.glb\" }",
    );
    std::fs::write(dir.join("ships.toml"), scene).unwrap();
    let error = load_scene_file(&dir.join("ships.toml")).unwrap_err();
    let message = error.to_string();
    assert!(
        matches!(error.kind(), SceneErrorKind::Model { .. }),
        "{error:?}"
    );
    assert!(message.contains("missing-ship.glb"), "{message}");
    assert!(
        message.contains("ships.toml") && message.contains("probe"),
        "{message}"
    );

    let text = with_object("").replace(
        "shape = { type = \"cube\" }",
        "shape = { type = \"model\", path = \"builtin:models/nothing.stl\" }",
    );
    let message = build(&text).unwrap_err().to_string();
    assert!(
        message.contains("nothing.stl") && message.contains("spider.stl"),
        "{message}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn missing_textures_are_warnings() {
    let dir = temp_dir();
    std::fs::write(
        dir.join("scene.toml"),
        with_object("texture = \"no-such-wood.png\""),
    )
    .unwrap();
    let (scene, _, warnings) = load_scene_file(&dir.join("scene.toml")).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].contains("no-such-wood.png") && warnings[0].contains("probe"),
        "{warnings:?}"
    );
    assert!(scene.objects[0].parts[0].material.texture.is_none());
    std::fs::remove_dir_all(dir).unwrap();
}

/// A flipbook loads every frame relative to the scene file, stacked in order; frames of
/// different sizes or a missing frame leave the object untextured with a warning naming the
/// file; bad lists and rates are refused.
#[test]
fn flipbooks_load_every_frame_or_say_which_one_failed() {
    let dir = temp_dir();
    std::fs::create_dir_all(dir.join("frames")).unwrap();
    for (name, size, colour) in [
        ("a.png", 2, [200, 0, 0, 255]),
        ("b.png", 2, [0, 0, 200, 255]),
        ("big.png", 3, [0, 200, 0, 255]),
    ] {
        image::RgbaImage::from_pixel(size, size, image::Rgba(colour))
            .save(dir.join("frames").join(name))
            .unwrap();
    }
    let load = |files: &str| {
        let text = with_object(&format!(
            "texture = {{ type = \"frames\", files = {files}, fps = 3.0 }}"
        ));
        std::fs::write(dir.join("book.toml"), text).unwrap();
        load_scene_file(&dir.join("book.toml")).unwrap()
    };
    let (scene, _, warnings) = load("[\"frames/a.png\", \"frames/b.png\", \"frames/a.png\"]");
    assert!(warnings.is_empty(), "{warnings:?}");
    let texture = scene.objects[0].parts[0].material.texture.as_ref().unwrap();
    assert_eq!((texture.width, texture.height, texture.frames), (2, 6, 3));
    assert_eq!(texture.frame_rate, 3.0);
    assert_eq!(
        texture.texels[4],
        [0, 0, 200, 255],
        "frame 1 starts at row 2"
    );
    assert_eq!(texture.frame_at(0.4), 1);
    for (files, named) in [
        ("[\"frames/a.png\", \"frames/big.png\"]", "big.png"),
        ("[\"frames/a.png\", \"frames/gone.png\"]", "frames/gone.png"),
    ] {
        let (scene, _, warnings) = load(files);
        assert!(scene.objects[0].parts[0].material.texture.is_none());
        assert!(
            warnings.len() == 1 && warnings[0].contains(named) && warnings[0].contains("probe"),
            "{warnings:?}"
        );
    }
    for (extra, key) in [
        (
            "texture = { type = \"frames\", files = [] }",
            "texture.files",
        ),
        (
            "texture = { type = \"frames\", files = [\"\"] }",
            "texture.files",
        ),
        (
            "texture = { type = \"frames\", files = [\"a.png\"], fps = 0.0 }",
            "texture.fps",
        ),
        (
            "texture = { type = \"frames\", files = [\"a.png\"], fps = inf }",
            "texture.fps",
        ),
    ] {
        let message = value_error(&with_object(extra));
        assert!(message.contains(key), "{extra}: {message}");
    }
}

#[test]
fn scene_files_load_models_and_textures_relative_to_their_folder() {
    let dir = temp_dir();
    std::fs::create_dir_all(dir.join("scenes/models")).unwrap();
    std::fs::write(dir.join("scenes/models/tetra.stl"), TETRAHEDRON).unwrap();
    let mut image = image::RgbaImage::new(2, 2);
    image.put_pixel(1, 0, image::Rgba([200, 100, 50, 255]));
    image.save(dir.join("scenes/models/wood.png")).unwrap();
    let text = "[observer]\nposition = [0.0, -5.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\n\
                [[object]]\nname = \"tetra\"\nshape = { type = \"model\", path = \"models/tetra.stl\" }\n\
                texture = \"models/wood.png\"\nfit = true\nbeta = [0.0, -0.6, 0.0]\n\n\
                [[object]]\nname = \"raw\"\nshape = { type = \"model\", path = \"models/tetra.stl\" }\n\
                color = [0.5, 0.5, 0.5]\n";
    std::fs::write(dir.join("scenes/tetra-demo.toml"), text).unwrap();
    let (scene, description, warnings) =
        load_scene_file(&dir.join("scenes/tetra-demo.toml")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(scene.name, "tetra-demo");
    assert_eq!(description.objects.len(), 2);

    let fitted = &scene.objects[0];
    assert_eq!(fitted.triangle_count(), 4);
    let texture = fitted.parts[0].material.texture.as_ref().unwrap();
    assert_eq!((texture.width, texture.height), (2, 2));
    assert_eq!(texture.texels[1], [200, 100, 50, 255]);
    let (lo, hi) = fitted.parts[0].mesh.bounds();
    assert!((lo + hi).length() < 1e-9, "centred: {lo} {hi}");
    let radius = fitted.parts[0]
        .mesh
        .positions()
        .iter()
        .map(|p| p.length())
        .fold(0.0, f64::max);
    assert!((radius - FIT_RADIUS).abs() < 1e-9, "{radius}");

    let raw = &scene.objects[1];
    assert_eq!(raw.parts[0].mesh.bounds().0, DVec3::splat(10.0));
    assert_eq!(raw.parts[0].material.base_color[..3], [0.5, 0.5, 0.5]);

    // A scene file that is not there, and one that is not TOML.
    let error = load_scene_file(&dir.join("scenes/none.toml")).unwrap_err();
    assert!(matches!(error.kind(), SceneErrorKind::Io(_)));
    assert!(error.to_string().contains("none.toml"), "{error}");
    std::fs::write(dir.join("bad.toml"), "[observer\n").unwrap();
    let error = load_scene_file(&dir.join("bad.toml")).unwrap_err();
    assert!(
        error.to_string().contains("bad.toml") && error.to_string().contains("line 1"),
        "{error}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn builtin_assets_load_from_any_scene() {
    let text = with_object("").replace(
        "shape = { type = \"cube\" }",
        "shape = { type = \"model\", path = \"builtin:models/spider.stl\" }\nfit = true\nscale = 2.0",
    );
    let (scene, warnings) = build(&text).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let object = &scene.objects[0];
    assert_eq!(object.triangle_count(), 1368);
    let radius = object
        .parts
        .iter()
        .flat_map(|p| p.mesh.positions())
        .map(|p| p.length())
        .fold(0.0, f64::max);
    assert!((radius - 2.0 * FIT_RADIUS).abs() < 1e-9, "{radius}");
}

#[test]
fn errors_of_unnamed_descriptions_name_the_scene() {
    let mut description = parse(&with_object("beta = [0.0, 2.0, 0.0]")).unwrap();
    assert!(
        description
            .build(Path::new("."))
            .unwrap_err()
            .to_string()
            .starts_with("scene:")
    );
    description.name = Some("demo".to_owned());
    let error = description.build(Path::new(".")).unwrap_err();
    assert!(
        error
            .to_string()
            .starts_with("scene \"demo\": object \"probe\""),
        "{error}"
    );
    assert_eq!(error.origin(), "scene \"demo\"");
}

#[test]
fn for_model_scenes_build_and_place_the_model_in_view() {
    let dir = temp_dir();
    std::fs::write(dir.join("tetra.stl"), TETRAHEDRON).unwrap();
    let beta = DVec3::new(0.3, -0.8, 0.1);
    let description = SceneDescription::for_model(&dir.join("tetra.stl"), beta);
    let (scene, warnings) = description.build(Path::new(".")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(scene.name, "tetra");
    let object = &scene.objects[0];
    let seen = object
        .frame
        .apparent_position(DVec3::ZERO, scene.observer.event());
    assert!(
        seen.length() < 1e-9,
        "the S′ origin is seen at the S origin: {seen}"
    );
    let forward = scene.observer.direction.normalize();
    assert!((forward - (-scene.observer.position).normalize()).length() < 1e-12);
    for p in object.parts[0].mesh.positions() {
        let apparent = object.frame.apparent_position(*p, scene.observer.event());
        assert!(
            (apparent - scene.observer.position).dot(forward) > 0.0,
            "in front of the camera"
        );
    }
    // Saving and loading it gives the same description.
    let text = description.to_toml_string();
    assert_eq!(parse(&text).unwrap(), description);
    // And a light that can be edited away.
    let mut no_light = description.clone();
    no_light.light = None;
    assert!(no_light.build(Path::new(".")).is_ok());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_complete_example_of_the_format_documentation_builds() {
    let doc = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/scene-format.md"
    ));
    let section = &doc[doc.find("## A complete example").unwrap()..];
    let start = section.find("```toml\n").unwrap() + "```toml\n".len();
    let example = &section[start..start + section[start..].find("```").unwrap()];
    let description = SceneDescription::from_toml_str(example, "docs/scene-format.md").unwrap();
    assert_eq!(description.objects.len(), 2);
    let (scene, warnings) = description.build(Path::new(".")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(scene.objects[0].triangle_count(), 300);
    assert_eq!(scene.objects[1].triangle_count(), 1368);
}

/// Clocks and blinking: every number is checked, unknown keys are refused with the key named,
/// and valid values reach the scene (a clock replaces the texture).
#[test]
fn clock_and_blink_values_are_checked() {
    for (extra, key) in [
        ("texture = { type = \"clock\", dial = 0.0 }", "texture.dial"),
        (
            "texture = { type = \"clock\", dial = -12.0 }",
            "texture.dial",
        ),
        ("texture = { type = \"clock\", rate = nan }", "texture.rate"),
        (
            "texture = { type = \"clock\", offset = inf }",
            "texture.offset",
        ),
        (
            "texture = { type = \"clock\", colors = [[1.0, 1.0, 1.0], [0.0, 2.0, 0.0]] }",
            "texture.colors",
        ),
        (
            "emission = { temperature_k = 3000.0, blink = { period = 0.0, duty = 0.5 } }",
            "emission.blink.period",
        ),
        (
            "emission = { temperature_k = 3000.0, blink = { period = 1.0, duty = 1.5 } }",
            "emission.blink.duty",
        ),
        (
            "emission = { temperature_k = 3000.0, blink = { period = nan, duty = 0.5 } }",
            "emission.blink.period",
        ),
    ] {
        let message = value_error(&with_object(extra));
        assert!(
            message.contains(key) && message.contains("probe"),
            "{extra}: {message}"
        );
    }
    for extra in [
        "texture = { type = \"clock\", speed = 2.0 }",
        "emission = { temperature_k = 3000.0, blink = { period = 1.0, duty = 0.5, phase = 0.1 } }",
        "emission = { temperature_k = 3000.0, blink = { duty = 0.5 } }",
    ] {
        let error = parse(&with_object(extra)).unwrap_err().to_string();
        assert!(
            error.contains("test.toml") && error.contains("line"),
            "{extra}: {error}"
        );
    }
    let (scene, _) = build(&with_object(
        "texture = { type = \"clock\", rate = 2.0, offset = -1.0 }
         emission = { temperature_k = 3000.0, blink = { period = 2.0, duty = 0.25 } }",
    ))
    .unwrap();
    let object = &scene.objects[0];
    let clock = object.clock.expect("a clock");
    assert_eq!((clock.rate, clock.offset, clock.dial), (2.0, -1.0, 12.0));
    assert!(object.parts.iter().all(|p| p.material.texture.is_none()));
    let emission = object.optics.emission.expect("an emission");
    assert!(emission.shines_at(0.4) && !emission.shines_at(0.6) && emission.shines_at(-1.9));
    // A description with both round-trips through its TOML.
    let description = parse(&with_object(
        "texture = { type = \"clock\", dial = 60.0 }
         emission = { temperature_k = 3000.0, blink = { period = 2.0, duty = 0.25 } }",
    ))
    .unwrap();
    let again = parse(&description.to_toml_string()).unwrap();
    assert_eq!(again, description);
}

#[test]
fn spectral_colour_and_sky_values_are_checked() {
    let scene = |tables: &str| {
        format!("[observer]\nposition = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n{tables}\n")
    };
    for t in ["0.0", "-1.0", "nan", "inf"] {
        let message = value_error(&scene(&format!(
            "[render]\ncolour = \"spectral\"\nexposure = {t}"
        )));
        assert!(message.contains("render.exposure"), "{message}");
    }
    let message = value_error(&scene("[render]\nexposure = 2.0"));
    assert!(
        message.contains("render.exposure") && message.contains("spectral"),
        "{message}"
    );
    for key in ["infrared", "ultraviolet"] {
        for v in ["-0.1", "1.5", "nan"] {
            let message = value_error(&with_object(&format!("{key} = {v}")));
            assert!(
                message.contains(key) && message.contains("probe"),
                "{message}"
            );
        }
    }
    for t in ["0.0", "-5.0", "nan"] {
        let message = value_error(&with_object(&format!(
            "emission = {{ temperature_k = {t} }}"
        )));
        assert!(message.contains("emission.temperature_k"), "{message}");
    }
    let message = value_error(&with_object(
        "emission = { temperature_k = 3000.0, brightness = -1.0 }",
    ));
    assert!(message.contains("emission.brightness"), "{message}");
    let message = value_error(&scene("[sky]\nstar_field = 2000000"));
    assert!(message.contains("sky.star_field"), "{message}");
    let message = value_error(&scene("[sky]\nstar_field = 10\nsaturation_magnitude = nan"));
    assert!(message.contains("sky.saturation_magnitude"), "{message}");
    let error = parse(&scene("[render]\ncolour = \"rainbow\""))
        .unwrap_err()
        .to_string();
    assert!(error.contains("unknown surface colour"), "{error}");
    // Valid values build, and reach the scene.
    let (built, _) = build(&scene(
        "[render]\ncolour = \"spectral\"\nexposure = 0.5\n[sky]\nstar_field = 7",
    ))
    .unwrap();
    assert_eq!(built.exposure, 0.5);
    assert_eq!(built.sky.stars.len(), 7);
}

/// A minimal scene with one unit cube and the `light` tables `lights`.
fn with_lights(lights: &str) -> String {
    format!(
        "[observer]\nposition = [0.0, -5.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\n{lights}\n\
         [[object]]\nshape = {{ type = \"cube\" }}\n"
    )
}

#[test]
fn light_lists_build_a_carried_lamp_and_moving_lights() {
    let (scene, _) = build(&with_lights(
        "[[light]]\nposition = [0.0, -5.0, 2.0]\nstrength = 0.5\ncarried = true\n\
         [[light]]\nposition = [1.0, 2.0, 3.0]\nbeta = [0.5, 0.0, 0.0]\ntemperature_k = 4000.0\n\
         strength = 9.0\n",
    ))
    .unwrap();
    assert_eq!(scene.light.strength, 0.5);
    assert_eq!(scene.light.position, DVec3::new(0.0, -5.0, 2.0));
    assert_eq!(scene.lights.len(), 1);
    assert_eq!(scene.lights[0].frame.beta(), DVec3::new(0.5, 0.0, 0.0));
    assert_eq!(scene.lights[0].frame.offset(), DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(
        (scene.lights[0].temperature_k, scene.lights[0].strength),
        (4000.0, 9.0)
    );
    // A list without a carried entry has no lamp.
    let (scene, _) = build(&with_lights("[[light]]\nposition = [1.0, 2.0, 3.0]\n")).unwrap();
    assert_eq!(scene.light.strength, 0.0);
    assert_eq!(scene.lights.len(), 1);
}

#[test]
fn bad_lights_are_refused_naming_the_key() {
    let lamp_moves = value_error(&with_lights(
        "[light]\nposition = [0.0, 0.0, 1.0]\nbeta = [0.1, 0.0, 0.0]\n",
    ));
    assert!(
        lamp_moves.contains("light.beta") && lamp_moves.contains("[[light]]"),
        "{lamp_moves}"
    );
    let fast = value_error(&with_lights(
        "[[light]]\nposition = [0.0, 0.0, 1.0]\nbeta = [1.0, 0.0, 0.0]\n",
    ));
    assert!(fast.contains("light[0].beta"), "{fast}");
    let negative = value_error(&with_lights(
        "[[light]]\nposition = [0.0, 0.0, 1.0]\nstrength = -1.0\n",
    ));
    assert!(negative.contains("light[0].strength"), "{negative}");
    let two_lamps = value_error(&with_lights(
        "[[light]]\nposition = [0.0, 0.0, 1.0]\ncarried = true\n[[light]]\nposition = [0.0, 0.0, 2.0]\ncarried = true\n",
    ));
    assert!(two_lamps.contains("at most one"), "{two_lamps}");
    let many: String = (0..9)
        .map(|i| format!("[[light]]\nposition = [{i}.0, 0.0, 1.0]\n"))
        .collect();
    let too_many = value_error(&with_lights(&many));
    assert!(
        too_many.contains("at most 8 moving lights, got 9"),
        "{too_many}"
    );
    let unknown = build(&with_lights(
        "[[light]]\nposition = [0.0, 0.0, 1.0]\ncolour = 1\n",
    ))
    .unwrap_err();
    assert!(unknown.to_string().contains("colour"), "{unknown}");
}

#[test]
fn bad_motions_are_refused_naming_the_object_and_the_point() {
    // Whether a point is too fast or beyond the horizon depends on the built mesh: the build
    // refuses it.
    let build_error = |text: &str| build(text).unwrap_err().to_string();
    let fast = build_error(&with_object(
        "spin = { axis = [0.0, 0.0, 1.0], rate = 2.0 }",
    ));
    assert!(
        fast.contains("spin.rate of object \"probe\"") && fast.contains("speed of light"),
        "{fast}"
    );
    let zero = value_error(&with_object(
        "spin = { axis = [0.0, 0.0, 0.0], rate = 0.5 }",
    ));
    assert!(
        zero.contains("spin of object \"probe\"") && zero.contains("zero vector"),
        "{zero}"
    );
    let horizon = build_error(&with_object(
        "thrust = { proper_acceleration = [0.0, 3.0, 0.0] }",
    ));
    assert!(horizon.contains("Rindler horizon"), "{horizon}");
    let both = value_error(&with_object(
        "spin = { axis = [0.0, 0.0, 1.0], rate = 0.5 }\nthrust = { proper_acceleration = [0.0, 0.1, 0.0] }",
    ));
    assert!(both.contains("not both"), "{both}");
    let backwards = value_error(&with_object(
        "thrust = { proper_acceleration = [0.0, 0.1, 0.0], duration = -1.0 }",
    ));
    assert!(backwards.contains("duration"), "{backwards}");
    // A thrust without end is written `inf`, and round-trips.
    let text = with_object("thrust = { proper_acceleration = [0.0, 0.1, 0.0], duration = inf }");
    let description = parse(&text).unwrap();
    let again = parse(&description.to_toml_string()).unwrap();
    assert_eq!(description, again);
}

//! Hostile and careless input (issue 8): absurd but finite sizes, resolutions and node graphs
//! that would allocate gigabytes or hang, devices and FIFOs where files are expected, image
//! headers that promise billions of texels, and parser messages that used to be megabytes long,
//! multi-line, or full of raw bytes and Rust debug output.
//!
//! Every case must be refused (or, for textures, warned about) quickly, with a message of one
//! bounded line that names the file or the key — and without allocating what it asked for.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use srt_scene::import::{MAX_JSON_OBJECTS, load_model, load_model_within};
use srt_scene::limits::{Budget, MAX_SCENE_TRIANGLES};
use srt_scene::message::MAX_MESSAGE_CHARS;
use srt_scene::textures::decode_image;
use srt_scene::{SceneDescription, load_scene_file};

/// A fresh temporary folder, removed when dropped.
fn temp() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary folder")
}

/// Writes `contents` to `dir/name` and returns the path.
fn write(dir: &Path, name: &str, contents: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, contents).expect("writing a test file");
    path
}

/// Checks that `message` is one printable line of bounded length that mentions `needle`.
fn assert_readable(message: &str, needle: &str) {
    assert!(
        message.chars().count() <= MAX_MESSAGE_CHARS,
        "{} characters: {message}",
        message.chars().count()
    );
    assert!(
        !message.chars().any(char::is_control),
        "control characters in: {message:?}"
    );
    assert!(message.contains(needle), "{needle:?} not in: {message}");
}

/// The error message of loading the model at `path`, which must fail; checks it is readable and
/// names the file.
fn model_error(path: &Path) -> String {
    let message = match load_model(path) {
        Ok(model) => panic!(
            "{} should fail, but loaded {} triangles",
            path.display(),
            model.triangle_count()
        ),
        Err(e) => e.to_string(),
    };
    assert_readable(&message, &path.file_name().unwrap().to_string_lossy());
    message
}

/// The error message of building the scene file `text` (written to `dir/scene.toml`), which must
/// fail; checks it is readable and names the file.
fn scene_error(dir: &Path, text: &str) -> String {
    let path = write(dir, "scene.toml", text);
    let message = match load_scene_file(&path) {
        Ok(_) => panic!("the scene should fail:\n{text}"),
        Err(e) => e.to_string(),
    };
    assert_readable(&message, "scene.toml");
    message
}

/// The warnings of building the scene file `text` (written to `dir/scene.toml`), which must load.
fn scene_warnings(dir: &Path, text: &str) -> Vec<String> {
    let path = write(dir, "scene.toml", text);
    match load_scene_file(&path) {
        Ok((_, _, warnings)) => warnings,
        Err(e) => panic!("the scene should load: {e}\n{text}"),
    }
}

/// A scene file with one object table whose body is `object`.
fn scene_with(object: &str) -> String {
    format!(
        "[observer]\nposition = [0.0, -5.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\n[[object]]\n\
         name = \"probe\"\n{object}\n"
    )
}

// ------------------------------------------------------------------------------------------------
// Absurd but finite geometry
// ------------------------------------------------------------------------------------------------

#[test]
fn absurd_sizes_and_scales_are_refused_naming_the_key() {
    let dir = temp();
    for (object, key) in [
        (
            "shape = { type = \"cube\", size = 1e300 }",
            "shape.size of object \"probe\"",
        ),
        (
            "shape = { type = \"sphere\", radius = 1e300 }",
            "shape.radius",
        ),
        (
            "shape = { type = \"cube\" }\nscale = 1e300",
            "scale of object \"probe\"",
        ),
        (
            "shape = { type = \"cube\" }\nscale = [1.0, 1e300, 1.0]",
            "scale",
        ),
        (
            "shape = { type = \"cube\" }\ntranslate = [0.0, 0.0, 1e300]",
            "translate",
        ),
        (
            "shape = { type = \"cube\" }\noffset = [-1e300, 0.0, 0.0]",
            "offset",
        ),
        (
            "shape = { type = \"cube\" }\nwireframe = 1e300",
            "wireframe",
        ),
    ] {
        let message = scene_error(dir.path(), &scene_with(object));
        assert_readable(&message, key);
        assert!(message.contains("1e9"), "the bound is not given: {message}");
    }
    let message = scene_error(
        dir.path(),
        "[observer]\nposition = [0.0, -5.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nct = 1e300\n",
    );
    assert_readable(&message, "observer.ct");
}

#[test]
fn placed_geometry_beyond_the_bound_is_refused_naming_the_object() {
    let dir = temp();
    // Each value is fine alone; together they put the cube's far face beyond 1e9.
    let message = scene_error(
        dir.path(),
        &scene_with("shape = { type = \"cube\", size = 2.0 }\ntranslate = [1e9, 0.0, 0.0]"),
    );
    assert_readable(
        &message,
        "object \"probe\" reaches 1.000000001e9 scene units",
    );

    // A model whose coordinates are finite in f32 but absurd, as they are and scaled.
    write(
        dir.path(),
        "huge.stl",
        "solid huge\nfacet normal 0 0 1\nouter loop\nvertex 3e38 0 0\nvertex 0 3e38 0\n\
         vertex 0 0 0\nendloop\nendfacet\nendsolid huge\n",
    );
    for extra in ["", "scale = 10.0"] {
        let message = scene_error(
            dir.path(),
            &scene_with(&format!(
                "shape = {{ type = \"model\", path = \"huge.stl\" }}\n{extra}"
            )),
        );
        assert_readable(&message, "object \"probe\" reaches");
        assert!(message.contains("±1e9"), "{message}");
    }
    // Fitted, the same model is usable.
    let warnings = scene_warnings(
        dir.path(),
        &scene_with("shape = { type = \"model\", path = \"huge.stl\" }\nfit = true"),
    );
    assert!(warnings.is_empty(), "{warnings:?}");
}

// ------------------------------------------------------------------------------------------------
// Allocation budgets
// ------------------------------------------------------------------------------------------------

#[test]
fn shape_resolutions_beyond_the_triangle_budget_are_refused_before_building() {
    let dir = temp();
    let message = scene_error(
        dir.path(),
        &scene_with("shape = { type = \"cube\", subdivisions = 1000 }"),
    );
    assert_readable(
        &message,
        "shape.subdivisions of object \"probe\" must be in 1..=400",
    );
    assert!(message.contains("12000000 triangles"), "{message}");
    let message = scene_error(
        dir.path(),
        &scene_with("shape = { type = \"sphere\", segments = 100000 }"),
    );
    assert_readable(&message, "shape.segments");
    assert!(message.contains("2000000"), "{message}");
    // Found by the fuzz campaign: the count in the message overflowed.
    for shape in [
        "cube\", subdivisions = 4294967295",
        "sphere\", segments = 4294967295",
    ] {
        let message = scene_error(
            dir.path(),
            &scene_with(&format!("shape = {{ type = \"{shape} }}")),
        );
        assert!(
            message.contains("got 4294967295 (which would make 1844674"),
            "{message}"
        );
    }
}

#[test]
fn the_triangle_budget_is_one_per_scene() {
    let dir = temp();
    // Two cubes of 1.08 million triangles each: the second does not fit.
    let object = "shape = { type = \"cube\", subdivisions = 300 }";
    let text = format!(
        "{}\n[[object]]\nname = \"second\"\n{object}\n",
        scene_with(object)
    );
    let message = scene_error(dir.path(), &text);
    assert_readable(
        &message,
        "shape.subdivisions of object \"second\" makes the scene too large",
    );
    assert!(message.contains("1080000 already loaded"), "{message}");
}

/// A glTF document with one triangle (in `tri.bin`, written next to it) as mesh 0, the given
/// nodes and scene roots.
fn gltf_with_nodes(dir: &Path, name: &str, nodes: &str, roots: &str) -> PathBuf {
    let triangle: Vec<u8> = [0.0_f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    write(dir, "tri.bin", triangle);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},
"buffers":[{{"uri":"tri.bin","byteLength":36}}],
"bufferViews":[{{"buffer":0,"byteLength":36}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
"nodes":[{nodes}],
"scenes":[{{"nodes":[{roots}]}}],"scene":0}}"#
    );
    write(dir, name, json)
}

/// `count` nodes, node i listing node i + 1 twice; the last has a mesh if `mesh`.
fn doubling_chain(count: usize, mesh: bool) -> String {
    let mut nodes = String::new();
    for i in 0..count {
        let _ = write!(nodes, "{{\"children\":[{0},{0}]}},", i + 1);
    }
    nodes.push_str(if mesh { "{\"mesh\":0}" } else { "{}" });
    nodes
}

#[test]
fn a_deep_shared_node_graph_is_counted_not_walked() {
    let dir = temp();
    // 2^64 paths to a mesh-less leaf, next to one triangle: loads at once.
    let nodes = format!("{},{{\"mesh\":0}}", doubling_chain(64, false));
    let path = gltf_with_nodes(dir.path(), "dag.gltf", &nodes, "0,65");
    let model = load_model(&path).unwrap();
    assert_eq!(model.triangle_count(), 1);
    // The same graph with the triangle at its leaf instances it 2^64 times: refused by count.
    let path = gltf_with_nodes(dir.path(), "bomb.gltf", &doubling_chain(64, true), "0");
    let message = model_error(&path);
    assert!(message.contains("the model is too large"), "{message}");
}

#[test]
fn a_position_attribute_naming_a_missing_accessor_is_an_error() {
    // Found by the fuzz campaign: the gltf crate's validation indexed out of bounds on it.
    let dir = temp();
    let path = gltf_with_nodes(dir.path(), "missing.gltf", "{\"mesh\":0}", "0");
    let json = std::fs::read_to_string(&path)
        .unwrap()
        .replace("\"POSITION\":0", "\"POSITION\":2147483648");
    let path = write(dir.path(), "missing.gltf", json);
    let message = model_error(&path);
    assert!(
        message.contains("POSITION names accessor 2147483648, but there are only 1"),
        "{message}"
    );
}

#[test]
fn a_node_cycle_is_refused() {
    let dir = temp();
    let path = gltf_with_nodes(
        dir.path(),
        "cycle.gltf",
        "{\"children\":[1]},{\"children\":[0],\"mesh\":0}",
        "0",
    );
    let message = model_error(&path);
    assert!(message.contains("has a cycle"), "{message}");
}

#[test]
fn one_mesh_instanced_millions_of_times_is_refused_before_instancing() {
    let dir = temp();
    // 2000 × 2000 = 4 million instances of one triangle through two levels of nodes.
    let many = |child: usize| vec![child.to_string(); 2000].join(",");
    let nodes = format!(
        "{{\"children\":[{}]}},{{\"children\":[{}]}},{{\"mesh\":0}}",
        many(1),
        many(2)
    );
    let path = gltf_with_nodes(dir.path(), "instances.gltf", &nodes, "0");
    let message = model_error(&path);
    assert!(message.contains("it would have 4000000 parts"), "{message}");
}

#[test]
fn instanced_triangles_beyond_the_budget_are_refused() {
    let dir = temp();
    // A mesh of 100 000 (degenerate) triangles, 300 000 byte indices all 0, instanced 30 times.
    let mut buffer = vec![0u8; 36 + 300_000];
    buffer[12..16].copy_from_slice(&1.0_f32.to_le_bytes());
    write(dir.path(), "heavy.bin", buffer);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},
"buffers":[{{"uri":"heavy.bin","byteLength":300036}}],
"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":300000}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,0,0]}},
  {{"bufferView":1,"componentType":5121,"count":300000,"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"nodes":[{{"children":[{}]}},{{"mesh":0}}],
"scenes":[{{"nodes":[0]}}],"scene":0}}"#,
        vec!["1"; 30].join(",")
    );
    let path = write(dir.path(), "heavy.gltf", json);
    let message = model_error(&path);
    assert!(
        message.contains("it would have 3000000 triangles"),
        "{message}"
    );
}

#[test]
fn gltf_json_with_too_many_objects_is_refused_before_parsing() {
    let dir = temp();
    let nodes = vec!["{}"; MAX_JSON_OBJECTS + 1].join(",");
    let path = gltf_with_nodes(dir.path(), "objects.gltf", &nodes, "0");
    let message = model_error(&path);
    assert!(message.contains("objects, more than the"), "{message}");
}

#[test]
fn ply_counts_are_checked_against_the_budget_and_the_file() {
    let dir = temp();
    let header = |vertices: u64, faces: u64| {
        format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {vertices}\nproperty float x\n\
             element face {faces}\nproperty list uchar int vertex_indices\nend_header\n"
        )
    };
    let path = write(dir.path(), "many.ply", header(10_000_000, 1));
    let message = model_error(&path);
    assert!(message.contains("10000000 vertices"), "{message}");
    let path = write(dir.path(), "faces.ply", header(3, 3_000_000));
    let message = model_error(&path);
    assert!(message.contains("3000000 faces"), "{message}");
}

#[test]
fn every_loader_charges_the_budget_before_building() {
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    for name in [
        "cube.obj",
        "cube_ascii.ply",
        "cube_binary_le.ply",
        "cube_ascii.stl",
        "cube_binary.stl",
        "cube.gltf",
        "cube.glb",
    ] {
        let path = fixtures.join(name);
        assert!(
            load_model_within(&path, &mut Budget::new()).is_ok(),
            "{name}"
        );
        let mut nearly_full = Budget::new();
        nearly_full
            .charge_mesh(MAX_SCENE_TRIANGLES as u64 - 5, 0)
            .unwrap();
        let message = load_model_within(&path, &mut nearly_full)
            .unwrap_err()
            .to_string();
        assert_readable(&message, "the model is too large: it would have");
        assert!(message.contains("already loaded"), "{name}: {message}");
        assert_eq!(nearly_full.triangles(), MAX_SCENE_TRIANGLES - 5, "{name}");
    }
}

#[test]
fn oversized_scene_files_are_refused_by_size() {
    let dir = temp();
    let text = format!(
        "{}{}",
        scene_with("shape = { type = \"cube\" }"),
        "# padding\n".repeat(120_000)
    );
    let message = scene_error(dir.path(), &text);
    assert!(
        message.contains("more than the 1048576 bytes a scene file may have"),
        "{message}"
    );
}

// ------------------------------------------------------------------------------------------------
// Images
// ------------------------------------------------------------------------------------------------

/// CRC-32 (IEEE) as PNG chunks use it.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A PNG whose header claims `width` × `height` RGBA texels, with an empty image data chunk.
fn png_claiming(width: u32, height: u32) -> Vec<u8> {
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = b"IHDR".to_vec();
    chunk.extend_from_slice(&width.to_be_bytes());
    chunk.extend_from_slice(&height.to_be_bytes());
    chunk.extend_from_slice(&[8, 6, 0, 0, 0]);
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&chunk);
    png.extend_from_slice(&crc32(&chunk).to_be_bytes());
    for name in [b"IDAT", b"IEND"] {
        png.extend_from_slice(&0u32.to_be_bytes());
        png.extend_from_slice(name);
        png.extend_from_slice(&crc32(name).to_be_bytes());
    }
    png
}

#[test]
fn image_headers_claiming_huge_sizes_are_refused_before_decoding() {
    let mut budget = Budget::new();
    let error =
        decode_image(&png_claiming(65_535, 65_535), None, "bomb.png", &mut budget).unwrap_err();
    assert!(
        error.contains("65535 × 65535 texels, more than 16384 per side"),
        "{error}"
    );
    let error =
        decode_image(&png_claiming(16_000, 16_000), None, "big.png", &mut budget).unwrap_err();
    assert!(error.contains("256000000 texels"), "{error}");
    assert_eq!(budget, Budget::new(), "a refused image is not charged");

    // In a scene, a texture that cannot be loaded is a warning naming it, not an error.
    let dir = temp();
    write(dir.path(), "bomb.png", png_claiming(65_535, 65_535));
    let warnings = scene_warnings(
        dir.path(),
        &scene_with("shape = { type = \"cube\" }\ntexture = \"bomb.png\""),
    );
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_readable(
        &warnings[0],
        "texture \"bomb.png\" cannot be loaded (the image is 65535 × 65535",
    );
}

// ------------------------------------------------------------------------------------------------
// Devices, FIFOs and folders where files are expected
// ------------------------------------------------------------------------------------------------

#[cfg(unix)]
mod devices {
    use super::*;

    const DEVICE: &str = "it is a character device, not a regular file";

    /// One triangle as OBJ text, with `header` before it.
    fn obj(header: &str) -> String {
        format!("{header}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    }

    /// Loads the model at `path`, which must load; returns its warnings.
    fn warnings_of(path: &Path) -> Vec<String> {
        match load_model(path) {
            Ok(model) => model.warnings,
            Err(e) => panic!("{} should load: {e}", path.display()),
        }
    }

    fn assert_warned(warnings: &[String], needle: &str) {
        assert!(
            warnings
                .iter()
                .any(|w| w.contains(needle) && w.contains(DEVICE)),
            "no warning about {needle} being a device: {warnings:?}"
        );
    }

    #[test]
    fn a_model_or_scene_file_that_is_a_device_is_refused() {
        let dir = temp();
        let link = dir.path().join("zero.stl");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        let message = model_error(&link);
        assert!(message.contains(DEVICE), "{message}");

        let error = load_scene_file(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert_readable(
            &error,
            "/dev/zero: cannot read the scene file: it is a character device",
        );

        let message = scene_error(
            dir.path(),
            &scene_with("shape = { type = \"model\", path = \"zero.stl\" }"),
        );
        assert!(message.contains(DEVICE), "{message}");
    }

    #[test]
    fn a_gltf_buffer_that_is_a_device_is_an_error() {
        let dir = temp();
        let json = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"/dev/zero","byteLength":36}],
            "bufferViews":[{"buffer":0,"byteLength":36}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}]}"#;
        let path = write(dir.path(), "buffer.gltf", json);
        let message = model_error(&path);
        assert!(message.contains("buffer 0 (\"/dev/zero\")"), "{message}");
        assert!(message.contains(DEVICE), "{message}");
    }

    #[test]
    fn textures_and_material_libraries_that_are_devices_are_warnings() {
        let dir = temp();
        // A glTF image.
        let path = gltf_with_nodes(dir.path(), "image.gltf", "{\"mesh\":0}", "0");
        let json = std::fs::read_to_string(&path).unwrap().replace(
            r#""attributes":{"POSITION":0}"#,
            r#""attributes":{"POSITION":0},"material":0"#,
        );
        let json = json.replacen(
            "\"asset\"",
            r#""images":[{"uri":"/dev/zero"}],"textures":[{"source":0}],
               "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"asset""#,
            1,
        );
        let path = write(dir.path(), "image.gltf", json);
        assert_warned(&warnings_of(&path), "/dev/zero");

        // An OBJ material library.
        let path = write(dir.path(), "mtllib.obj", obj("mtllib /dev/zero"));
        assert_warned(&warnings_of(&path), "material library \"/dev/zero\"");

        // An MTL diffuse texture.
        write(
            dir.path(),
            "zero.mtl",
            "newmtl red\nKd 1 0 0\nmap_Kd /dev/zero\n",
        );
        let path = write(dir.path(), "map.obj", obj("mtllib zero.mtl\nusemtl red"));
        assert_warned(
            &warnings_of(&path),
            "texture \"/dev/zero\" of material \"red\"",
        );

        // A PLY texture comment.
        let ply = "ply\nformat ascii 1.0\ncomment TextureFile /dev/zero\nelement vertex 3\n\
                   property float x\nproperty float y\nproperty float z\nelement face 1\n\
                   property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n\
                   3 0 1 2\n";
        let path = write(dir.path(), "texture.ply", ply);
        assert_warned(&warnings_of(&path), "/dev/zero");

        // A scene file's texture.
        let warnings = scene_warnings(
            dir.path(),
            &scene_with("shape = { type = \"cube\" }\ntexture = \"/dev/zero\""),
        );
        assert_warned(&warnings, "texture \"/dev/zero\"");
    }

    #[test]
    fn fifos_and_folders_are_refused_without_blocking() {
        let dir = temp();
        let folder = dir.path().join("folder.obj");
        std::fs::create_dir(&folder).unwrap();
        let message = model_error(&folder);
        assert!(message.contains("it is a folder, not a file"), "{message}");

        let fifo = dir.path().join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|status| status.success()) {
            use std::io::Write as _;
            let _ = writeln!(
                std::io::stderr(),
                "SKIPPED the FIFO case: mkfifo is not available"
            );
            return;
        }
        // Opening a FIFO would block until a writer comes: the check happens before.
        let message = model_error(&fifo);
        assert!(
            message.contains("it is a FIFO (named pipe), not a regular file"),
            "{message}"
        );
    }
}

// ------------------------------------------------------------------------------------------------
// Messages a person can read
// ------------------------------------------------------------------------------------------------

#[test]
fn a_long_ascii_stl_line_gives_a_short_message_with_the_line() {
    let dir = temp();
    let text = format!("solid x\nfacet normal {}\n", "1 ".repeat(250_000));
    let path = write(dir.path(), "long.stl", text);
    let message = model_error(&path);
    assert!(
        message.contains("line 2: three numbers expected, found more"),
        "{message}"
    );
}

#[test]
fn raw_bytes_of_a_binary_stl_header_are_not_printed() {
    let dir = temp();
    // A binary STL whose header starts with "solid" (as many exporters write), cut short.
    let mut bytes = b"solid \x00\x01\x1b[31m\x7f\xff\xfe".to_vec();
    bytes.resize(84, 0);
    bytes[80..84].copy_from_slice(&12u32.to_le_bytes());
    bytes.extend((0..=255u8).cycle().take(500));
    let path = write(dir.path(), "binary.stl", bytes);
    let message = model_error(&path);
    assert!(
        message.contains(
            "the binary header declares 12 facets (684 bytes), but the file has only 584 bytes"
        ),
        "{message}"
    );
    // Text with control characters is escaped where it is quoted.
    let path = write(
        dir.path(),
        "text.stl",
        "solid x\nfacet \x1b[31mnormal 0 0 1\n",
    );
    let message = model_error(&path);
    assert!(message.contains("line 2: expected"), "{message}");
    assert!(message.contains("\\x1b[31m"), "{message}");
}

#[test]
fn ply_errors_are_one_line_without_debug_output() {
    let dir = temp();
    for (name, text) in [
        (
            "property.ply",
            "ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n0\n",
        ),
        (
            "value.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\nseven\n",
        ),
        (
            "type.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nend_header\n1.5\n",
        ),
        ("magic.ply", "plx\nformat ascii 1.0\nend_header\n"),
        (
            "statement.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float\nend_header\n",
        ),
    ] {
        let path = write(dir.path(), name, text);
        let message = model_error(&path);
        assert!(
            !message.contains(['{', '}']) && !message.contains("Scalar("),
            "debug output in: {message}"
        );
    }
    let message = model_error(&dir.path().join("value.ply"));
    assert!(
        message.contains("line 6: the data line \"seven\" is not a list of numbers"),
        "{message}"
    );
    let message = model_error(&dir.path().join("type.ply"));
    assert!(
        message.contains("line 6: \"1.5\" is not a number of the type the header declares"),
        "{message}"
    );
}

#[test]
fn obj_errors_name_the_line() {
    let dir = temp();
    let path = write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv 1 0 0\n\nv 0 one 0\nf 1 2 3\n",
    );
    let message = model_error(&path);
    assert!(
        message.contains("line 4 (\"v 0 one 0\"): a vertex position"),
        "{message}"
    );
    let path = write(
        dir.path(),
        "index.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nf 1 2 9\no c\n",
    );
    let message = model_error(&path);
    assert!(message.contains("line 6 (\"f 1 2 9\")"), "{message}");
}

#[test]
fn long_names_and_values_give_bounded_messages() {
    let dir = temp();
    let name = "n".repeat(5000);
    let text = format!(
        "[observer]\nposition = [0.0, -5.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\n[[object]]\n\
         name = \"{name}\"\nshape = {{ type = \"cube\", size = -1.0 }}\n"
    );
    let message = scene_error(dir.path(), &text);
    assert!(message.ends_with('…'), "{message}");
    // A description built in memory names the scene instead of a file.
    let description = SceneDescription::from_toml_str(&text, "memory").unwrap();
    let message = description.build(dir.path()).unwrap_err().to_string();
    assert_readable(&message, "scene: shape.size of object \"nnn");
}

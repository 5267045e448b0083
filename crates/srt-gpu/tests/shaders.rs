//! Every WGSL shader srt builds ([`srt_gpu::shaders::all`]) parses and validates with naga, so a
//! shader error fails `cargo test` with naga's annotated message rather than at pipeline creation.

use naga::valid::{Capabilities, ValidationFlags, Validator};

/// Parses and validates `source`, returning naga's rendered error on failure.
fn validate(name: &str, source: &str) -> Result<naga::valid::ModuleInfo, String> {
    let path = format!("{name}.wgsl (composed)");
    let module = naga::front::wgsl::parse_str(source).map_err(|e| {
        format!(
            "parse error:\n{}",
            e.emit_to_string_with_path(source, &path)
        )
    })?;
    Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .map_err(|e| {
            format!(
                "validation error:\n{}",
                e.emit_to_string_with_path(source, &path)
            )
        })
}

#[test]
fn every_shader_parses_and_validates() {
    let shaders = srt_gpu::shaders::all();
    assert!(!shaders.is_empty(), "shaders::all() lists no shader");
    let mut failures = Vec::new();
    for shader in &shaders {
        let name = &shader.name;
        match validate(name, &shader.source) {
            Ok(_) => println!("{name}: ok ({} lines)", shader.source.lines().count()),
            Err(message) => failures.push(format!("{name}: {message}")),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} shaders failed:\n\n{}",
        failures.len(),
        shaders.len(),
        failures.join("\n\n")
    );
}

#[test]
fn shader_names_are_unique() {
    let shaders = srt_gpu::shaders::all();
    let mut names: Vec<&str> = shaders.iter().map(|shader| shader.name.as_str()).collect();
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(names.len(), before, "duplicate names in shaders::all()");
}

#[test]
fn a_broken_shader_is_reported_with_its_location() {
    // Guards the test above against passing vacuously: naga must reject this and say where.
    let message = validate("broken", "fn f() -> f32 { return vec2<f32>(1.0); }").unwrap_err();
    assert!(message.contains("broken.wgsl"), "{message}");
}

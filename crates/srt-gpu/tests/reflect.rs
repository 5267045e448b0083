//! Values that Rust and WGSL share are checked against what naga reflects from the composed
//! shaders, without a GPU:
//!
//! - the named codes and flag bits of `srt_gpu::types` equal the WGSL `const`s of the same
//!   meaning, and every WGSL const of those families has a Rust twin;
//! - every WGSL `override` gets its value from Rust (`Shader::overrides`, nothing more, nothing
//!   less) and is used: `WORKGROUP_SIZE` is the workgroup size of every compute entry point;
//! - every binding of every pipeline (`pipelines::specs`, `probe::specs`) matches the WGSL
//!   global of its name in `@group`, `@binding`, kind and stages, and every resource an entry
//!   point uses has a binding.

use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};
use naga::{AddressSpace, Expression, ImageClass, ImageDimension, Literal, Module, TypeInner};
use srt_gpu::motion::MotionCode;
use srt_gpu::pipelines::{BindGroupSpec, PipelineSpec, Slot};
use srt_gpu::shaders::{self, ObjectVariant, Shader, WORKGROUP_SIZE};
use srt_gpu::types::{
    BVH_STACK_SIZE, DRAW_ARGS_BOUND, DRAW_ARGS_FOOTPRINT_VERTICES, DRAW_ARGS_PIECES_TAKEN,
    DRAW_ARGS_SHADE_VERTICES, DRAW_ARGS_WORDS, EffectsCode, FOOTPRINT_HULL_LEN,
    FOOTPRINT_HULL_POINTS, FOOTPRINT_PIECES_OVERFLOWED, FOOTPRINT_VERTICES, FOOTPRINT_WHOLE_SCREEN,
    FootprintCode, MAX_MOVING_LIGHTS, OutputCode, PartFlags, ProjectionCode, SHADOW_NODE_ROWS,
    SHADOW_OBJECT_ROWS, SHADOW_TRIANGLE_ROWS, SurfaceColourCode, ToneMapCode,
};

/// Every WGSL const with a Rust twin, and the twin's value.
fn shared_consts() -> Vec<(&'static str, u32)> {
    vec![
        ("EFFECTS_GEOMETRY", EffectsCode::GEOMETRY.0),
        ("EFFECTS_DOPPLER", EffectsCode::DOPPLER.0),
        ("EFFECTS_SEARCHLIGHT", EffectsCode::SEARCHLIGHT.0),
        ("SURFACE_COLOUR_PAPER", SurfaceColourCode::PAPER.0),
        ("SURFACE_COLOUR_SPECTRAL", SurfaceColourCode::SPECTRAL.0),
        ("TONE_MAP_LUMINANCE", ToneMapCode::LUMINANCE.0),
        ("TONE_MAP_SEARCHLIGHT", ToneMapCode::SEARCHLIGHT.0),
        ("FOOTPRINT_HULL", FootprintCode::HULL.0),
        ("FOOTPRINT_RECTANGLE", FootprintCode::RECTANGLE.0),
        ("PART_TEXTURED", PartFlags::TEXTURED.0),
        ("PART_VERTEX_COLOURS", PartFlags::VERTEX_COLOURS.0),
        ("PART_CULL_BACK_FACES", PartFlags::CULL_BACK_FACES.0),
        ("PART_ENCLOSING_BOX", PartFlags::ENCLOSING_BOX.0),
        ("FOOTPRINT_HULL_POINTS", FOOTPRINT_HULL_POINTS as u32),
        ("FOOTPRINT_VERTICES", FOOTPRINT_VERTICES),
        ("FOOTPRINT_HULL_LEN", FOOTPRINT_HULL_LEN),
        ("FOOTPRINT_WHOLE_SCREEN", FOOTPRINT_WHOLE_SCREEN),
        ("FOOTPRINT_PIECES_OVERFLOWED", FOOTPRINT_PIECES_OVERFLOWED),
        ("BVH_STACK_SIZE", BVH_STACK_SIZE),
        ("MAX_SPLIT_DEPTH", srt_proxy::MAX_SPLIT_DEPTH),
        ("DRAW_ARGS_FOOTPRINT_VERTICES", DRAW_ARGS_FOOTPRINT_VERTICES),
        ("DRAW_ARGS_SHADE_VERTICES", DRAW_ARGS_SHADE_VERTICES),
        ("DRAW_ARGS_PIECES_TAKEN", DRAW_ARGS_PIECES_TAKEN),
        ("DRAW_ARGS_BOUND", DRAW_ARGS_BOUND),
        ("DRAW_ARGS_WORDS", DRAW_ARGS_WORDS),
        ("OUTPUT_DISPLAY", OutputCode::DISPLAY.0),
        ("OUTPUT_RADIANCE", OutputCode::RADIANCE.0),
        ("OUTPUT_SEEN_EVENT", OutputCode::SEEN_EVENT.0),
        ("OUTPUT_SEEN_OBJECT", OutputCode::SEEN_OBJECT.0),
        ("PROJECTION_PERSPECTIVE", ProjectionCode::PERSPECTIVE.0),
        (
            "PROJECTION_EQUIRECTANGULAR",
            ProjectionCode::EQUIRECTANGULAR.0,
        ),
        ("PROJECTION_FISHEYE", ProjectionCode::FISHEYE.0),
        (
            "STAR_LIGHT_WORDS_PER_PIXEL",
            srt_gpu::sky::STAR_LIGHT_WORDS_PER_PIXEL,
        ),
        ("MAX_MOVING_LIGHTS", MAX_MOVING_LIGHTS as u32),
        ("SHADOW_OBJECT_ROWS", SHADOW_OBJECT_ROWS),
        ("SHADOW_NODE_ROWS", SHADOW_NODE_ROWS),
        ("SHADOW_TRIANGLE_ROWS", SHADOW_TRIANGLE_ROWS),
        ("MOTION_REST", MotionCode::REST.0),
        ("MOTION_SPIN", MotionCode::SPIN.0),
        ("MOTION_THRUST", MotionCode::THRUST.0),
        ("MOTION_MAX_PIECES", srt_gpu::motion::MAX_PIECES),
        ("MOTION_CROSSING_STEPS", srt_gpu::motion::CROSSING_STEPS),
        ("MOTION_NEWTON_STEPS", srt_gpu::motion::NEWTON_STEPS),
        ("MOTION_PIECES_PER_GROUP", srt_gpu::motion::PIECES_PER_GROUP),
        (
            "SPECTRAL_HEADER_WORDS",
            srt_gpu::spectral::SPECTRAL_HEADER_WORDS as u32,
        ),
    ]
}

/// Name prefixes of WGSL consts that must all have a Rust twin.
const SHARED_FAMILIES: [&str; 14] = [
    "BVH_",
    "MOTION_",
    "DRAW_ARGS_",
    "EFFECTS_",
    "FOOTPRINT_",
    "MAX_MOVING_LIGHTS",
    "OUTPUT_",
    "PART_",
    "PROJECTION_",
    "SHADOW_",
    "SPECTRAL_HEADER_",
    "STAR_LIGHT_WORDS_",
    "SURFACE_COLOUR_",
    "TONE_MAP_",
];

fn parse(name: &str, source: &str) -> (Module, ModuleInfo) {
    let module = naga::front::wgsl::parse_str(source).unwrap_or_else(|e| {
        panic!(
            "{name} does not parse (see tests/shaders.rs):\n{}",
            e.emit_to_string(source)
        )
    });
    let info = Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name} does not validate: {}", e.emit_to_string(source)));
    (module, info)
}

/// The value of every named `u32` const of `module`.
fn u32_consts(module: &Module) -> Result<Vec<(String, u32)>, String> {
    module
        .constants
        .iter()
        .filter_map(|(_, c)| c.name.clone().map(|name| (name, c.init)))
        .filter_map(|(name, init)| match module.global_expressions[init] {
            Expression::Literal(Literal::U32(value)) => Some(Ok((name, value))),
            // Other scalars and vectors (e.g. GREY_WEIGHTS, checked on its own) are not u32s.
            Expression::Literal(_) | Expression::Compose { .. } => None,
            ref other => Some(Err(format!("const {name} is not a literal: {other:?}"))),
        })
        .collect()
}

/// Differences between `table` and the u32 consts of `module` (named `shader`); `seen` collects
/// the names found.
fn check_consts(
    shader: &str,
    module: &Module,
    table: &[(&str, u32)],
    seen: &mut Vec<String>,
) -> Vec<String> {
    let consts = match u32_consts(module) {
        Ok(consts) => consts,
        Err(e) => return vec![format!("{shader}: {e}")],
    };
    let mut failures = Vec::new();
    for (name, wgsl) in &consts {
        match table.iter().find(|(rust_name, _)| rust_name == name) {
            Some((_, rust)) if rust == wgsl => seen.push(name.clone()),
            Some((_, rust)) => {
                failures.push(format!("{shader}: WGSL {name} = {wgsl}, Rust says {rust}"));
            }
            None if SHARED_FAMILIES.iter().any(|p| name.starts_with(p)) => failures.push(format!(
                "{shader}: WGSL const {name} has no Rust twin in tests/reflect.rs"
            )),
            None => {}
        }
    }
    failures
}

#[test]
fn shared_consts_equal_their_rust_twins() {
    let table = shared_consts();
    let mut failures = Vec::new();
    let mut seen = Vec::new();
    for shader in shaders::all() {
        let (module, _) = parse(&shader.name, &shader.source);
        failures.extend(check_consts(&shader.name, &module, &table, &mut seen));
        // The hull array of the Footprint struct is as long as the const says.
        if let Some((_, ty)) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some("Footprint"))
        {
            let TypeInner::Struct { members, .. } = &ty.inner else {
                panic!("Footprint is not a struct");
            };
            let hull = members
                .iter()
                .find(|m| m.name.as_deref() == Some("hull"))
                .unwrap();
            let TypeInner::Array { size, .. } = module.types[hull.ty].inner else {
                panic!("Footprint.hull is not an array");
            };
            assert_eq!(
                size,
                naga::ArraySize::Constant(
                    std::num::NonZeroU32::new(FOOTPRINT_HULL_POINTS as u32).unwrap()
                ),
                "{}: Footprint.hull",
                shader.name
            );
        }
    }
    for (name, _) in &table {
        if !seen.iter().any(|s| s == name) {
            failures.push(format!("no shader defines WGSL const {name}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(
        FOOTPRINT_VERTICES as usize,
        3 * (FOOTPRINT_HULL_POINTS - 2),
        "the fan of the LRT pass covers the largest hull"
    );
}

/// The literal elements of `module`'s vector or array const `name`, if it has one; an error if
/// the const is not a composition of literals.
fn literal_const(module: &Module, name: &str) -> Option<Result<Vec<Literal>, String>> {
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))?;
    let Expression::Compose { components, .. } = &module.global_expressions[constant.init] else {
        return Some(Err(format!("const {name} is not a vector or an array")));
    };
    Some(
        components
            .iter()
            .map(|&c| match module.global_expressions[c] {
                Expression::Literal(value) => Ok(value),
                ref other => Err(format!("const {name} has an element {other:?}")),
            })
            .collect(),
    )
}

/// The components of `module`'s `f32` vector const `name` ([`literal_const`]).
fn f32_vector_const(module: &Module, name: &str) -> Option<Result<Vec<f32>, String>> {
    literal_const(module, name).map(|literals| {
        literals?
            .into_iter()
            .map(|l| match l {
                Literal::F32(value) => Ok(value),
                other => Err(format!("const {name} has a component {other:?}")),
            })
            .collect()
    })
}

/// The elements of `module`'s `u32` array const `name` ([`literal_const`]).
fn u32_array_const(module: &Module, name: &str) -> Option<Result<Vec<u32>, String>> {
    literal_const(module, name).map(|literals| {
        literals?
            .into_iter()
            .map(|l| match l {
                Literal::U32(value) => Ok(value),
                other => Err(format!("const {name} has an element {other:?}")),
            })
            .collect()
    })
}

/// The clock face's geometry and digit patterns in clock.wgsl are srt-trace's (in f32), in every
/// shader that draws it.
#[test]
fn the_clock_face_equals_the_reference() {
    use srt_trace::clock::{CLOCK_DIAL, CLOCK_DIGITS, CLOCK_HANDS, CLOCK_SEGMENTS, CLOCK_STROKES};
    let vectors = [
        ("CLOCK_DIAL", CLOCK_DIAL),
        ("CLOCK_HANDS", CLOCK_HANDS),
        ("CLOCK_DIGITS", CLOCK_DIGITS),
        ("CLOCK_STROKES", CLOCK_STROKES),
    ];
    let mut found = 0;
    for shader in shaders::all() {
        let (module, _) = parse(&shader.name, &shader.source);
        let Some(segments) = u32_array_const(&module, "CLOCK_SEGMENTS") else {
            continue;
        };
        assert_eq!(segments, Ok(CLOCK_SEGMENTS.to_vec()), "{}", shader.name);
        for (name, reference) in vectors {
            let expected = reference.map(|v| v as f32).to_vec();
            assert_eq!(
                f32_vector_const(&module, name),
                Some(Ok(expected)),
                "{name} in {}",
                shader.name
            );
        }
        found += 1;
    }
    assert!(found >= 2, "the LRT and polygon shaders draw clocks");
}

/// The grey value's weights (Eq. 18) in colour.wgsl are the reference's, in f32.
#[test]
fn grey_weights_equal_the_reference() {
    let reference = srt_trace::GREY_WEIGHTS.map(|w| w as f32).to_vec();
    let mut found = 0;
    for shader in shaders::all() {
        let (module, _) = parse(&shader.name, &shader.source);
        if let Some(weights) = f32_vector_const(&module, "GREY_WEIGHTS") {
            assert_eq!(weights, Ok(reference.clone()), "{}", shader.name);
            found += 1;
        }
    }
    assert!(found > 0, "no shader defines GREY_WEIGHTS");
}

#[test]
fn a_const_mismatch_is_detected() {
    // Guards the comparison against passing vacuously.
    let (module, _) = parse(
        "test",
        "const PART_TEXTURED: u32 = 1u; const PART_NEW: u32 = 8u; const OTHER: u32 = 3u;",
    );
    let mut seen = Vec::new();
    let failures = check_consts("test", &module, &[("PART_TEXTURED", 2)], &mut seen);
    assert_eq!(failures.len(), 2, "{failures:?}");
    assert!(failures[0].contains("Rust says 2"), "{failures:?}");
    assert!(failures[1].contains("PART_NEW"), "{failures:?}");
}

/// The name of the override an expression of `module` refers to, if it is one.
fn override_name(module: &Module, expression: &Expression) -> Option<String> {
    match expression {
        Expression::Override(handle) => module.overrides[*handle].name.clone(),
        _ => None,
    }
}

/// Names of the overrides referenced by any function's code or any workgroup size.
fn used_overrides(module: &Module) -> Vec<String> {
    let functions = module
        .functions
        .iter()
        .map(|(_, f)| f)
        .chain(module.entry_points.iter().map(|e| &e.function));
    let mut used: Vec<String> = functions
        .flat_map(|f| f.expressions.iter().map(|(_, e)| e))
        .filter_map(|e| override_name(module, e))
        .collect();
    used.extend(
        module
            .entry_points
            .iter()
            .filter_map(|e| e.workgroup_size_overrides)
            .flatten()
            .flatten()
            .filter_map(|h| override_name(module, &module.global_expressions[h])),
    );
    used.sort();
    used.dedup();
    used
}

/// Differences between the overrides `shader` declares and uses and the values Rust gives it.
fn check_overrides(shader: &Shader, module: &Module) -> Vec<String> {
    let mut failures = Vec::new();
    let declared: Vec<String> = module
        .overrides
        .iter()
        .filter_map(|(_, o)| o.name.clone())
        .collect();
    let used = used_overrides(module);
    for name in &declared {
        if !shader.overrides.iter().any(|(rust, _)| rust == name) {
            failures.push(format!(
                "{}: override {name} gets no value from Rust",
                shader.name
            ));
        }
        if !used.contains(name) {
            failures.push(format!("{}: override {name} is never used", shader.name));
        }
    }
    for (rust, _) in &shader.overrides {
        if !declared.iter().any(|name| name == rust) {
            failures.push(format!(
                "{}: Rust sets {rust}, which the shader does not declare",
                shader.name
            ));
        }
    }
    for entry in &module.entry_points {
        if entry.stage != naga::ShaderStage::Compute {
            continue;
        }
        let size = entry.workgroup_size_overrides.map(|[x, y, z]| {
            (
                x.and_then(|h| override_name(module, &module.global_expressions[h])),
                y.is_none() && z.is_none(),
            )
        });
        if size != Some((Some("WORKGROUP_SIZE".to_owned()), true)) {
            failures.push(format!(
                "{}: entry point {} has workgroup size {:?} / {:?}, not (WORKGROUP_SIZE, 1, 1)",
                shader.name, entry.name, entry.workgroup_size, entry.workgroup_size_overrides
            ));
        }
    }
    failures
}

#[test]
fn overrides_get_their_values_from_rust_and_are_used() {
    let mut failures = Vec::new();
    let mut compute_shaders = 0;
    for shader in shaders::all() {
        let (module, _) = parse(&shader.name, &shader.source);
        failures.extend(check_overrides(&shader, &module));
        if module
            .entry_points
            .iter()
            .any(|e| e.stage == naga::ShaderStage::Compute)
        {
            compute_shaders += 1;
            let value = shader
                .overrides
                .iter()
                .find(|(name, _)| *name == "WORKGROUP_SIZE")
                .map(|(_, v)| *v);
            assert_eq!(value, Some(f64::from(WORKGROUP_SIZE)), "{}", shader.name);
        }
        println!("{}: overrides {:?}", shader.name, shader.overrides);
    }
    assert_eq!(compute_shaders, 3, "proxy, probe and sky");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn an_override_without_a_rust_value_or_use_is_detected() {
    let source = "override A: u32; override B: f32; \
                  @compute @workgroup_size(8) fn main() { let x = A; }";
    let (module, _) = parse("test", source);
    let shader = Shader {
        name: "test".into(),
        source: source.to_owned(),
        overrides: vec![("A", 1.0), ("C", 2.0)],
    };
    let failures = check_overrides(&shader, &module);
    let expected = [
        "override B gets no value",
        "override B is never used",
        "Rust sets C",
        "not (WORKGROUP_SIZE, 1, 1)",
    ];
    assert_eq!(failures.len(), expected.len(), "{failures:?}");
    for (failure, text) in failures.iter().zip(expected) {
        assert!(failure.contains(text), "{failure}");
    }
}

/// The wgpu stage of a naga entry point.
fn stage(stage: naga::ShaderStage) -> wgpu::ShaderStages {
    match stage {
        naga::ShaderStage::Vertex => wgpu::ShaderStages::VERTEX,
        naga::ShaderStage::Fragment => wgpu::ShaderStages::FRAGMENT,
        naga::ShaderStage::Compute => wgpu::ShaderStages::COMPUTE,
        other => panic!("unexpected stage {other:?}"),
    }
}

/// Whether the WGSL global `var` of `module` is what `ty` binds.
fn kind_matches(module: &Module, var: &naga::GlobalVariable, ty: &wgpu::BindingType) -> bool {
    let inner = &module.types[var.ty].inner;
    match ty {
        wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            ..
        } => var.space == AddressSpace::Uniform,
        wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            ..
        } => matches!(var.space, AddressSpace::Storage { access }
            if access.contains(naga::StorageAccess::STORE) != *read_only),
        wgpu::BindingType::Texture {
            sample_type,
            view_dimension:
                view_dimension @ (wgpu::TextureViewDimension::D2 | wgpu::TextureViewDimension::D2Array),
            multisampled,
        } => {
            let expected_arrayed = *view_dimension == wgpu::TextureViewDimension::D2Array;
            let expected_kind = match sample_type {
                wgpu::TextureSampleType::Float { .. } => naga::ScalarKind::Float,
                wgpu::TextureSampleType::Uint => naga::ScalarKind::Uint,
                wgpu::TextureSampleType::Sint => naga::ScalarKind::Sint,
                wgpu::TextureSampleType::Depth => return false,
            };
            matches!(inner, TypeInner::Image {
                dim: ImageDimension::D2,
                arrayed,
                class: ImageClass::Sampled { kind, multi },
            } if *kind == expected_kind && multi == multisampled && *arrayed == expected_arrayed)
        }
        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering) => {
            matches!(inner, TypeInner::Sampler { comparison: false })
        }
        _ => false,
    }
}

/// Differences between `spec`'s bindings and the WGSL of its shader.
fn check_bindings(spec: &PipelineSpec) -> Vec<String> {
    let label = spec.label;
    let (module, info) = parse(label, &spec.shader.source);
    let mut failures = Vec::new();
    let entries: Vec<(usize, &naga::EntryPoint)> = module
        .entry_points
        .iter()
        .enumerate()
        .filter(|(_, e)| spec.entry_points.contains(&e.name.as_str()))
        .collect();
    if entries.len() != spec.entry_points.len() {
        failures.push(format!(
            "{label}: entry points {:?} not all in the shader",
            spec.entry_points
        ));
    }
    let slot_at = |group: u32, binding: u32| -> Option<(&BindGroupSpec, &Slot)> {
        spec.groups.iter().find(|g| g.index == group).and_then(|g| {
            g.slots
                .iter()
                .find(|s| s.binding == binding)
                .map(|s| (g, s))
        })
    };
    for (position, group) in spec.groups.iter().enumerate() {
        if group.index as usize != position {
            failures.push(format!(
                "{label}: group {:?} has index {} but is layout position {position}",
                group.label, group.index
            ));
        }
        for slot in group.slots {
            let Some((handle, var)) = module
                .global_variables
                .iter()
                .find(|(_, v)| v.name.as_deref() == Some(slot.wgsl_name))
            else {
                failures.push(format!("{label}: no WGSL global {}", slot.wgsl_name));
                continue;
            };
            let wanted = naga::ResourceBinding {
                group: group.index,
                binding: slot.binding,
            };
            if var.binding != Some(wanted) {
                failures.push(format!(
                    "{label}: {} is at {:?} in WGSL, Rust binds it at {wanted:?}",
                    slot.wgsl_name, var.binding
                ));
            }
            if !kind_matches(&module, var, &slot.ty) {
                failures.push(format!(
                    "{label}: {} is {:?} {:?} in WGSL, Rust binds {:?}",
                    slot.wgsl_name, var.space, module.types[var.ty].inner, slot.ty
                ));
            }
            for (index, entry) in &entries {
                let used = !info.get_entry_point(*index)[handle].is_empty();
                if used && !slot.visibility.contains(stage(entry.stage)) {
                    failures.push(format!(
                        "{label}: {} is used by {} but visible to {:?} only",
                        slot.wgsl_name, entry.name, slot.visibility
                    ));
                }
            }
        }
    }
    // Every resource an entry point uses is bound.
    for (handle, var) in module.global_variables.iter() {
        let Some(binding) = var.binding else {
            continue;
        };
        let used = entries
            .iter()
            .any(|(index, _)| !info.get_entry_point(*index)[handle].is_empty());
        let name = var.name.as_deref().unwrap_or("?");
        match slot_at(binding.group, binding.binding) {
            Some((_, slot)) if slot.wgsl_name == name => {}
            Some((_, slot)) => failures.push(format!(
                "{label}: WGSL {name} at {binding:?}, Rust binds {} there",
                slot.wgsl_name
            )),
            None if used => failures.push(format!(
                "{label}: WGSL {name} at {binding:?} is used but Rust binds nothing there"
            )),
            None => {}
        }
    }
    failures
}

/// The renderer's six pipelines and the image-based method's two in variants that between
/// them compile every piece of code ([`ObjectVariant::covering`]).
fn renderer_specs() -> Vec<PipelineSpec> {
    ObjectVariant::covering()
        .into_iter()
        .flat_map(|variant| {
            let [face, lookup] = srt_gpu::pipelines::image_based_specs(variant);
            [
                Vec::from(srt_gpu::pipelines::specs(variant)),
                vec![face, lookup],
            ]
            .concat()
        })
        .collect()
}

fn all_specs() -> Vec<PipelineSpec> {
    let mut specs = renderer_specs();
    specs.extend(srt_gpu::probe::specs());
    specs.extend(srt_gpu::pipelines::sky_specs());
    specs.push(srt_gpu::display::spec());
    specs
}

#[test]
fn bindings_match_the_wgsl() {
    let specs = all_specs();
    assert_eq!(
        specs.len(),
        8 * ObjectVariant::covering().len() + 6,
        "proxy, lrt visibility, lrt shading, rt visibility, polygon, lrt part depth, the \
         image-based faces and look-up (once per covering ObjectVariant), three probes, the \
         sky's two passes and the display pass"
    );
    let mut failures = Vec::new();
    for spec in &specs {
        failures.extend(check_bindings(spec));
        println!(
            "{}: {} groups, {} bindings checked",
            spec.label,
            spec.groups.len(),
            spec.groups.iter().map(|g| g.slots.len()).sum::<usize>()
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_binding_mismatch_is_detected() {
    // Guards the comparison against passing vacuously: move the LRT's fragment counter to
    // binding 7, make its footprints writable and hide them from the vertex stage.
    let mut lrt = srt_gpu::pipelines::specs(ObjectVariant {
        counting: true,
        ..ObjectVariant::PLAIN
    })[1]
        .clone();
    let mut group = lrt.groups[3];
    let mut slots = group.slots.to_vec();
    slots[0].ty = srt_gpu::pipelines::storage(false);
    slots[0].visibility = wgpu::ShaderStages::FRAGMENT;
    slots[1].binding = 7;
    group.slots = Vec::leak(slots);
    lrt.groups[3] = group;
    let failures = check_bindings(&lrt);
    let joined = failures.join("\n");
    for text in [
        "fragment_count is at Some(ResourceBinding { group: 3, binding: 1 })",
        "footprints is Storage",
        "footprints is used by lrt_vertex but visible to",
        "fragment_count at ResourceBinding { group: 3, binding: 1 } is used but Rust binds nothing",
    ] {
        assert!(joined.contains(text), "missing {text:?} in:\n{joined}");
    }
}

/// Storage buffers that `spec`'s layout makes visible to `stage` (what wgpu counts against
/// `max_storage_buffers_per_shader_stage`).
fn storage_buffers(spec: &PipelineSpec, stage: wgpu::ShaderStages) -> usize {
    spec.groups
        .iter()
        .flat_map(|g| g.slots)
        .filter(|s| s.visibility.contains(stage))
        .filter(|s| {
            matches!(
                s.ty,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { .. },
                    ..
                }
            )
        })
        .count()
}

#[test]
fn render_passes_bind_no_uniform_buffer_and_fit_the_storage_limits() {
    // Lavapipe (Mesa 22.3) recompiles a shader at every bind while a uniform buffer decides one
    // of its branches (render_bindings.wgsl); so the render passes read storage buffers only,
    // at most WebGPU's default of 8 per stage, which `device_descriptor` asks for.
    let limit = wgpu::Limits::default().max_storage_buffers_per_shader_stage as usize;
    let mut render = renderer_specs();
    render.extend(srt_gpu::pipelines::sky_specs());
    render.push(srt_gpu::display::spec());
    let mut failures = Vec::new();
    let mut most = 0;
    for spec in &render {
        for slot in spec.groups.iter().flat_map(|g| g.slots) {
            if matches!(
                slot.ty,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    ..
                }
            ) {
                failures.push(format!(
                    "{}: {} is a uniform buffer",
                    spec.label, slot.wgsl_name
                ));
            }
        }
        for stage in [
            wgpu::ShaderStages::VERTEX,
            wgpu::ShaderStages::FRAGMENT,
            wgpu::ShaderStages::COMPUTE,
        ] {
            let count = storage_buffers(spec, stage);
            most = most.max(count);
            if count > limit {
                failures.push(format!(
                    "{}: {count} storage buffers for {stage:?}, more than {limit}",
                    spec.label
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(
        most, limit,
        "the shading pass binds 8 storage buffers per stage"
    );
}

#[test]
fn blocks_declared_as_uniforms_for_gl_match_their_layouts() {
    // On the GL backend the render passes' blocks are uniform buffers (BlockSpace): the WGSL
    // declared that way must still match the layouts made in that space, and every render
    // pass must have had a block to declare.
    let space = shaders::BlockSpace::Uniform;
    let mut render = renderer_specs();
    render.extend(srt_gpu::pipelines::sky_specs());
    let mut failures = Vec::new();
    for spec in render {
        let mut gl = spec.clone();
        gl.shader.source = space.declare(&spec.shader.source);
        if gl.shader.source == spec.shader.source {
            failures.push(format!("{}: no block declared as a uniform", spec.label));
        }
        for group in &mut gl.groups {
            let slots: Vec<Slot> = group
                .slots
                .iter()
                .map(|slot| Slot {
                    ty: space.binding_type(slot.wgsl_name, slot.ty),
                    ..*slot
                })
                .collect();
            group.slots = Vec::leak(slots);
        }
        failures.extend(check_bindings(&gl));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn only_the_visibility_fragments_declare_their_depth_at_least_the_footprints() {
    // Where the device allows it (ConservativeDepth::Declared), the visibility passes' fragment
    // entry points, and no other, promise the GPU a depth at or behind the rasterised one (the
    // footprint's nearest_depth), so that it may test depth before running them.
    let greater = Some(naga::EarlyDepthTest::Allow {
        conservative: naga::ConservativeDepth::GreaterEqual,
    });
    let mut declared = Vec::new();
    let mut failures = Vec::new();
    for spec in all_specs() {
        let source = shaders::ConservativeDepth::Declared.declare(&spec.shader.source);
        let module = naga::front::wgsl::parse_str(&source)
            .unwrap_or_else(|e| panic!("{}: {}", spec.label, e.emit_to_string(&source)));
        Validator::new(ValidationFlags::all(), Capabilities::EARLY_DEPTH_TEST)
            .validate(&module)
            .unwrap_or_else(|e| panic!("{}: {}", spec.label, e.emit_to_string(&source)));
        let undeclared = shaders::ConservativeDepth::Undeclared.declare(&spec.shader.source);
        assert_eq!(undeclared, spec.shader.source, "{}", spec.label);
        for entry in &module.entry_points {
            let visibility = shaders::VISIBILITY_FRAGMENT_ENTRIES.contains(&entry.name.as_str());
            let expected = if visibility { greater } else { None };
            if entry.early_depth_test != expected {
                failures.push(format!(
                    "{}: {} has {:?}",
                    spec.label, entry.name, entry.early_depth_test
                ));
            }
            if visibility && spec.entry_points.contains(&entry.name.as_str()) {
                declared.push(entry.name.clone());
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    declared.sort_unstable();
    declared.dedup();
    let mut expected = shaders::VISIBILITY_FRAGMENT_ENTRIES
        .map(str::to_owned)
        .to_vec();
    expected.sort_unstable();
    assert_eq!(
        declared, expected,
        "every visibility fragment is some pipeline's"
    );
}

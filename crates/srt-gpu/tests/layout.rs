//! The `#[repr(C)]` twins in `srt_gpu::types` have exactly the memory layout
//! naga computes for their WGSL structs: size, and every member's name, offset, size and scalar
//! type, in every composed shader that defines the struct.
//!
//! Adding a struct is one line in [`table`].

use std::mem::{offset_of, size_of};

use naga::proc::Layouter;
use naga::{Module, ScalarKind, TypeInner};
use srt_gpu::types::{
    EffectsCode, FootprintCode, FrameUniforms, GpuBvhNode, GpuFootprint, GpuFrame, GpuMovingLight,
    GpuPhysicsProbeInput, GpuPhysicsProbeOutput, GpuRtTriangle, GpuShadowObject,
    GpuSpectralProbeInput, GpuSpectralProbeOutput, GpuStar, GpuVertex, LightUniforms,
    ObjectUniforms, OutputCode, PartFlags, PartUniforms, ProjectionCode, SkyUniforms,
    SurfaceColourCode, ToneMapCode,
};

/// What a member's components are, as both sides can tell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Leaf {
    F32,
    U32,
    I32,
    /// A nested struct, by its WGSL name.
    Struct(&'static str),
}

/// The leaf type of a Rust field.
trait HasLeaf {
    const LEAF: Leaf;
}

impl HasLeaf for f32 {
    const LEAF: Leaf = Leaf::F32;
}
impl HasLeaf for u32 {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for i32 {
    const LEAF: Leaf = Leaf::I32;
}
impl<T: HasLeaf, const N: usize> HasLeaf for [T; N] {
    const LEAF: Leaf = T::LEAF;
}
// The named codes and flags are u32 on the GPU.
impl HasLeaf for EffectsCode {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for FootprintCode {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for SurfaceColourCode {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for ToneMapCode {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for OutputCode {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for ProjectionCode {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for PartFlags {
    const LEAF: Leaf = Leaf::U32;
}
impl HasLeaf for GpuFrame {
    const LEAF: Leaf = Leaf::Struct("Frame");
}
impl HasLeaf for GpuMovingLight {
    const LEAF: Leaf = Leaf::Struct("MovingLight");
}
impl HasLeaf for LightUniforms {
    const LEAF: Leaf = Leaf::Struct("LightUniforms");
}

/// One member as the Rust side lays it out.
#[derive(Debug, PartialEq, Eq)]
struct Member {
    name: &'static str,
    offset: usize,
    size: usize,
    leaf: Leaf,
}

/// A Rust struct's layout, to compare with the WGSL struct `wgsl`.
struct Twin {
    rust: &'static str,
    wgsl: &'static str,
    size: usize,
    members: Vec<Member>,
}

fn field<T, F: HasLeaf>(_: fn(&T) -> &F) -> (usize, Leaf) {
    (size_of::<F>(), F::LEAF)
}

/// `twin!(RustType => "WgslName" { field, … })`: the Rust layout of the listed fields, which
/// must be all of them, in WGSL member order, with the WGSL member names.
macro_rules! twin {
    ($ty:ty => $wgsl:literal { $($field:ident),+ $(,)? }) => {
        Twin {
            rust: stringify!($ty),
            wgsl: $wgsl,
            size: size_of::<$ty>(),
            members: vec![$({
                let (size, leaf) = field(|v: &$ty| &v.$field);
                Member { name: stringify!($field), offset: offset_of!($ty, $field), size, leaf }
            }),+],
        }
    };
}

/// Every GPU struct and its WGSL twin.
fn table() -> Vec<Twin> {
    vec![
        twin!(GpuFrame => "Frame" { rest_to_observer, observer_to_rest, beta_gamma, offset, observer_rest }),
        twin!(FrameUniforms => "FrameUniforms" { view_projection, camera_forward, camera_right, camera_up, observer, light, shading, background, lut, viewport, picture, effects, footprint_shape, depth_scale, colour, tone_map, exposure, searchlight_ln_y, output, projection, fisheye_half_fov, eye_separation, projection_padding, radiance, lights }),
        twin!(ObjectUniforms => "ObjectUniforms" { frame, style, optics, time, world_time, blink, clock, clock_face, clock_ink, motion, motion_axis, motion_centre, motion_low, motion_high, view_bound }),
        twin!(PartUniforms => "PartUniforms" { base_color, flags, triangle_count, id, frames, frame_height, frame_rate, padding }),
        twin!(GpuVertex => "Vertex" { position, normal, color, uv }),
        twin!(GpuFootprint => "Footprint" { hull, triangle, nearest_depth, flags, padding }),
        twin!(GpuBvhNode => "BvhNode" { min, primitive_count, max, first }),
        twin!(GpuRtTriangle => "RtTriangle" { p0, part, p1, triangle, p2, padding }),
        twin!(GpuMovingLight => "MovingLight" { offset_temperature, beta_gamma, strength }),
        twin!(LightUniforms => "LightUniforms" { lamp, counts, moving }),
        twin!(GpuShadowObject => "ShadowObject" { observer_to_rest, offset, bvh }),
        twin!(GpuStar => "Star" { direction_temperature, magnitude }),
        twin!(SkyUniforms => "SkyUniforms" { beta_saturation, counts, direction_map, direction_unmap, image, supersampling }),
        twin!(GpuPhysicsProbeInput => "PhysicsProbeInput" { frame, event, rest_event, point, direction, view, propagation, direction_rest, incident, outgoing }),
        twin!(GpuPhysicsProbeOutput => "PhysicsProbeOutput" { to_observer, to_rest, emission_event, apparent_position, apparent_tangent, aberrate, ray_origin, ray_direction, scalars }),
        twin!(GpuSpectralProbeInput => "SpectralProbeInput" { rgb_temperature, factors, bands }),
        twin!(GpuSpectralProbeOutput => "SpectralProbeOutput" { reflected, emitted }),
    ]
}

/// The leaf type of a WGSL type, or a description of why it has none we can compare.
fn wgsl_leaf(module: &Module, ty: naga::Handle<naga::Type>) -> Result<Leaf, String> {
    let inner = &module.types[ty].inner;
    let scalar = match inner {
        TypeInner::Scalar(s)
        | TypeInner::Vector { scalar: s, .. }
        | TypeInner::Matrix { scalar: s, .. } => *s,
        TypeInner::Array { base, .. } => return wgsl_leaf(module, *base),
        TypeInner::Struct { .. } => {
            let name = module.types[ty].name.clone().unwrap_or_default();
            return Ok(Leaf::Struct(name.leak()));
        }
        other => return Err(format!("{other:?}")),
    };
    match (scalar.kind, scalar.width) {
        (ScalarKind::Float, 4) => Ok(Leaf::F32),
        (ScalarKind::Uint, 4) => Ok(Leaf::U32),
        (ScalarKind::Sint, 4) => Ok(Leaf::I32),
        other => Err(format!("{other:?}")),
    }
}

/// The WGSL layout of struct `name` in `module`, if it defines one, as (size, members).
fn wgsl_layout(module: &Module, layouter: &Layouter, name: &str) -> Option<(usize, Vec<Member>)> {
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))?;
    let TypeInner::Struct { members, span } = &ty.inner else {
        panic!("WGSL type {name} is not a struct: {:?}", ty.inner);
    };
    let size = layouter[handle].size as usize;
    assert_eq!(
        size, *span as usize,
        "naga's layouter and struct span disagree for {name}"
    );
    let members = members
        .iter()
        .map(|m| Member {
            name: m.name.clone().unwrap_or_default().leak(),
            offset: m.offset as usize,
            size: layouter[m.ty].size as usize,
            leaf: wgsl_leaf(module, m.ty)
                .unwrap_or_else(|e| panic!("{name}.{:?}: unsupported type {e}", m.name)),
        })
        .collect();
    Some((size, members))
}

#[test]
fn rust_twins_match_naga_layouts() {
    let shaders: Vec<(String, Module, Layouter)> = srt_gpu::shaders::all()
        .into_iter()
        .map(|srt_gpu::shaders::Shader { name, source, .. }| {
            let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| {
                panic!(
                    "{name} does not parse (see tests/shaders.rs):\n{}",
                    e.emit_to_string(&source)
                )
            });
            let mut layouter = Layouter::default();
            layouter
                .update(module.to_ctx())
                .unwrap_or_else(|e| panic!("{name}: layout failed: {e:?}"));
            (name, module, layouter)
        })
        .collect();
    let mut failures = Vec::new();
    for twin in table() {
        let mut found_in = Vec::new();
        for (shader, module, layouter) in &shaders {
            let Some((size, members)) = wgsl_layout(module, layouter, twin.wgsl) else {
                continue;
            };
            found_in.push(shader.as_str());
            if size != twin.size {
                failures.push(format!(
                    "{} is {} bytes but WGSL {} in shader {shader} is {size}",
                    twin.rust, twin.size, twin.wgsl
                ));
            }
            if members != twin.members {
                let rows = |ms: &[Member]| {
                    ms.iter()
                        .map(|m| {
                            format!(
                                "    {:<20} offset {:>4} size {:>4} {:?}",
                                m.name, m.offset, m.size, m.leaf
                            )
                        })
                        .collect::<Vec<_>>()
                        .join("\n")
                };
                failures.push(format!(
                    "{} and WGSL {} (shader {shader}) differ.\n  Rust:\n{}\n  WGSL:\n{}",
                    twin.rust,
                    twin.wgsl,
                    rows(&twin.members),
                    rows(&members)
                ));
            }
        }
        if found_in.is_empty() {
            failures.push(format!(
                "no shader in shaders::all() defines WGSL struct {} (twin of {})",
                twin.wgsl, twin.rust
            ));
        } else {
            println!(
                "{} ↔ {}: {} bytes, {} members, checked in {}",
                twin.rust,
                twin.wgsl,
                twin.size,
                twin.members.len(),
                found_in.join(", ")
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// Buffers the renderer sizes in Rust have the size of their WGSL globals: the fragment counter,
/// the frame's screen bound and the indirect draw arguments with the part's bound (in every
/// shader that declares them).
#[test]
fn buffers_sized_in_rust_match_their_wgsl_globals() {
    let expected = [
        ("fragment_count", srt_gpu::types::FRAGMENT_COUNTER_BYTES),
        ("frame_bound", srt_gpu::types::FRAME_BOUND_BYTES),
        ("draw_args", srt_gpu::types::DRAW_ARGS_BYTES),
        ("part_draw_args", srt_gpu::types::DRAW_ARGS_BYTES),
    ];
    let draw = size_of::<wgpu::util::DrawIndirectArgs>() as u64;
    assert_eq!(srt_gpu::types::SHADE_DRAW_OFFSET, draw);
    // Two draws, the piece counter, then the part's bound.
    assert_eq!(srt_gpu::types::DRAW_ARGS_BYTES, 2 * draw + 4 + 16);
    assert_eq!(4 * u64::from(srt_gpu::types::DRAW_ARGS_BOUND), 2 * draw + 4);
    for (name, bytes) in expected {
        let mut declared_in = Vec::new();
        for shader in srt_gpu::shaders::all() {
            let module = naga::front::wgsl::parse_str(&shader.source).expect("shaders parse");
            let mut layouter = Layouter::default();
            layouter.update(module.to_ctx()).expect("layout");
            let found = module
                .global_variables
                .iter()
                .find(|(_, g)| g.name.as_deref() == Some(name));
            if let Some((_, global)) = found {
                assert_eq!(
                    u64::from(layouter[global.ty].size),
                    bytes,
                    "{name} in {}",
                    shader.name
                );
                declared_in.push(shader.name);
            }
        }
        assert!(!declared_in.is_empty(), "no shader declares {name}");
        println!("{name}: {bytes} bytes in {}", declared_in.join(", "));
    }
}

#[test]
fn a_layout_mismatch_is_detected() {
    // Guards the comparison against passing vacuously: vec3 + f32 packs into 16 bytes in WGSL,
    // and a Rust struct that puts the f32 at 16 must be reported.
    let module =
        naga::front::wgsl::parse_str("struct S { a: vec3<f32>, b: f32, c: vec2<u32> }").unwrap();
    let mut layouter = Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (size, members) = wgsl_layout(&module, &layouter, "S").unwrap();
    assert_eq!(size, 32, "rounded up to the 16-byte alignment of vec3");
    assert_eq!(
        members[1],
        Member {
            name: "b",
            offset: 12,
            size: 4,
            leaf: Leaf::F32
        }
    );
    assert_eq!(
        members[2],
        Member {
            name: "c",
            offset: 16,
            size: 8,
            leaf: Leaf::U32
        }
    );
    assert_ne!(
        members[1],
        Member {
            name: "b",
            offset: 16,
            size: 4,
            leaf: Leaf::F32
        }
    );
}

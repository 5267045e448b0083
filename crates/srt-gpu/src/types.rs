//! GPU data layouts: `#[repr(C)]` bytemuck twins of the structs in `shaders/types.wgsl` and
//! `shaders/physics.wgsl`, defined once here. `tests/layout.rs` checks every field's offset and
//! size against naga's layout of the WGSL struct.

use bytemuck::{Pod, Zeroable};
use glam::{DMat4, DVec3};
use srt_physics::{Event, Frame};

/// Converts an f64 matrix to the column-major f32 array WGSL expects.
#[must_use]
pub fn mat4(m: DMat4) -> [[f32; 4]; 4] {
    m.to_cols_array_2d().map(|c| c.map(|v| v as f32))
}

/// `vec4<f32>` from three f64 components and a fourth.
#[must_use]
pub fn vec4(v: DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// Twin of WGSL `Frame` (physics.wgsl): an object's rest frame for one observation event.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuFrame {
    /// Λ_β.
    pub rest_to_observer: [[f32; 4]; 4],
    /// Λ_−β.
    pub observer_to_rest: [[f32; 4]; 4],
    /// β and γ.
    pub beta_gamma: [f32; 4],
    /// Offset **a**, 0.
    pub offset: [f32; 4],
    /// Observation event in S′ (ct′, x′, y′, z′), computed in f64.
    pub observer_rest: [f32; 4],
}

impl GpuFrame {
    /// The frame prepared for observation event `observer`.
    #[must_use]
    pub fn new(frame: &Frame, observer: Event) -> Self {
        let rest = frame.to_rest(observer);
        Self {
            rest_to_observer: mat4(frame.rest_to_observer_matrix()),
            observer_to_rest: mat4(frame.observer_to_rest_matrix()),
            beta_gamma: vec4(frame.beta(), frame.gamma()),
            offset: vec4(frame.offset(), 0.0),
            observer_rest: [
                rest.ct as f32,
                rest.position.x as f32,
                rest.position.y as f32,
                rest.position.z as f32,
            ],
        }
    }
}

/// Twin of WGSL `FrameUniforms`: per-image parameters.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct FrameUniforms {
    /// S → clip space.
    pub view_projection: [[f32; 4]; 4],
    /// Unit camera forward, w = 0.
    pub camera_forward: [f32; 4],
    /// Camera right × tan(fov/2) × aspect.
    pub camera_right: [f32; 4],
    /// Camera up × tan(fov/2).
    pub camera_up: [f32; 4],
    /// Observer position (xyz) and ct_obs (w).
    pub observer: [f32; 4],
    /// Light position (xyz) and temperature in kelvin (w).
    pub light: [f32; 4],
    /// Ambient, diffuse, specular, shininess.
    pub shading: [f32; 4],
    /// Background colour.
    pub background: [f32; 4],
    /// ln T_min, ln T_max, texel count, unused.
    pub lut: [f32; 4],
    /// Width, height, 1/width, 1/height.
    pub viewport: [f32; 4],
    /// Effects, footprint shape, unused, unused.
    pub modes: [u32; 4],
    /// Depth scale (x).
    pub depth_scale: [f32; 4],
}

/// Twin of WGSL `ObjectUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ObjectUniforms {
    /// The rest frame.
    pub frame: GpuFrame,
    /// Wireframe width (x, ≤ 0 for none).
    pub style: [f32; 4],
}

/// Twin of WGSL `PartUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct PartUniforms {
    /// Base colour factor.
    pub base_color: [f32; 4],
    /// Has texture, has vertex colours, triangle count, cull back faces (closed solid, observer
    /// outside it).
    pub flags: [u32; 4],
}

/// Twin of WGSL `Vertex`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuVertex {
    /// Position in S′ (w = 1).
    pub position: [f32; 4],
    /// Unit normal in S′ (w = 0).
    pub normal: [f32; 4],
    /// Vertex colour (1 when the mesh has none).
    pub color: [f32; 4],
    /// Texture coordinates (xy).
    pub uv: [f32; 4],
}

/// Twin of WGSL `Footprint`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuFootprint {
    /// Hull points in pixels.
    pub hull: [[f32; 2]; 6],
    /// Rectangle min x, min y, max x, max y.
    pub rect: [f32; 4],
    /// Valid hull points.
    pub hull_len: u32,
    /// 1 for a whole-screen footprint.
    pub whole_screen: u32,
    /// Padding to the WGSL size.
    pub padding: [u32; 2],
}

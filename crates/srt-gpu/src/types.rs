//! GPU data layouts: `#[repr(C)]` bytemuck twins of the structs in `shaders/types.wgsl` and
//! `shaders/physics.wgsl`, defined once here, and the named codes and flag bits those structs
//! carry. `tests/layout.rs` checks every field's offset and size against naga's layout of the
//! WGSL struct; `tests/reflect.rs` checks that the WGSL `const`s of the codes and bits equal the
//! Rust ones.

use bytemuck::{Pod, Zeroable};
use glam::{DMat4, DVec3};
use srt_color::{Output, RadianceScale, ToneMap};
use srt_physics::{Event, Frame, Poincare};
use srt_scene::{Clock, Effects, Object, SurfaceColour, SurfaceOptics};

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

/// `vec4<f32>` (ct, x, y, z) of an event.
#[must_use]
pub fn event4(e: Event) -> [f32; 4] {
    [
        e.ct as f32,
        e.position.x as f32,
        e.position.y as f32,
        e.position.z as f32,
    ]
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
        Self {
            rest_to_observer: mat4(frame.rest_to_observer_matrix()),
            observer_to_rest: mat4(frame.observer_to_rest_matrix()),
            beta_gamma: vec4(frame.beta(), frame.gamma()),
            offset: vec4(frame.offset(), 0.0),
            observer_rest: event4(frame.to_rest(observer)),
        }
    }
}

/// `FrameUniforms::effects`: which effects the shading shows (WGSL `EFFECTS_*` in types.wgsl).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct EffectsCode(pub u32);

impl EffectsCode {
    /// Geometry only: no Doppler shift, no searchlight (WGSL `EFFECTS_GEOMETRY`).
    pub const GEOMETRY: Self = Self(0);
    /// The Doppler shift of the light's colour (WGSL `EFFECTS_DOPPLER`).
    pub const DOPPLER: Self = Self(1);
    /// Doppler shift and searchlight brightening (WGSL `EFFECTS_SEARCHLIGHT`).
    pub const SEARCHLIGHT: Self = Self(2);
}

impl From<Effects> for EffectsCode {
    fn from(effects: Effects) -> Self {
        match effects {
            Effects::Geometry => Self::GEOMETRY,
            Effects::Doppler => Self::DOPPLER,
            Effects::Searchlight => Self::SEARCHLIGHT,
        }
    }
}

/// `FrameUniforms::colour`: how lit surfaces are coloured (WGSL `SURFACE_COLOUR_*`); the object
/// passes are compiled once per code (`SURFACE_COLOUR_VARIANT`, [`crate::shaders::ObjectVariant`]).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct SurfaceColourCode(pub u32);

impl SurfaceColourCode {
    /// The paper's colour table at D·T (WGSL `SURFACE_COLOUR_PAPER`).
    pub const PAPER: Self = Self(0);
    /// Reflectance spectra (WGSL `SURFACE_COLOUR_SPECTRAL`).
    pub const SPECTRAL: Self = Self(1);
    /// Every code, in order: the index of a code is its value.
    pub const ALL: [Self; 2] = [Self::PAPER, Self::SPECTRAL];

    /// The code's index in [`SurfaceColourCode::ALL`].
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl From<SurfaceColour> for SurfaceColourCode {
    fn from(colour: SurfaceColour) -> Self {
        match colour {
            SurfaceColour::Paper => Self::PAPER,
            SurfaceColour::Spectral => Self::SPECTRAL,
        }
    }
}

/// `FrameUniforms::tone_map`: the tone map of spectral colour (WGSL `TONE_MAP_*`).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct ToneMapCode(pub u32);

impl ToneMapCode {
    /// Fig. 6 left (WGSL `TONE_MAP_LUMINANCE`).
    pub const LUMINANCE: Self = Self(0);
    /// Fig. 6 right (WGSL `TONE_MAP_SEARCHLIGHT`).
    pub const SEARCHLIGHT: Self = Self(1);
}

impl From<ToneMap> for ToneMapCode {
    fn from(tone_map: ToneMap) -> Self {
        match tone_map {
            ToneMap::Luminance => Self::LUMINANCE,
            ToneMap::Searchlight => Self::SEARCHLIGHT,
        }
    }
}

/// `ObjectUniforms::optics` of `optics`: ultraviolet and infrared reflectances (−1 for none),
/// emission temperature (0 for none) and brightness.
#[must_use]
pub fn optics4(optics: &SurfaceOptics) -> [f32; 4] {
    let (temperature, brightness) = optics
        .emission
        .map_or((0.0, 0.0), |e| (e.temperature_k, e.brightness));
    [
        optics.ultraviolet.unwrap_or(-1.0) as f32,
        optics.infrared.unwrap_or(-1.0) as f32,
        temperature as f32,
        brightness as f32,
    ]
}

/// `FrameUniforms::footprint_shape`: what the LRT pass draws per triangle (WGSL `FOOTPRINT_*`).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct FootprintCode(pub u32);

impl FootprintCode {
    /// The convex hull of the footprint (WGSL `FOOTPRINT_HULL`).
    pub const HULL: Self = Self(0);
    /// Its window-aligned rectangle (WGSL `FOOTPRINT_RECTANGLE`).
    pub const RECTANGLE: Self = Self(1);
}

/// Twin of WGSL `FrameUniforms`: per-image parameters.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct FrameUniforms {
    /// S → clip space.
    pub view_projection: [[f32; 4]; 4],
    /// Unit camera forward, w = 0.
    pub camera_forward: [f32; 4],
    /// Camera right × tan(fov/2) × aspect × the target's share of the width; w: the target's
    /// centre in units of it ([`crate::projection::TargetCamera`]).
    pub camera_right: [f32; 4],
    /// Camera up × tan(fov/2) × the target's share of the height; w as `camera_right`'s.
    pub camera_up: [f32; 4],
    /// Observer position (xyz), w = 0: the observation time reaches the shaders through each
    /// object's [`GpuFrame::observer_rest`].
    pub observer: [f32; 4],
    /// Light position (xyz) and temperature in kelvin (w).
    pub light: [f32; 4],
    /// Ambient, diffuse, specular, shininess.
    pub shading: [f32; 4],
    /// Background as the output holds it (WGSL's comment says how).
    pub background: [f32; 4],
    /// ln T_min, ln T_max, texel count, unused.
    pub lut: [f32; 4],
    /// Width, height, 1/width, 1/height.
    pub viewport: [f32; 4],
    /// The whole picture's width and height in target pixels, and the target's first column
    /// and row in it: (width, height, 0, 0) of the target itself unless it holds a window of a
    /// larger picture ([`crate::projection::ImageWindow`]).
    pub picture: [f32; 4],
    /// Which effects the shading shows.
    pub effects: EffectsCode,
    /// What the LRT pass draws per triangle.
    pub footprint_shape: FootprintCode,
    /// LRT depth = apparent distance × this.
    pub depth_scale: f32,
    /// How lit surfaces are coloured.
    pub colour: SurfaceColourCode,
    /// The tone map of spectral colour.
    pub tone_map: ToneMapCode,
    /// Multiplier on the light before the tone map (spectral colour).
    pub exposure: f32,
    /// ln Y(1500 K), the searchlight tone map's divisor.
    pub searchlight_ln_y: f32,
    /// What the passes write: display colours or radiance.
    pub output: OutputCode,
    /// How the picture's points map to viewing directions.
    pub projection: ProjectionCode,
    /// Half the fisheye's field of view in radians (0 for the other projections).
    pub fisheye_half_fov: f32,
    /// A stereo pair's eye separation, or −1 for one picture from the observer.
    pub eye_separation: f32,
    /// Unused: keeps `radiance` on its 16-byte boundary.
    pub projection_padding: u32,
    /// How light becomes radiance: ln Y of the lamp, 1/g, 1 where brightness follows luminance
    /// else 0, and the largest value the colour target holds ([`radiance_params`]).
    pub radiance: [f32; 4],
    /// The lamp's strength and the moving lights: per frame like the rest, and in the same
    /// buffer to keep the shading pass within eight storage buffers.
    pub lights: LightUniforms,
}

/// `FrameUniforms::output`: what the passes write per pixel (WGSL `OUTPUT_*` in light.wgsl).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct OutputCode(pub u32);

impl OutputCode {
    /// Display colours through the tone map (WGSL `OUTPUT_DISPLAY`).
    pub const DISPLAY: Self = Self(0);
    /// Radiance (WGSL `OUTPUT_RADIANCE`).
    pub const RADIANCE: Self = Self(1);
    /// What each pixel sees of time: emission ct_W, proper time, apparent distance, Doppler
    /// factor (WGSL `OUTPUT_SEEN_EVENT`).
    pub const SEEN_EVENT: Self = Self(2);
    /// The seen object's index in the first channel, −1 for none (WGSL `OUTPUT_SEEN_OBJECT`).
    pub const SEEN_OBJECT: Self = Self(3);
}

impl From<Output> for OutputCode {
    fn from(output: Output) -> Self {
        match output {
            Output::Display => Self::DISPLAY,
            Output::Radiance => Self::RADIANCE,
        }
    }
}

/// `FrameUniforms::projection`: how the picture's points map to viewing directions (WGSL
/// `PROJECTION_*` in types.wgsl, after [`srt_scene::Projection`]).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct ProjectionCode(pub u32);

impl ProjectionCode {
    /// The pinhole (WGSL `PROJECTION_PERSPECTIVE`).
    pub const PERSPECTIVE: Self = Self(0);
    /// The full sphere (WGSL `PROJECTION_EQUIRECTANGULAR`).
    pub const EQUIRECTANGULAR: Self = Self(1);
    /// The azimuthal equidistant fisheye (WGSL `PROJECTION_FISHEYE`).
    pub const FISHEYE: Self = Self(2);
}

impl From<srt_scene::Projection> for ProjectionCode {
    fn from(projection: srt_scene::Projection) -> Self {
        match projection {
            srt_scene::Projection::Perspective => Self::PERSPECTIVE,
            srt_scene::Projection::Equirectangular => Self::EQUIRECTANGULAR,
            srt_scene::Projection::Fisheye { .. } => Self::FISHEYE,
        }
    }
}

/// `FrameUniforms::radiance` of `scale` for a colour target whose largest finite value is
/// `limit`.
#[must_use]
pub fn radiance_params(scale: &RadianceScale, limit: f32) -> [f32; 4] {
    [
        scale.ln_y_lamp() as f32,
        scale.inverse_white() as f32,
        if scale.follows_luminance() { 1.0 } else { 0.0 },
        limit,
    ]
}

/// Twin of WGSL `ObjectUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ObjectUniforms {
    /// The rest frame.
    pub frame: GpuFrame,
    /// Wireframe width (x, ≤ 0 for none).
    pub style: [f32; 4],
    /// Spectral optics ([`optics4`]).
    pub optics: [f32; 4],
    /// Index in scene order, rest-time shift, ct_W of the rest origin, 0 ([`object_time`]).
    pub time: [f32; 4],
    /// The time row of the object's rest coordinates → W ([`object_time`]).
    pub world_time: [f32; 4],
    /// Its emission's blinking ([`blink4`]).
    pub blink: [f32; 4],
    /// Its clock face's rate, offset and dial, and 1 if it has one ([`ClockUniforms`]).
    pub clock: [f32; 4],
    /// The clock's face colour (rgb).
    pub clock_face: [f32; 4],
    /// The clock's ink colour (rgb).
    pub clock_ink: [f32; 4],
    /// Its motion within its rest frame: x unused (the kind is the pipeline variant's), rate or
    /// α, phase or elapsed time, final rapidity ([`crate::motion::MotionUniforms`]).
    pub motion: [f32; 4],
    /// The spin axis or thrust direction (xyz) and the body's reach (w).
    pub motion_axis: [f32; 4],
    /// The spin centre (xyz); w unused.
    pub motion_centre: [f32; 4],
    /// The body's box at rest, lower corner (xyz), and its lowest height along the spin axis (w).
    pub motion_low: [f32; 4],
    /// The body's box at rest, upper corner (xyz), and its highest height along the spin axis (w).
    pub motion_high: [f32; 4],
    /// In a wide projection, the rectangle of the whole picture (pixels: min x, min y, max x,
    /// max y) where the object may be seen ([`crate::culling::ball_wide_bound`]).
    pub view_bound: [f32; 4],
}

/// `ObjectUniforms::clock`, `clock_face` and `clock_ink` of a clock face, or zeros for none.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClockUniforms {
    /// Rate, offset, dial, and 1 (0: no clock).
    pub clock: [f32; 4],
    /// Face colour, alpha 1.
    pub face: [f32; 4],
    /// Ink colour, alpha 1.
    pub ink: [f32; 4],
}

impl From<Option<&Clock>> for ClockUniforms {
    fn from(clock: Option<&Clock>) -> Self {
        clock.map_or_else(Self::default, |c| {
            let rgba = |rgb: [f64; 3]| [rgb[0] as f32, rgb[1] as f32, rgb[2] as f32, 1.0];
            Self {
                clock: [c.rate as f32, c.offset as f32, c.dial as f32, 1.0],
                face: rgba(c.face),
                ink: rgba(c.ink),
            }
        })
    }
}

/// `ObjectUniforms::blink` of `optics`: the blink period in proper time and the duty (period 0:
/// the emission, if any, never blinks).
#[must_use]
pub fn blink4(optics: &SurfaceOptics) -> [f32; 4] {
    optics
        .emission
        .and_then(|e| e.blink)
        .map_or([0.0; 4], |b| [b.period as f32, b.duty as f32, 0.0, 0.0])
}

/// `ObjectUniforms::time` and `world_time` of `object`, the `index`-th of a scene whose S → W
/// transformation is `world`: with them a shader turns a rest event e′ into the object's proper
/// time (e′.ct − rest_time_shift) and the world time ct_W = dot(world_time, e′) + time.z, the
/// composition of Eq. 1 (S′ → S) and S → W computed here in f64.
#[must_use]
pub fn object_time(object: &Object, index: usize, world: &Poincare) -> ([f32; 4], [f32; 4]) {
    let to_world = Poincare::of_frame(&object.frame).then(world);
    let row = to_world.lorentz.row(0);
    let time = [
        index as f32,
        object.rest_time_shift as f32,
        to_world.translation.x as f32,
        0.0,
    ];
    (time, row.as_vec4().to_array())
}

/// `PartUniforms::flags`: one bit per yes/no property of a mesh part (WGSL `PART_*` in
/// types.wgsl).
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Pod, Zeroable)]
pub struct PartFlags(pub u32);

impl PartFlags {
    /// The part has a texture (WGSL `PART_TEXTURED`).
    pub const TEXTURED: Self = Self(1);
    /// Its vertices carry colours (WGSL `PART_VERTEX_COLOURS`).
    pub const VERTEX_COLOURS: Self = Self(2);
    /// Back faces may be culled this frame: every mesh of the batch is a closed solid with
    /// outward fronts and the observer is outside it
    /// ([`BackFaceCulling::applies`](crate::culling::BackFaceCulling::applies); WGSL
    /// `PART_CULL_BACK_FACES`).
    pub const CULL_BACK_FACES: Self = Self(4);
    /// The part is the box that holds its object (the ray tracer's, [`crate::ray_tracing`]): a
    /// hit its fragments find lies anywhere inside it, so its footprints' nearest depth is
    /// bounded over all its corners, not over the face drawn (WGSL `PART_ENCLOSING_BOX`).
    pub const ENCLOSING_BOX: Self = Self(8);

    /// These flags with `flag` set or cleared.
    #[must_use]
    pub const fn with(self, flag: Self, on: bool) -> Self {
        if on {
            Self(self.0 | flag.0)
        } else {
            Self(self.0 & !flag.0)
        }
    }

    /// Whether every bit of `flag` is set.
    #[must_use]
    pub const fn contains(self, flag: Self) -> bool {
        self.0 & flag.0 == flag.0
    }
}

/// Twin of WGSL `PartUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct PartUniforms {
    /// Base colour factor.
    pub base_color: [f32; 4],
    /// Yes/no properties of the part.
    pub flags: PartFlags,
    /// Triangles in the part.
    pub triangle_count: u32,
    /// The part's number in the scene, from 1: the LRT visibility pass writes it (0 where no
    /// triangle is seen) and the shading pass compares it.
    pub id: u32,
    /// Frames stacked in the part's texture (1: a still image; srt_scene::Texture::frames).
    pub frames: u32,
    /// Height of one frame in the texture's first uploaded level, in texels.
    pub frame_height: u32,
    /// Frames per unit of proper time (0 for a still image).
    pub frame_rate: f32,
    /// Padding to the WGSL size.
    pub padding: [u32; 2],
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

/// Twin of WGSL `Star` (types.wgsl): one star of the sky.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuStar {
    /// Unit direction observer → star in the world frame (xyz), temperature in kelvin (w).
    pub direction_temperature: [f32; 4],
    /// Visual magnitude at rest (x).
    pub magnitude: [f32; 4],
}

impl From<&srt_scene::Star> for GpuStar {
    fn from(star: &srt_scene::Star) -> Self {
        Self {
            direction_temperature: vec4(star.direction, star.temperature_k),
            magnitude: [star.magnitude as f32, 0.0, 0.0, 0.0],
        }
    }
}

/// Twin of WGSL `SkyUniforms` (types.wgsl): the sky's motion and brightness for one image.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct SkyUniforms {
    /// Velocity of the world frame relative to S (xyz), saturation magnitude (w).
    pub beta_saturation: [f32; 4],
    /// Number of stars (x), the sky image's width (y) and height (z), 1 if there is one (w).
    pub counts: [u32; 4],
    /// Directions in W → directions in S before aberration (columns; w unused).
    pub direction_map: [[f32; 4]; 3],
    /// The inverse of `direction_map`.
    pub direction_unmap: [[f32; 4]; 3],
    /// The sky image's brightness factor (x).
    pub image: [f32; 4],
    /// Supersampling (x): each output pixel is x × x target pixels
    /// ([`crate::GpuRenderer::set_supersampling`]); yzw unused.
    pub supersampling: [u32; 4],
}

/// A 3×3 matrix as WGSL's `mat3x3<f32>` lays it out: three columns of `vec4` alignment.
#[must_use]
pub fn mat3(m: glam::DMat3) -> [[f32; 4]; 3] {
    m.to_cols_array_2d()
        .map(|c| [c[0] as f32, c[1] as f32, c[2] as f32, 0.0])
}

/// Most points of a footprint's convex hull (WGSL `FOOTPRINT_HULL_POINTS`): the hull of the
/// three corners and three tangent intersections.
pub const FOOTPRINT_HULL_POINTS: usize = 6;

/// Vertices drawn per footprint: a fan of `FOOTPRINT_HULL_POINTS − 2` triangles (WGSL
/// `FOOTPRINT_VERTICES` in types.wgsl); spare triangles of smaller hulls are degenerate.
pub const FOOTPRINT_VERTICES: u32 = 3 * (FOOTPRINT_HULL_POINTS as u32 - 2);

/// Size of the LRT pass's WGSL `fragment_count` (`array<atomic<u32>, 3>`: fragments run,
/// fragments shaded, and visibility fragments whose depth came out nearer than their
/// footprint's `nearest_depth`), which the renderer clears and reads back.
pub const FRAGMENT_COUNTER_BYTES: u64 = 12;

/// Size of WGSL `frame_bound` (`array<u32, 4>`: the union of every footprint's screen
/// rectangle in the frame), one buffer per renderer, cleared before every proxy pass.
pub const FRAME_BOUND_BYTES: u64 = 16;

/// Footprint slots for the pieces of split triangles in every batch, beyond
/// [`footprint_slots`]'s share per triangle.
pub const PIECE_SLOTS: u64 = 1024;

/// Footprint slots of a batch of `triangles` triangles (the length of WGSL `footprints`): one
/// per triangle, then [`PIECE_SLOTS`] and one more per two triangles for the pieces of split
/// triangles (a split triangle whose pieces find no slot is drawn by the rectangle holding them).
#[must_use]
pub const fn footprint_slots(triangles: u64) -> u64 {
    triangles + PIECE_SLOTS + triangles / 2
}

/// Index in WGSL `draw_args` of the LRT visibility pass's draw (its vertex count first): the
/// first of two non-indexed indirect draws, each a `wgpu::util::DrawIndirectArgs`.
pub const DRAW_ARGS_FOOTPRINT_VERTICES: u32 = 0;
/// Index in WGSL `draw_args` of the LRT shading pass's draw (its vertex count first).
pub const DRAW_ARGS_SHADE_VERTICES: u32 = 4;
/// Index in WGSL `draw_args` of the count of piece slots taken (and asked for once they ran out).
pub const DRAW_ARGS_PIECES_TAKEN: u32 = 8;
/// Index in WGSL `draw_args` of the part's screen bound, the union of its footprints'
/// rectangles in whole pixels: four words (!min x, !min y, max x, max y), all grown by
/// `atomicMax` from 0, which reads as empty (min > max).
pub const DRAW_ARGS_BOUND: u32 = 9;
/// Words (u32) in WGSL `draw_args`, one buffer per part.
pub const DRAW_ARGS_WORDS: u32 = 13;

/// Size of WGSL `draw_args` in bytes.
pub const DRAW_ARGS_BYTES: u64 = 4 * DRAW_ARGS_WORDS as u64;

/// Byte offset of the LRT shading pass's draw in WGSL `draw_args`.
pub const SHADE_DRAW_OFFSET: u64 = 4 * DRAW_ARGS_SHADE_VERTICES as u64;

/// Entries of the GPU ray tracer's traversal stack (WGSL `BVH_STACK_SIZE` in types.wgsl): a
/// batch's BVH may be at most this deep less one ([`crate::bvh::ObjectBvh::build`] checks).
pub const BVH_STACK_SIZE: u32 = 64;

/// Twin of WGSL `BvhNode`: one node of a batch's BVH in S′ ([`crate::bvh::ObjectBvh`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuBvhNode {
    /// Lower corner of the (widened) box.
    pub min: [f32; 3],
    /// Triangles in this leaf; 0 for an inner node.
    pub primitive_count: u32,
    /// Upper corner of the (widened) box.
    pub max: [f32; 3],
    /// An inner node's first child (the second follows it); a leaf's first entry in the
    /// primitive list.
    pub first: u32,
}

/// Twin of WGSL `RtTriangle`: one triangle of an object as the ray tracer reads it, in its
/// BVH's leaf order, with the id the visibility pass writes for it.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuRtTriangle {
    /// First corner in S′.
    pub p0: [f32; 3],
    /// The batch's part id ([`PartUniforms::id`]).
    pub part: u32,
    /// Second corner in S′.
    pub p1: [f32; 3],
    /// The triangle's number in its batch.
    pub triangle: u32,
    /// Third corner in S′.
    pub p2: [f32; 3],
    /// Padding to the WGSL size.
    pub padding: u32,
}

/// Most lights on their own worldlines the shading passes read (WGSL `MAX_MOVING_LIGHTS` in
/// types.wgsl): [`srt_scene::MAX_MOVING_LIGHTS`], the length of [`LightUniforms::moving`].
pub const MAX_MOVING_LIGHTS: usize = srt_scene::MAX_MOVING_LIGHTS;

/// Twin of WGSL `MovingLight`: one light on its own worldline ([`srt_scene::MovingLight`]),
/// resting at the origin of its frame, whose worldline in S is offset + β·ct.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuMovingLight {
    /// The frame's offset **a** (xyz) and the Planck temperature in its rest frame (w).
    pub offset_temperature: [f32; 4],
    /// β (xyz) and γ (w).
    pub beta_gamma: [f32; 4],
    /// The strength (x), 1 − β² computed in f64 (y); zw unused.
    pub strength: [f32; 4],
}

impl From<&srt_scene::MovingLight> for GpuMovingLight {
    fn from(light: &srt_scene::MovingLight) -> Self {
        let frame = &light.frame;
        let beta = frame.beta();
        Self {
            offset_temperature: vec4(frame.offset(), light.temperature_k),
            beta_gamma: vec4(beta, frame.gamma()),
            strength: [
                light.strength as f32,
                (1.0 - beta.length_squared()) as f32,
                0.0,
                0.0,
            ],
        }
    }
}

/// Twin of WGSL `LightUniforms`: the lamp's strength and the lights on their own worldlines,
/// with where the shadow casters are in WGSL `shadow_scene` ([`crate::shadows`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct LightUniforms {
    /// The lamp's strength ([`srt_scene::Light::strength`]) in x; yzw unused.
    pub lamp: [f32; 4],
    /// The moving lights in use (x), the shadow casters in `shadow_scene` (y), the rows where
    /// its BVH nodes (z) and its triangles (w) begin.
    pub counts: [u32; 4],
    /// The moving lights, the first `counts[0]` in use.
    pub moving: [GpuMovingLight; MAX_MOVING_LIGHTS],
}

/// Twin of WGSL `ShadowObject`: one object of the scene as the shadow test reads it
/// ([`crate::shadows`]), rewritten every frame.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuShadowObject {
    /// Λ_−β of its rest frame (S four-vectors → S′).
    pub observer_to_rest: [[f32; 4]; 4],
    /// Its frame's offset **a** (xyz), 0.
    pub offset: [f32; 4],
    /// Its BVH's root node in `shadow_scene`'s nodes (x), 1 if it emits light and so casts no
    /// shadow (y), its index in scene order (z); w unused.
    pub bvh: [u32; 4],
}

/// Rows (16 bytes, WGSL `vec4<u32>`) of one [`GpuShadowObject`] in `shadow_scene` (WGSL
/// `SHADOW_OBJECT_ROWS`).
pub const SHADOW_OBJECT_ROWS: u32 = (size_of::<GpuShadowObject>() / 16) as u32;
/// Rows of one [`GpuBvhNode`] in `shadow_scene` (WGSL `SHADOW_NODE_ROWS`).
pub const SHADOW_NODE_ROWS: u32 = (size_of::<GpuBvhNode>() / 16) as u32;
/// Rows of one triangle ([`GpuRtTriangle`]) in `shadow_scene` (WGSL `SHADOW_TRIANGLE_ROWS`).
pub const SHADOW_TRIANGLE_ROWS: u32 = (size_of::<GpuRtTriangle>() / 16) as u32;

/// Twin of WGSL `Footprint`: a footprint as the proxy pass stores it and the visibility passes
/// draw it, 64 bytes.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuFootprint {
    /// The convex polygon drawn, in pixels: the first [`GpuFootprint::hull_len`] points (a
    /// rectangle, whole-screen footprints and the paper's rectangle footprints included, as its
    /// four corners).
    pub hull: [[f32; 2]; FOOTPRINT_HULL_POINTS],
    /// The triangle of the batch it is a footprint of: the triangle of its slot, or the one it
    /// is a piece of.
    pub triangle: u32,
    /// The depth at which the footprint is drawn: at most the depth of any hit its fragments
    /// can find (the apparent distance bound of [`srt_proxy::nearest_apparent_distance`], less
    /// a margin for f32 rounding, times the frame's depth scale), so that the visibility passes
    /// may declare the depth they write "greater or equal" ([`crate::shaders::ConservativeDepth`]).
    pub nearest_depth: f32,
    /// The hull's number of points ([`FOOTPRINT_HULL_LEN`]) and the flags
    /// [`FOOTPRINT_WHOLE_SCREEN`] and [`FOOTPRINT_PIECES_OVERFLOWED`].
    pub flags: u32,
    /// Pads the footprint to the hull's alignment.
    pub padding: u32,
}

/// Bits of [`GpuFootprint::flags`] holding the hull's number of points, 0 for a footprint that
/// draws nothing (a culled back face, or a triangle nothing of which is on screen) (WGSL
/// `FOOTPRINT_HULL_LEN`).
pub const FOOTPRINT_HULL_LEN: u32 = 7;
/// [`GpuFootprint::flags`]: a whole-screen footprint (WGSL `FOOTPRINT_WHOLE_SCREEN`).
pub const FOOTPRINT_WHOLE_SCREEN: u32 = 8;
/// [`GpuFootprint::flags`]: in a triangle's own slot, the batch's piece slots ran out while its
/// pieces were stored, and the footprint is the rectangle holding all of them as drawn (WGSL
/// `FOOTPRINT_PIECES_OVERFLOWED`).
pub const FOOTPRINT_PIECES_OVERFLOWED: u32 = 16;

impl GpuFootprint {
    /// The hull's number of points (0: the footprint draws nothing).
    #[must_use]
    pub const fn hull_len(&self) -> usize {
        (self.flags & FOOTPRINT_HULL_LEN) as usize
    }

    /// The hull's points, in pixels.
    #[must_use]
    pub fn hull_points(&self) -> &[[f32; 2]] {
        &self.hull[..self.hull_len().min(FOOTPRINT_HULL_POINTS)]
    }

    /// Whether it is a whole-screen footprint.
    #[must_use]
    pub const fn whole_screen(&self) -> bool {
        self.flags & FOOTPRINT_WHOLE_SCREEN != 0
    }

    /// Whether it is a triangle's fallback rectangle around its pieces (the piece slots ran out).
    #[must_use]
    pub const fn pieces_overflowed(&self) -> bool {
        self.flags & FOOTPRINT_PIECES_OVERFLOWED != 0
    }

    /// The rectangle (min x, min y, max x, max y) of the hull's points, which holds what is drawn
    /// of the footprint; `None` for one that draws nothing.
    #[must_use]
    pub fn bounds(&self) -> Option<[f32; 4]> {
        let points = self.hull_points();
        let first = points.first()?;
        Some(points.iter().fold(
            [first[0], first[1], first[0], first[1]],
            |[x0, y0, x1, y1], p| [x0.min(p[0]), y0.min(p[1]), x1.max(p[0]), y1.max(p[1])],
        ))
    }
}

/// Twin of WGSL `PhysicsProbeInput`: one set of arguments for every physics kernel
/// (the `probe` module (feature `probe`)).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuPhysicsProbeInput {
    /// The object's rest frame and the observation event.
    pub frame: GpuFrame,
    /// An event in S for `to_rest`.
    pub event: [f32; 4],
    /// An event in S′ for `to_observer`.
    pub rest_event: [f32; 4],
    /// A point at rest in S′ (xyz) and the ray parameter s (w).
    pub point: [f32; 4],
    /// A direction in S′ for `apparent_tangent`.
    pub direction: [f32; 4],
    /// A viewing direction in S for `backward_ray`.
    pub view: [f32; 4],
    /// A propagation direction in S for `doppler_factor`.
    pub propagation: [f32; 4],
    /// A propagation direction in S′ for `aberrate`.
    pub direction_rest: [f32; 4],
    /// Incident propagation direction for `reflection_doppler`.
    pub incident: [f32; 4],
    /// Outgoing propagation direction for `reflection_doppler`.
    pub outgoing: [f32; 4],
}

/// Twin of WGSL `PhysicsProbeOutput`: every physics kernel's result for one input
/// (the `probe` module (feature `probe`)).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuPhysicsProbeOutput {
    /// `to_observer(frame, rest_event)`.
    pub to_observer: [f32; 4],
    /// `to_rest(frame, event)`.
    pub to_rest: [f32; 4],
    /// `emission_event(frame, point)`.
    pub emission_event: [f32; 4],
    /// `apparent_position(frame, point)` (xyz).
    pub apparent_position: [f32; 4],
    /// `apparent_tangent(frame, point, direction)` (xyz).
    pub apparent_tangent: [f32; 4],
    /// `aberrate(β, direction_rest)` (xyz).
    pub aberrate: [f32; 4],
    /// `backward_ray(frame, view)`: origin (xyz) and `ct_origin` (w).
    pub ray_origin: [f32; 4],
    /// `backward_ray(frame, view)`: direction (xyz).
    pub ray_direction: [f32; 4],
    /// `doppler_factor`, `reflection_doppler`, `apparent_distance`, `lorentz_factor`.
    pub scalars: [f32; 4],
}

/// Twin of WGSL `SpectralProbeInput`: one set of arguments of the spectral kernels
/// (the `probe` module (feature `probe`)).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuSpectralProbeInput {
    /// sRGB-encoded surface colour (xyz), light (and emitter) temperature in kelvin (w).
    pub rgb_temperature: [f32; 4],
    /// D_in, D_out, exposure, tone map code as a float.
    pub factors: [f32; 4],
    /// Ultraviolet and infrared reflectances (< 0: none), emission brightness, unused.
    pub bands: [f32; 4],
}

/// Twin of WGSL `SpectralProbeOutput`: the spectral kernels' display colours.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuSpectralProbeOutput {
    /// Reflected light's display sRGB (xyz).
    pub reflected: [f32; 4],
    /// Emitted light's display sRGB (xyz).
    pub emitted: [f32; 4],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn part_flags_set_and_clear_single_bits() {
        let flags = PartFlags::default()
            .with(PartFlags::TEXTURED, true)
            .with(PartFlags::CULL_BACK_FACES, true);
        assert!(flags.contains(PartFlags::TEXTURED));
        assert!(!flags.contains(PartFlags::VERTEX_COLOURS));
        assert_eq!(flags.0, 5);
        let cleared = flags.with(PartFlags::TEXTURED, false);
        assert_eq!(cleared, PartFlags::CULL_BACK_FACES);
    }

    #[test]
    fn part_flag_bits_are_distinct_single_bits() {
        let bits = [
            PartFlags::TEXTURED,
            PartFlags::VERTEX_COLOURS,
            PartFlags::CULL_BACK_FACES,
        ];
        assert!(bits.iter().all(|b| b.0.is_power_of_two()));
        assert_eq!(bits.iter().fold(0, |acc, b| acc | b.0).count_ones(), 3);
    }

    #[test]
    fn effects_map_to_distinct_codes() {
        let codes =
            [Effects::Geometry, Effects::Doppler, Effects::Searchlight].map(EffectsCode::from);
        assert_eq!(
            codes,
            [
                EffectsCode::GEOMETRY,
                EffectsCode::DOPPLER,
                EffectsCode::SEARCHLIGHT
            ]
        );
    }

    #[test]
    fn colours_and_tone_maps_map_to_distinct_codes() {
        assert_eq!(
            SurfaceColour::ALL.map(SurfaceColourCode::from),
            [SurfaceColourCode::PAPER, SurfaceColourCode::SPECTRAL]
        );
        assert_eq!(
            ToneMap::ALL.map(ToneMapCode::from),
            [ToneMapCode::LUMINANCE, ToneMapCode::SEARCHLIGHT]
        );
    }

    #[test]
    fn optics_mark_what_is_absent() {
        assert_eq!(optics4(&SurfaceOptics::default()), [-1.0, -1.0, 0.0, 0.0]);
        let optics = SurfaceOptics {
            ultraviolet: Some(0.1),
            infrared: Some(0.9),
            emission: Some(srt_scene::Emission {
                temperature_k: 3000.0,
                brightness: 2.0,
                blink: Some(srt_scene::Blink {
                    period: 1.5,
                    duty: 0.25,
                }),
            }),
        };
        assert_eq!(optics4(&optics), [0.1, 0.9, 3000.0, 2.0]);
        assert_eq!(blink4(&optics), [1.5, 0.25, 0.0, 0.0]);
        assert_eq!(blink4(&SurfaceOptics::default()), [0.0; 4]);
    }
}

//! GPU local ray tracing of relativistic scenes with wgpu and WGSL (§4 of Müller, Grottel and
//! Weiskopf 2010), headless, with readback.
//!
//! Passes (WGSL in `shaders/`, each with a CPU mirror of the same name):
//! - `proxy` — compute pass, one invocation per triangle: the conservative footprint of the
//!   apparent triangle (mirror: `srt-proxy`);
//! - `lrt` — two passes: the visibility pass draws the footprints (FOOTPRINT_VERTICES per
//!   triangle) and each fragment traces its viewing ray in the triangle's rest frame, writing
//!   the apparent distance as depth and the triangle's id; the shading pass shades the kept
//!   triangle once per pixel (mirror: `srt-trace`);
//! - `rt` — the BVH ray tracer's visibility pass, a second exact method: per object, the
//!   footprints of its box (the proxy pass run over the box's 12 triangles) are drawn and each
//!   fragment walks the object's BVH in S′ ([`bvh`], [`ray_tracing`]); the LRT's shading pass
//!   follows. [`Method::Auto`] picks LRT or the ray tracer per object (mirror: `srt-trace`);
//! - `polygon` — the per-vertex photo-object method of §3.2, for comparison;
//! - `image_based` — the paper's other comparison (Table 1's IB): per velocity group a cube map
//!   of the objects at rest, looked up along each pixel's aberrated direction
//!   ([`Method::ImageBased`]);
//! - `sky` — the stars of a scene's sky: a compute pass splats each aberrated, Doppler-shifted
//!   star into a per-pixel buffer, a full-screen pass writes background and stars before the
//!   objects are drawn (mirror: `srt-trace`'s sky);
//! - `display` — shows a frame: its display colours into a window's or a canvas's 8-bit target,
//!   quantised as the PNG is ([`display`]).
//!
//! The shading passes colour surfaces with the paper's colour table or, for scenes with spectral
//! colour, with `spectral.wgsl`, the mirror of `srt-color`'s reflectance spectra (tables uploaded
//! by [`spectral`]). Lights on their own worldlines add their light from their retarded events,
//! and their late shadows are tested per pixel against every object's BVH in its rest frame
//! (`shadows.wgsl`, buffers by [`shadows`]; mirror: `srt_physics::RetardedLight` and
//! `srt-trace`'s shadow test).
//!
//! Bodies that spin or thrust within their rest frame (`srt_physics::motion`) are always traced
//! through their BVH: the backward ray becomes a curve in body space, marched in pieces
//! (`motion.wgsl`, [`motion`]; mirror: `srt-trace`'s `moving`).
//!
//! `physics.wgsl` mirrors `srt-physics` in f32 and is composed in front of every pass. The
//! validation harness `probe` (single kernels run against the CPU crates) is compiled only with
//! the `probe` feature, which `cargo xtask` and this crate's tests enable; the production modules
//! never depend on it.

pub mod auto;
pub mod bvh;
pub mod context;
pub mod culling;
pub mod display;
pub mod error;
pub mod exact_path;
pub mod formats;
pub mod limits;
pub mod lut;
pub mod motion;
pub mod passes;
pub mod pipelines;
#[cfg(feature = "probe")]
pub mod probe;
pub mod projection;
pub mod ray_tracing;
pub mod readback;
pub mod renderer;
pub mod shaders;
pub mod shadows;
pub mod sky;
pub mod spectral;
pub mod textures;
pub mod types;

pub use context::{GpuContext, SoftwareApi, context_or_skip};
pub use error::GpuError;
pub use readback::{TextureReadback, read_texture};
pub use renderer::{
    FootprintShape, FragmentCounts, FrameStats, GpuImage, GpuRenderer, Method, SEEN_CHANNELS,
    TriangleFootprints,
};

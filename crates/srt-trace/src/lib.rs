//! The exact CPU reference renderer of srt.
//!
//! For every pixel sample the backward viewing ray from the observation event is transformed into
//! each object's rest frame S′, where the object is static: a plain ray–mesh intersection through
//! a BVH finds the surface (Eq. 15–16). The hit is mapped back to S (Eq. 7–8) and the smallest
//! apparent distance over all objects wins, so occlusion and intersections between differently
//! moving objects are right. Shading follows §4.2 (Eq. 17–18) with the colour table of
//! `srt-color`. Nothing here approximates the geometry: it is the reference every other method
//! (the GPU local ray tracer, the polygon method) is measured against, and it never shares code
//! with the footprint computation it checks (`srt-proxy`).
//!
//! ```no_run
//! # fn scene() -> srt_scene::Scene { unimplemented!() }
//! use srt_trace::{RenderSettings, Tracer};
//! let scene = scene();
//! let image = Tracer::new(&scene).render(RenderSettings { width: 640, height: 360, samples: 4 }, &|_| {});
//! assert_eq!(image.pixels.len(), 640 * 360);
//! ```

pub mod clock;
pub mod compare;
mod group;
mod intersect;
mod measure;
mod moving;
mod prepared;
mod render;
mod sah;
mod seen;
mod shade;
mod shared;
mod sky;
mod texture;
mod walk;

pub use intersect::{TriangleHit, intersect_triangle, plane_hit};
pub use measure::{
    FrameMeasure, MEASURED_SAMPLES, MeasuredPicture, PROBE_ROWS, WARM_UP_ROWS, measure_picture,
};
pub use render::{
    FrameCost, Hit, Output, RenderSettings, RenderedImage, SurfaceState, Tracer, pixel_ndc,
    sample_offsets, spread_rows,
};
pub use seen::SeenEvent;
pub use shade::{
    Arriving, GREY_WEIGHTS, Illumination, MAX_SOURCES, Sources, SurfacePoint, arriving,
    arriving_unless_shadowed, grey_value, shade,
};
pub use shared::forget_kept_bvhs;
pub use sky::{
    StarImage, StarLayer, project, sky_image_colour, sky_image_light, star_colour, star_image,
    star_layer, star_light, tent_splat,
};
pub use texture::sample_trilinear;

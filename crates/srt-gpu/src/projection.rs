//! The projection the GPU passes use, in one place: the polygon method rasterises through it,
//! the proxy pass projects footprints with it, and `cargo xtask validate` recomputes the f64
//! footprints with the same matrix.

use glam::DMat4;
use srt_scene::Observer;

/// Near plane of the projection (distance in scene units).
pub const NEAR_PLANE: f64 = 1e-3;
/// Far plane of the projection.
pub const FAR_PLANE: f64 = 1e5;

/// The S → clip-space matrix of `observer` for a `width` × `height` image.
#[must_use]
pub fn view_projection(observer: &Observer, width: u32, height: u32) -> DMat4 {
    observer.view_projection(f64::from(width) / f64::from(height), NEAR_PLANE, FAR_PLANE)
}

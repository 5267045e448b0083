//! The projection the GPU passes use, in one place: the polygon method rasterises through it,
//! the proxy pass projects footprints with it, and `cargo xtask validate` recomputes the f64
//! footprints with the same matrix. A render target may hold a window of a larger picture (a
//! tile): [`target_camera`] gives the camera and matrix of that window.

use glam::{DMat4, DVec2, DVec3, DVec4};
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

/// The part of a larger picture a render target holds: the target's pixels are the picture's
/// pixels from (`left`, `top`) on, in an `image_width` × `image_height` picture. srt draws a
/// picture beyond the adapter's limits (or its memory bound) as such tiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageWindow {
    /// The picture column of the target's first column.
    pub left: u32,
    /// The picture row of the target's first row.
    pub top: u32,
    /// The whole picture's width in pixels.
    pub image_width: u32,
    /// The whole picture's height in pixels.
    pub image_height: u32,
}

impl ImageWindow {
    /// Checks that a `width` × `height` target at the window lies within its picture.
    ///
    /// # Panics
    /// If it does not (a caller's bug).
    pub fn check_holds(&self, width: u32, height: u32) {
        assert!(
            self.left + width <= self.image_width && self.top + height <= self.image_height,
            "a {width}x{height} target at ({}, {}) of a {}x{} picture",
            self.left,
            self.top,
            self.image_width,
            self.image_height
        );
    }
}

/// The camera of a render target as the frame uniforms hold it (WGSL `FrameUniforms`,
/// camera.wgsl): through the pinhole, a pixel (x, y) of a `width` × `height` target, with
/// ndc = (2x/width − 1, 1 − 2y/height), looks along
/// `forward + (ndc.x + offset.x) right + (ndc.y + offset.y) up`; for a wide projection
/// `forward`, `right` and `up` are the observer's unit basis and the shaders map the whole
/// picture's points to directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetCamera {
    /// S → clip space of the target.
    pub view_projection: DMat4,
    /// The observer's unit viewing direction (the picture's centre).
    pub forward: DVec3,
    /// The observer's right axis × tan(fov/2) × aspect, × the target's share of the width.
    pub right: DVec3,
    /// The observer's up axis × tan(fov/2), × the target's share of the height.
    pub up: DVec3,
    /// The target's centre in the picture, in units of `right` and `up` (0 for the whole
    /// picture).
    pub offset: DVec2,
}

/// The camera of a `width` × `height` target of `observer`'s picture: the whole picture, or
/// `window` of it (for a wide projection, the unit basis whatever the window). For a window the target is an off-centre part of the picture's view: the
/// same ray through each pixel as in the whole picture, and the projection matrix followed by
/// the map of the window's part of clip space onto the target's.
///
/// # Panics
/// If `window` reaches beyond its picture.
#[must_use]
pub fn target_camera(
    observer: &Observer,
    width: u32,
    height: u32,
    window: Option<ImageWindow>,
) -> TargetCamera {
    let (forward, right, up) = observer.basis();
    if observer.picture_decides() {
        // The shaders map the whole picture's points (camera.wgsl's eye_point and
        // eye_direction, through FrameUniforms::picture, windows included): a wide projection
        // takes the unit basis; each eye's half of a side-by-side pair is a pinhole picture of
        // half the width.
        if let Some(window) = window {
            window.check_holds(width, height);
        }
        let (right, up) = if observer.projection.is_pinhole() {
            let (picture_width, picture_height) =
                window.map_or((width, height), |w| (w.image_width, w.image_height));
            let tan_half = (0.5 * observer.fov_y_deg.to_radians()).tan();
            let eye_aspect = 0.5 * f64::from(picture_width) / f64::from(picture_height);
            (right * tan_half * eye_aspect, up * tan_half)
        } else {
            (right, up)
        };
        return TargetCamera {
            view_projection: view_projection(observer, width, height),
            forward,
            right,
            up,
            offset: DVec2::ZERO,
        };
    }
    let tan_half = (0.5 * observer.fov_y_deg.to_radians()).tan();
    let Some(window) = window else {
        let aspect = f64::from(width) / f64::from(height);
        return TargetCamera {
            view_projection: view_projection(observer, width, height),
            forward,
            right: right * tan_half * aspect,
            up: up * tan_half,
            offset: DVec2::ZERO,
        };
    };
    window.check_holds(width, height);
    let (image_width, image_height) = (
        f64::from(window.image_width),
        f64::from(window.image_height),
    );
    let aspect = image_width / image_height;
    // The target's share of the picture and its centre, in the picture's NDC.
    let share = DVec2::new(
        f64::from(width) / image_width,
        f64::from(height) / image_height,
    );
    let centre = DVec2::new(
        f64::from(2 * window.left + width) / image_width - 1.0,
        1.0 - f64::from(2 * window.top + height) / image_height,
    );
    let offset = centre / share;
    // Clip x' = (x − centre.x w) / share.x, and y' likewise: the window's NDC onto [−1, 1].
    let window_clip = DMat4::from_cols(
        DVec4::new(1.0 / share.x, 0.0, 0.0, 0.0),
        DVec4::new(0.0, 1.0 / share.y, 0.0, 0.0),
        DVec4::Z,
        DVec4::new(-offset.x, -offset.y, 0.0, 1.0),
    );
    TargetCamera {
        view_projection: window_clip
            * view_projection(observer, window.image_width, window.image_height),
        forward,
        right: right * tan_half * aspect * share.x,
        up: up * tan_half * share.y,
        offset,
    }
}

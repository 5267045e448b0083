//! `srt view`: an interactive teaching tool for special relativity (the "future work" of §6 of
//! Müller, Grottel and Weiskopf 2010). A window shows the scene rendered by the GPU local ray
//! tracer of `srt-gpu` — the same passes `srt render` uses — and a side panel lets the user add
//! 3D models, set each object's velocity, fly the observer, scrub the observation time, toggle
//! the Doppler and searchlight effects, compare local ray tracing with the polygon method, and
//! save the scene as TOML or the image as PNG.
//!
//! - [`edit`]: the scene and every edit of it, independent of the UI and the GPU (arguments and
//!   files are resolved by [`srt_scene::resolve`], every edit is checked by the scene file's
//!   rules);
//! - [`camera`]: the fly camera;
//! - [`pilot`]: relativistic flight — throttle, coasting and braking under a proper
//!   acceleration, integrated exactly by `srt_physics::flight`;
//! - [`probe`]: what one pixel shows, computed exactly by the CPU reference tracer;
//! - [`view`]: rendering panes (seen, measured or Newtonian; side by side) into textures the UI
//!   shows;
//! - [`exact_path`]: whether an exact pane is drawn by the GPU or by the CPU tracer (on a
//!   software adapter, the faster of the two);
//! - [`app`]: the panel, the status line and the input handling ([`ViewerApp`]);
//! - [`run`]: opens the window (eframe on winit, egui drawn with egui-wgpu on the same wgpu
//!   device the scene is rendered with).
//!
//! Runs on software adapters too (Mesa's lavapipe with `WGPU_BACKEND=vulkan`, llvmpipe with
//! `WGPU_BACKEND=gl`), slower but correct.

pub mod app;
pub mod camera;
pub mod edit;
pub mod exact_path;
pub mod pilot;
pub mod probe;
pub mod record;
pub mod view;

use std::sync::Arc;

use eframe::{egui, egui_wgpu};
use srt_gpu::GpuContext;

pub use app::{Level, Status, ViewerApp};
pub use edit::open_arguments;
pub use exact_path::ExactPath;
pub use srt_scene::edit::{EditError, Editor, parse_speed};
pub use view::{Pane, ViewMethod};

/// Why `srt view` could not run.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// An argument that cannot be opened (unknown name, missing or invalid file).
    #[error(transparent)]
    Open(#[from] EditError),
    /// The window or its GPU could not be opened (no display, no adapter).
    #[error(
        "cannot open the viewer's window: {0} (it needs a display and a GPU adapter; without a \
         GPU, install Mesa's lavapipe: `apt-get install mesa-vulkan-drivers`, then \
         WGPU_BACKEND=vulkan)"
    )]
    Window(String),
}

/// Initial size of the window in points.
pub const WINDOW_SIZE: [f32; 2] = [1600.0, 900.0];

/// The window's wgpu set-up: backends from `WGPU_BACKEND` (default: Vulkan, then GL), our
/// device limits.
fn wgpu_options() -> egui_wgpu::WgpuConfiguration {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.device_descriptor = Arc::new(srt_gpu::context::device_descriptor);
    let present_mode = if std::env::var("SRT_VIEW_NOVSYNC").is_ok() {
        wgpu::PresentMode::AutoNoVsync
    } else {
        wgpu::PresentMode::AutoVsync
    };
    egui_wgpu::WgpuConfiguration {
        wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup),
        surface: egui_wgpu::SurfaceConfig {
            present_mode,
            desired_maximum_frame_latency: Some(2),
        },
        ..Default::default()
    }
}

/// Runs `srt view` with the command line's arguments after `view`: scene names (see `srt
/// scenes`), scene files (`.toml`) and model files (glTF/GLB, OBJ, PLY, STL), as `srt render`
/// accepts them. The first is the scene (none: the `teaser` scene); every further one adds its
/// objects to it. Returns when the window is closed.
///
/// # Errors
/// [`ViewerError::Open`] for an argument that cannot be opened (unknown name, missing or invalid
/// file), [`ViewerError::Window`] for a window or GPU that cannot be opened (no display, no
/// adapter).
pub fn run(arguments: &[String]) -> Result<(), ViewerError> {
    let (editor, warnings) = open_arguments(arguments)?;
    let title = format!("srt view — {}", editor.scene().name);
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(title)
            .with_app_id("srt-view")
            .with_inner_size(WINDOW_SIZE)
            .with_min_inner_size([640.0, 400.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: wgpu_options(),
        ..Default::default()
    };
    eframe::run_native(
        "srt view",
        options,
        Box::new(move |cc| {
            let state = cc
                .wgpu_render_state
                .as_ref()
                .ok_or("the window has no wgpu renderer")?;
            let ctx =
                GpuContext::from_device(state.device.clone(), state.queue.clone(), &state.adapter);
            Ok(Box::new(ViewerApp::new(
                editor,
                Some((ctx, Some(Arc::clone(&state.renderer)))),
                &warnings,
            )))
        }),
    )
    .map_err(|error| ViewerError::Window(error.to_string()))
}

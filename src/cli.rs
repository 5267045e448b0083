//! Command-line syntax of `srt` (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use glam::DVec3;

/// srt: see what an observer really sees of objects flying at near light speed.
#[derive(Debug, Parser)]
#[command(name = "srt", version, about, long_about = None)]
pub struct Cli {
    /// What to do (default: render the `fig10-cube50` scene).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    // The model list in this help text is checked against `model_extension_list()` by a test.
    /// Render a built-in scene, a scene file (.toml) or a 3D model (.gltf, .glb, .obj, .ply, .stl).
    Render(RenderArgs),
    /// List the built-in scenes.
    Scenes,
    /// Open the interactive viewer: SCENE_OR_MODEL... (default `teaser`); further models are
    /// added to the first scene.
    View {
        /// Built-in scene names, scene files (.toml) or model files.
        scenes: Vec<String>,
    },
}

impl Default for Command {
    fn default() -> Self {
        Self::Render(RenderArgs::default())
    }
}

/// Which renderer to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum Backend {
    /// The exact CPU ray tracer (srt-trace).
    Cpu,
    /// The GPU local ray tracer.
    Gpu,
    /// The GPU if an adapter exists, otherwise the CPU.
    #[default]
    Auto,
}

/// Rendering method on the command line (mirrors `srt_gpu::Method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum MethodArg {
    /// Local ray tracing: exact per pixel (the paper's method; what the CPU renderer computes).
    #[default]
    Lrt,
    /// Per-vertex polygon rendering (§3.2), the approximate baseline; GPU only.
    Polygon,
}

/// Effect mode on the command line (mirrors `srt_scene::Effects`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum EffectsArg {
    /// Geometry only: aberration and light travel time, no colour shift.
    Geometry,
    /// Doppler colour shift, brightness normalised (Fig. 6 left).
    Doppler,
    /// Doppler shift and searchlight effect (Fig. 6 right).
    Searchlight,
}

/// Options of `srt render`.
#[derive(Debug, Clone, Args)]
pub struct RenderArgs {
    /// Built-in scene name (see `srt scenes`), scene file (.toml) or model file.
    #[arg(default_value = "fig10-cube50")]
    pub scene: String,
    /// Output image: .png (8-bit sRGB) or .exr (linear light, 32-bit float). With --frames, a
    /// frame number is inserted before the extension. Default: SCENE.png in the current folder.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Image width in pixels.
    #[arg(long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub height: u32,
    /// Renderer.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    pub backend: Backend,
    /// Rendering method.
    #[arg(long, value_enum, default_value_t = MethodArg::Lrt)]
    pub method: MethodArg,
    /// Effect mode (overrides the scene's).
    #[arg(long, value_enum)]
    pub effects: Option<EffectsArg>,
    /// Observation time ct_obs (overrides the scene's).
    #[arg(long, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// Velocity X,Y,Z in units of c given to every object (overrides the scene's; a bare model
    /// without it approaches the observer at 0.9c).
    #[arg(long, value_parser = parse_vector, allow_hyphen_values = true)]
    pub beta: Option<DVec3>,
    /// Samples per pixel (antialiasing). The GPU renders ⌈√N⌉² samples on a regular grid.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub samples: u32,
    /// Render an animation of N frames, sweeping the observation time from --t0 to --t1.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// First observation time of an animation (default: the scene's time).
    #[arg(long, allow_hyphen_values = true)]
    pub t0: Option<f64>,
    /// Last observation time of an animation (default: first + 10).
    #[arg(long, allow_hyphen_values = true)]
    pub t1: Option<f64>,
}

impl Default for RenderArgs {
    fn default() -> Self {
        Self {
            scene: "fig10-cube50".into(),
            output: None,
            width: 1280,
            height: 720,
            backend: Backend::Auto,
            method: MethodArg::Lrt,
            effects: None,
            time: None,
            beta: None,
            samples: 1,
            frames: None,
            t0: None,
            t1: None,
        }
    }
}

/// Parses "X,Y,Z" into a vector of finite numbers.
fn parse_vector(text: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!(
            "expected three comma-separated numbers X,Y,Z, got {text:?}"
        ));
    };
    let number = |s: &str| -> Result<f64, String> {
        let v: f64 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(format!("{s:?} is not a finite number"))
        }
    };
    Ok(DVec3::new(number(x)?, number(y)?, number(z)?))
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory as _;

    use super::Cli;

    /// The `render` help names the model formats the resolver accepts, in its order.
    #[test]
    fn render_help_lists_the_resolvers_model_extensions() {
        let command = Cli::command();
        let render = command
            .find_subcommand("render")
            .expect("a render subcommand");
        let about = render.get_about().expect("render has help").to_string();
        let listed = format!("({})", srt_scene::resolve::model_extension_list());
        assert!(
            about.contains(&listed),
            "`srt render` help {about:?} should list {listed}"
        );
    }

    /// A negative vector is ordinary input for `--beta`.
    #[test]
    fn negative_components_parse() {
        let vector = super::parse_vector("-0.9, 0,-1e-3").expect("parses");
        assert_eq!(vector, glam::DVec3::new(-0.9, 0.0, -1e-3));
    }
}

//! Command-line syntax of `srt` (clap).

use std::path::PathBuf;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand};
use glam::DVec3;
use srt::engine::{Backend, MAX_IMAGE_SIDE, MAX_SAMPLES};
use srt_gpu::Method;
use srt_scene::{Choice, Effects, Projection, Setting, SurfaceColour, View, parse_vector};

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
    Render(Box<RenderArgs>),
    /// List the built-in scenes, one line each; `--show NAME` prints one scene's file with its
    /// explanation, ready to copy and edit (`srt scenes --show fig4 > mine.toml`).
    Scenes {
        /// The built-in scene whose file to print.
        #[arg(long, value_name = "NAME")]
        show: Option<String>,
    },
    /// Join rendered frames (PNG or EXR, in the order given) into a video: .mp4 (H.264) or .gif.
    Encode(EncodeArgs),
    /// Print how an image or video was made: the scene, time, velocities, effects and renderer
    /// that srt records in every PNG, EXR, MP4 and GIF it writes.
    Info {
        /// A PNG or EXR image, or an MP4 or GIF video, written by `srt render` or `srt encode`.
        image: PathBuf,
    },
    /// Open the interactive viewer: SCENE_OR_MODEL... (default `teaser`); further models are
    /// added to the first scene.
    View {
        /// Built-in scene names, scene files (.toml) or model files.
        scenes: Vec<String>,
    },
}

impl Default for Command {
    fn default() -> Self {
        Self::Render(Box::default())
    }
}

/// A clap parser for one of the library's named choices ([`Choice`]): its names, each with its
/// help, are the possible values, so that the names and their meanings live in one place.
fn choice<T: Choice + Send + Sync>() -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(
        T::all()
            .iter()
            .map(|value| PossibleValue::new(value.name()).help(value.help())),
    )
    .try_map(|name| T::parse(&name))
}

/// Options of `srt render`.
#[derive(Debug, Clone, Args)]
pub struct RenderArgs {
    /// Built-in scene name (see `srt scenes`), scene file (.toml) or model file.
    #[arg(default_value = "fig10-cube50")]
    pub scene: String,
    /// Output: .png (8-bit sRGB) or .exr (linear light, 32-bit float) images, or with --frames a
    /// video, .mp4 (H.264) or .gif. With --frames, a frame number is inserted before an image's
    /// extension. Default: SCENE.png in the current folder.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Image width in pixels.
    #[arg(long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE)))]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE)))]
    pub height: u32,
    /// Renderer.
    #[arg(long, value_parser = choice::<Backend>(), default_value_t = Backend::Auto)]
    pub backend: Backend,
    /// Rendering method.
    #[arg(long, value_parser = choice::<Method>(), default_value_t = Method::Auto)]
    pub method: Method,
    /// Effect mode (overrides the scene's).
    #[arg(long, value_parser = choice::<Effects>())]
    pub effects: Option<Effects>,
    /// How lit surfaces are coloured (overrides the scene's `render.colour`).
    #[arg(long, value_parser = choice::<SurfaceColour>())]
    pub colour: Option<SurfaceColour>,
    /// Multiplier on the light before the tone map, > 0 (spectral colour only; overrides the
    /// scene's `render.exposure`).
    #[arg(long)]
    pub exposure: Option<f64>,
    /// Picture to draw: seen (apparent), measured (contracted, simultaneous in the observer's
    /// frame) or newtonian (rest shape where it is now); the last two are static, Doppler factor 1.
    #[arg(long, value_parser = choice::<View>(), default_value_t = View::Seen)]
    pub view: View,
    /// The observation time: the observer's own clock when it looks (overrides the scene
    /// file's `observer.time`; its `ct` is W's time at `position`).
    #[arg(long, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// Velocity X,Y,Z in units of c given to every object (overrides the scene's; a bare model
    /// without it approaches the observer at 0.9c).
    #[arg(long, value_parser = parse_vector, allow_hyphen_values = true)]
    pub beta: Option<DVec3>,
    /// Velocity X,Y,Z in units of c of the observer through the scene's world frame (overrides
    /// the scene's `observer.beta`); objects keep their velocities relative to the world.
    #[arg(long, value_parser = parse_vector, allow_hyphen_values = true)]
    pub observer_beta: Option<DVec3>,
    /// How the image maps pixels to directions: perspective (the scene's field of view),
    /// equirectangular (the whole sphere, W = 2H), fisheye (180°, a dome master) or
    /// fisheye:FOV (overrides the scene's `observer.projection`).
    #[arg(long, value_name = "PROJECTION", value_parser = parse_projection)]
    pub projection: Option<Projection>,
    /// Give any scene file key a value, e.g. `--set observer.fov_y_deg=60`,
    /// `--set object.cube.beta=0,0.5,0` (an object by its name or index from 0),
    /// `--set render.colour=spectral`; repeatable, applied in order before the options above. The
    /// value is TOML (a bare word is a string, numbers with commas an array), judged by the scene
    /// file's own rules (docs/scene-format.md).
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_setting)]
    pub settings: Vec<Setting>,
    /// Texels a side of each face of the image-based method's cube map (`--method
    /// image-based`; overrides the scene's `render.cube_map_size`, default 2048, the paper's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(srt_scene::MAX_CUBE_MAP_SIZE)))]
    pub cube_map_size: Option<u32>,
    /// Samples per pixel (antialiasing). The GPU renders ⌈√N⌉² samples on a regular grid.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_SAMPLES)))]
    pub samples: u32,
    /// Burn a caption into the bottom of the picture: scene, the observer's time, each object's
    /// velocity, view, effects and renderer (the display colours only: an EXR's radiance stays
    /// data).
    #[arg(long)]
    pub caption: bool,
    /// Add per-pixel channels to an EXR beside R, G, B: what each pixel sees of time
    /// (emission_ct, proper_time, distance, doppler, object; docs/scene-format.md).
    #[arg(long)]
    pub aov: bool,
    /// Render an animation of N frames, sweeping the observation time from --t0 to --t1.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// First observation time of an animation (default: the scene's time); needs --frames.
    #[arg(long, allow_hyphen_values = true)]
    pub t0: Option<f64>,
    /// Last observation time of an animation (default: first + 10); needs --frames.
    #[arg(long, allow_hyphen_values = true)]
    pub t1: Option<f64>,
    /// Render only share K of N of the frames (K counts from 1): frames i with i mod N = K − 1,
    /// as numbered images. Every share's frames are byte for byte those of an unsharded run; see
    /// docs/cluster.md.
    #[arg(long, value_name = "K/N", value_parser = parse_shard)]
    pub shard: Option<ShardArg>,
    /// Video options.
    #[command(flatten)]
    pub video: VideoArgs,
}

/// `--shard K/N` as typed: two whole numbers (their range is checked by `srt render`, which can
/// say what is wrong in one line).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShardArg {
    /// K, the share to render (1-based).
    pub index: u32,
    /// N, the number of shares.
    pub count: u32,
}

/// Options of the videos `srt render` and `srt encode` write.
#[derive(Debug, Clone, Copy, Default, Args)]
pub struct VideoArgs {
    /// Frames per second of a video (.mp4 or .gif; default 24; a GIF stores delays in 1/100 s,
    /// so 24 fps plays at 25).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=120))]
    pub fps: Option<u32>,
}

impl VideoArgs {
    /// The frame rate: `--fps`, or [`DEFAULT_FPS`].
    #[must_use]
    pub fn fps(self) -> u32 {
        self.fps.unwrap_or(DEFAULT_FPS)
    }
}

/// The frame rate of videos unless `--fps` says otherwise.
pub const DEFAULT_FPS: u32 = 24;

/// Options of `srt encode`.
#[derive(Debug, Clone, Args)]
pub struct EncodeArgs {
    /// The frames, in playing order (a shell glob such as frames_*.png sorts numbered frames).
    #[arg(required = true, value_name = "FRAME")]
    pub frames: Vec<PathBuf>,
    /// The video to write: .mp4 (H.264) or .gif.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Video options.
    #[command(flatten)]
    pub video: VideoArgs,
}

impl Default for RenderArgs {
    fn default() -> Self {
        Self {
            scene: "fig10-cube50".into(),
            output: None,
            width: 1280,
            height: 720,
            backend: Backend::Auto,
            method: Method::Auto,
            effects: None,
            colour: None,
            exposure: None,
            view: View::Seen,
            time: None,
            beta: None,
            observer_beta: None,
            projection: None,
            settings: Vec::new(),
            cube_map_size: None,
            samples: 1,
            caption: false,
            aov: false,
            frames: None,
            t0: None,
            t1: None,
            shard: None,
            video: VideoArgs::default(),
        }
    }
}

/// Parses "K/N" into two whole numbers.
fn parse_shard(text: &str) -> Result<ShardArg, String> {
    let parse = |part: &str| part.trim().parse::<u32>().ok();
    match text.split_once('/') {
        Some((index, count)) => match (parse(index), parse(count)) {
            (Some(index), Some(count)) => Ok(ShardArg { index, count }),
            _ => Err(format!("expected K/N with two whole numbers, got {text:?}")),
        },
        None => Err(format!(
            "expected K/N (share K of N, e.g. 2/8), got {text:?}"
        )),
    }
}

/// `--set KEY=VALUE` as typed (srt-scene's [`Setting`] parser).
fn parse_setting(text: &str) -> Result<Setting, String> {
    text.parse()
}

/// `--projection` as typed: `perspective`, `equirectangular`, `fisheye` or `fisheye:FOV`
/// (srt-scene's one parser, which Python's `projection=` and the page's `projection=` use too).
fn parse_projection(text: &str) -> Result<Projection, String> {
    text.parse()
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

    /// `--shard` takes K/N as two whole numbers; their range is `srt render`'s to judge.
    #[test]
    fn shard_parses_two_whole_numbers() {
        let shard = super::parse_shard("2/8").expect("parses");
        assert_eq!((shard.index, shard.count), (2, 8));
        let zero = super::parse_shard("0/0").expect("parses; refused later");
        assert_eq!((zero.index, zero.count), (0, 0));
        for bad in ["2", "2/", "a/3", "1/-2", "1.5/3"] {
            assert!(super::parse_shard(bad).is_err(), "{bad} parsed");
        }
    }

    /// A negative vector is ordinary input for `--beta`.
    #[test]
    fn negative_components_parse() {
        let vector = srt_scene::parse_vector("-0.9, 0,-1e-3").expect("parses");
        assert_eq!(vector, glam::DVec3::new(-0.9, 0.0, -1e-3));
    }

    /// `--observer-beta` takes a vector, negative components included; a non-number is refused.
    #[test]
    fn observer_beta_parses_a_vector() {
        use clap::Parser as _;
        let parsed =
            Cli::try_parse_from(["srt", "render", "fig7", "--observer-beta", "-0.5,0,0.1"])
                .expect("parses");
        let Some(super::Command::Render(args)) = parsed.command else {
            panic!("not a render command");
        };
        assert_eq!(args.observer_beta, Some(glam::DVec3::new(-0.5, 0.0, 0.1)));
        assert!(Cli::try_parse_from(["srt", "render", "--observer-beta", "0,nan,0"]).is_err());
    }
}

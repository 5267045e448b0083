//! `srt render`: resolve the scene with the command-line overrides (applied by srt-scene to its
//! description, [`srt_scene::Overrides`]), choose the backend, render one image, a share of an
//! animation's numbered frames, or a video, and write it with a record of how it was made.

use std::borrow::Cow;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

use std::sync::atomic::AtomicBool;

use crate::caption::{Captioner, Ink};
use anyhow::{Context as _, bail};
use glam::DVec3;
use image::RgbImage;
use srt::empty::ObjectsSeen;
use srt::engine::{Engine, Frame};
use srt::software::Job;
use srt_scene::description::observation_time;
use srt_scene::{Editor, OverrideNames, Overrides, Projection, Scene, Setting, ValueName, View};
use srt_trace::{Output, RenderSettings};

use crate::cli::RenderArgs;
use crate::output::{
    Band, Layers, OutputFormat, bands, check_writable, display_bytes, numbered, write_image,
};
use crate::progress::DelayedBar;
use crate::provenance::Provenance;
use crate::shard::Shard;
use crate::source::{SceneOrigin, load_scene};
use srt_video::{StereoMode, VideoWriter, check_size};

/// What an animation writes: numbered images (this machine's share of them) or one video.
enum Animation {
    /// Numbered images of the frames of `shard`.
    Images(Shard),
    /// A video of all frames.
    Video,
}

/// Runs `srt render`.
///
/// # Errors
/// Any user-facing failure: unknown scene, bad file, bad override, bad --frames/--shard
/// combination, no GPU for `--backend gpu`, unwritable output.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    // A named output and the animation options are checked before the scene is even loaded: a
    // typo in -o must not cost a model import and a render.
    if let Some(output) = &args.output {
        check_writable(output)?;
    }
    let animation = check_animation(args)?;
    let loaded = load_scene(&args.scene, &overrides(args))?;
    for warning in &loaded.warnings {
        eprintln!("warning: {warning}");
    }
    let mut editor = loaded.editor;
    let scene = editor.scene();
    // The paper's scenes are drawn in the paper's colour on purpose, as is a scene with
    // --colour paper; a user's own scene that loses colours is told.
    let colour_chosen = args.colour.is_some() || loaded.origin.is_builtin();
    if let Some(note) = scene.paper_colour_note().filter(|_| !colour_chosen) {
        eprintln!("note: {note}");
    }
    let output = match &args.output {
        Some(output) => output.clone(),
        None => {
            let output = PathBuf::from(format!("{}.png", file_safe(&scene.name)));
            check_writable(&output)?;
            output
        }
    };
    let settings = settings_of(args);
    scene
        .check_picture_size(settings.width, settings.height)
        .map_err(anyhow::Error::msg)?;
    let view = args.view;
    // The GPU uploads geometry once; a view's shapes do not depend on the time (only offsets
    // do), so the scene viewed at its own time serves every frame.
    let first = viewed(view, scene)?;
    let first_frame = Frame::new(&first);
    let job = Job {
        settings,
        frames: args.frames.unwrap_or(1),
        passes: 1 + u32::from(args.aov),
    };
    let mut engine = choose_engine(args, &job, &first_frame)?;
    let record = base_record(
        &loaded.origin,
        loaded.observer_beta,
        scene,
        &engine,
        settings,
        view,
    );
    let (Some(frames), Some(animation)) = (args.frames, animation) else {
        let start = Instant::now();
        let record = record.with(&[("time", format!("{:?}", scene.observer.time))]);
        let captioner = captioner(args, loaded.observer_beta, &engine);
        let picture = Picture {
            frame: &first_frame,
            captioned: scene,
            captioner: captioner.as_ref(),
            settings,
            show_rows: true,
        };
        let objects = picture.write(&mut engine, &record, args.aov, &output)?;
        if let Some(warning) = objects.empty_warning(&first) {
            eprintln!("warning: {warning}");
        }
        println!("{}", wrote(&output, settings, &engine, start));
        return Ok(());
    };
    // The animation's ends follow observer.time's rule; every frame's time lies between them.
    let t0 = observation_time(ValueName::Option("--t0"), args.t0.unwrap_or(editor.time()))?;
    let t1 = observation_time(ValueName::Option("--t1"), args.t1.unwrap_or(t0 + 10.0))?;
    let sweep = Sweep {
        frames,
        t0,
        t1,
        view,
        captioner: captioner(args, loaded.observer_beta, &engine),
    };
    match animation {
        Animation::Images(shard) => render_numbered(
            &mut engine,
            &mut editor,
            &sweep,
            shard,
            &output,
            &record,
            args,
        ),
        Animation::Video => render_video(&mut engine, &mut editor, &sweep, &output, &record, args),
    }
}

/// An animation's frames: `frames` observation times from `t0` to `t1`, in `view`, each
/// captioned by `captioner` if there is one.
struct Sweep {
    frames: u32,
    t0: f64,
    t1: f64,
    view: View,
    captioner: Option<Captioner>,
}

impl Sweep {
    /// Sets `editor`'s scene to frame `frame`'s time; the scene then, and the frame's scene in
    /// the sweep's view.
    fn frame_scene<'e>(
        &self,
        editor: &'e mut Editor,
        frame: u32,
    ) -> anyhow::Result<(&'e Scene, Cow<'e, Scene>)> {
        editor.set_time(self.time_of(frame))?;
        let editor: &'e Editor = editor;
        Ok((editor.scene(), viewed(self.view, editor.scene())?))
    }

    /// The picture of one frame of the sweep: `frame`, captioned from `scene` (the frame's
    /// scene before its view is applied).
    fn picture<'p, 'f>(
        &'p self,
        frame: &'p Frame<'f>,
        scene: &'p Scene,
        settings: RenderSettings,
    ) -> Picture<'p, 'f> {
        Picture {
            frame,
            captioned: scene,
            captioner: self.captioner.as_ref(),
            settings,
            show_rows: false,
        }
    }

    /// The observation time of frame `frame` (0-based): evenly spaced, the last at `t1`.
    fn time_of(&self, frame: u32) -> f64 {
        let fraction = if self.frames > 1 {
            f64::from(frame) / f64::from(self.frames - 1)
        } else {
            0.0
        };
        self.t0 + fraction * (self.t1 - self.t0)
    }

    /// `record` for frame `frame` of the sweep: its observation time and number.
    fn frame_record(&self, record: &Provenance, frame: u32) -> Provenance {
        record.with(&[
            ("time", format!("{:?}", self.time_of(frame))),
            ("frame", format!("{frame} of 0 to {}", self.frames - 1)),
        ])
    }
}

/// One picture to render and write a band of rows at a time, so that it is never held whole
/// on the CPU (docs/performance.md, "Memory").
struct Picture<'p, 'f> {
    /// The frame: the scene in its view.
    frame: &'p Frame<'f>,
    /// The scene the caption describes (before its view is applied: its velocities are the
    /// objects').
    captioned: &'p Scene,
    /// The caption's maker, with `--caption`.
    captioner: Option<&'p Captioner>,
    /// Size and samples.
    settings: RenderSettings,
    /// Whether to show the CPU's row progress (single images; animations count frames).
    show_rows: bool,
}

impl Picture<'_, '_> {
    /// Renders the picture with `engine` and writes it to `path` with `record` (an EXR with its
    /// radiance, and with `aov` its time channels); whether it showed an object.
    fn write(
        &self,
        engine: &mut Engine,
        record: &Provenance,
        aov: bool,
        path: &Path,
    ) -> anyhow::Result<ObjectsSeen> {
        let settings = self.settings;
        let layers = Layers::for_path(path, aov);
        let mut objects = ObjectsSeen::default();
        let bar = self.row_bar(engine);
        let band_rows = engine.band_rows(settings);
        let ink = self.ink();
        let never = AtomicBool::new(false);
        let finished = "a render that is never stopped finishes";
        write_image(
            (settings.width, settings.height),
            band_rows,
            layers,
            record,
            path,
            &mut |rows| {
                let display = self.display_band(
                    engine,
                    rows.clone(),
                    ink.as_ref(),
                    &mut objects,
                    bar.as_ref(),
                )?;
                let radiance = layers
                    .radiance
                    .then(|| {
                        engine.render_band(
                            self.frame,
                            settings,
                            rows.clone(),
                            Output::Radiance,
                            &|_| {},
                            &never,
                        )
                    })
                    .transpose()?
                    .map(|pixels| pixels.expect(finished));
                let seen = layers
                    .seen
                    .then(|| {
                        engine.render_aov_band(self.frame, settings, rows.clone(), &|_| {}, &never)
                    })
                    .transpose()?
                    .map(|values| values.expect(finished));
                Ok(Band {
                    display,
                    radiance,
                    seen,
                })
            },
        )?;
        if let Some(bar) = bar {
            bar.finish();
        }
        Ok(objects)
    }

    /// Renders the picture's display colours into an 8-bit image, a band of rows at a time
    /// (for a video's frame); whether it showed an object.
    fn rgb8(&self, engine: &mut Engine) -> anyhow::Result<(RgbImage, ObjectsSeen)> {
        let settings = self.settings;
        let mut objects = ObjectsSeen::default();
        let ink = self.ink();
        let mut bytes = Vec::with_capacity(3 * settings.width as usize * settings.height as usize);
        for rows in bands(settings.height, engine.band_rows(settings)) {
            let display = self.display_band(engine, rows, ink.as_ref(), &mut objects, None)?;
            bytes.extend_from_slice(&display_bytes(&display));
        }
        let image = RgbImage::from_raw(settings.width, settings.height, bytes)
            .expect("one colour per pixel");
        Ok((image, objects))
    }

    /// The display colours of `rows`, the pixels among them that show an object noted in
    /// `objects`, with `ink` (the caption) burnt into them; `bar` shows the rows finished.
    fn display_band(
        &self,
        engine: &mut Engine,
        rows: Range<u32>,
        ink: Option<&Ink>,
        objects: &mut ObjectsSeen,
        bar: Option<&DelayedBar>,
    ) -> anyhow::Result<Vec<DVec3>> {
        let never = AtomicBool::new(false);
        let first_row = rows.start;
        let progress = |done: u32| {
            if let Some(bar) = bar {
                bar.set_position(u64::from(first_row + done));
            }
        };
        let drawn = engine
            .draw_band(
                self.frame,
                self.settings,
                rows.clone(),
                Output::Display,
                &progress,
                &never,
            )?
            .expect("a render that is never stopped finishes");
        objects.look_at(&drawn.seen);
        let mut display = drawn.pixels;
        if let Some(ink) = ink {
            ink.burn_into_rows(&mut display, self.settings.width, rows);
        }
        Ok(display)
    }

    /// The caption laid out for the picture, with `--caption`.
    fn ink(&self) -> Option<Ink> {
        (self.captioner).map(|captioner| {
            captioner.ink_for(self.captioned, self.settings.width, self.settings.height)
        })
    }

    /// The bar showing the CPU's finished rows, for a single image.
    fn row_bar(&self, engine: &Engine) -> Option<DelayedBar> {
        (self.show_rows && matches!(engine, Engine::Cpu)).then(|| {
            DelayedBar::new(
                u64::from(self.settings.height),
                "rows",
                format!("rendering {}", self.frame.scene().name),
            )
        })
    }
}

/// Renders `shard`'s share of the sweep as numbered images beside `output`.
fn render_numbered(
    engine: &mut Engine,
    editor: &mut Editor,
    sweep: &Sweep,
    shard: Shard,
    output: &Path,
    record: &Provenance,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    let settings = settings_of(args);
    let frames = sweep.frames;
    let digits = frames.to_string().len().max(4);
    let share: Vec<u32> = shard.frames(frames).collect();
    if share.is_empty() {
        println!(
            "share {}/{} gets none of the {frames} frames; nothing to render",
            shard.index(),
            shard.count()
        );
    }
    let bar = DelayedBar::new(
        share.len() as u64,
        "frames",
        format!("rendering {}", editor.scene().name),
    );
    let mut empty = EmptyFrames::default();
    for frame in share {
        let frame_start = Instant::now();
        let (scene, frame_scene) = sweep.frame_scene(editor, frame)?;
        let record = sweep.frame_record(record, frame);
        let path = numbered(output, frame, digits);
        let frame_of = Frame::new(&frame_scene);
        let objects = sweep
            .picture(&frame_of, scene, settings)
            .write(engine, &record, args.aov, &path)?;
        empty.look_at(&frame_scene, &objects);
        bar.println(&wrote(&path, settings, engine, frame_start));
        bar.inc();
    }
    bar.finish();
    empty.report();
    Ok(())
}

/// Whether every frame of an animation showed no object ([`empty_picture_warning`]), and why the
/// first did.
#[derive(Default)]
struct EmptyFrames {
    /// The first frame's warning, while every frame so far was empty.
    first: Option<String>,
    /// Whether some frame showed an object.
    some_seen: bool,
}

impl EmptyFrames {
    /// Takes one frame of `scene` into account, whose pixels showed `objects`.
    fn look_at(&mut self, scene: &Scene, objects: &ObjectsSeen) {
        if self.some_seen {
            return;
        }
        match objects.empty_warning(scene) {
            Some(warning) => {
                self.first.get_or_insert(warning);
            }
            None => {
                self.some_seen = true;
                self.first = None;
            }
        }
    }

    /// Warns when every frame was empty.
    fn report(&self) {
        if let Some(first) = &self.first {
            eprintln!("warning: every frame is empty; the first: {first}");
        }
    }
}

/// Renders the sweep as one video, `output`, holding `record` for all its frames
/// ([`Provenance::for_video`]).
fn render_video(
    engine: &mut Engine,
    editor: &mut Editor,
    sweep: &Sweep,
    output: &Path,
    record: &Provenance,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    let start = Instant::now();
    let settings = settings_of(args);
    let mut video = VideoWriter::create(output, settings.width, settings.height, args.video.fps())?;
    let whole = Provenance::for_video(
        &sweep.frame_record(record, 0),
        &sweep.frame_record(record, sweep.frames - 1),
        sweep.frames as usize,
        args.video.fps(),
        "rendered by srt render",
    );
    video.set_comment(&whole.to_text());
    if editor.scene().observer.projection == Projection::Equirectangular {
        // 360° players show it around the viewer (the Spherical Video V2 boxes of an MP4), the
        // left eye's picture above the right eye's for a stereo pair.
        video.set_spherical(if editor.scene().observer.stereo.is_some() {
            StereoMode::TopBottom
        } else {
            StereoMode::Mono
        });
    }
    let bar = DelayedBar::new(
        u64::from(sweep.frames),
        "frames",
        format!("rendering {}", editor.scene().name),
    );
    let mut empty = EmptyFrames::default();
    for frame in 0..sweep.frames {
        let (scene, frame_scene) = sweep.frame_scene(editor, frame)?;
        let frame_of = Frame::new(&frame_scene);
        let (image, objects) = sweep.picture(&frame_of, scene, settings).rgb8(engine)?;
        empty.look_at(&frame_scene, &objects);
        video.push(&image)?;
        bar.inc();
    }
    bar.finish();
    empty.report();
    video.finish()?;
    println!(
        "wrote {} ({} frame{} at {} fps, ct {:?} to {:?}; {})",
        output.display(),
        sweep.frames,
        if sweep.frames == 1 { "" } else { "s" },
        args.video.fps(),
        sweep.t0,
        sweep.t1,
        details(settings, engine, start)
    );
    Ok(())
}

/// The caption's maker when `--caption` asks for one.
fn captioner(args: &RenderArgs, observer_beta: DVec3, engine: &Engine) -> Option<Captioner> {
    args.caption.then(|| Captioner {
        observer_beta,
        view: args.view,
        renderer: match engine {
            Engine::Cpu => "cpu".to_owned(),
            Engine::Gpu { method, .. } => format!("gpu {}", method.name()),
        },
    })
}

/// The picture size and samples the options ask for.
const fn settings_of(args: &RenderArgs) -> RenderSettings {
    RenderSettings {
        width: args.width,
        height: args.height,
        samples: args.samples,
    }
}

/// Checks --frames, --shard and a video output against each other and the picture size, before
/// anything is loaded; returns what an animation writes (`None` without --frames).
fn check_animation(args: &RenderArgs) -> anyhow::Result<Option<Animation>> {
    let format = args
        .output
        .as_deref()
        .map(OutputFormat::for_path)
        .transpose()?;
    let shard = args.shard.map(Shard::new).transpose()?;
    if args.frames.is_none() {
        let given = [("--t0", args.t0), ("--t1", args.t1)];
        if let Some((option, _)) = given.iter().find(|(_, value)| value.is_some()) {
            bail!(
                "{option} sweeps an animation's time and needs --frames N; for one picture at \
                 one time, give --time T"
            );
        }
    }
    if args.aov && format != Some(OutputFormat::Exr) {
        let output = args.output.as_ref().map_or_else(
            || "the default SCENE.png".to_owned(),
            |output| output.display().to_string(),
        );
        bail!(
            "--aov writes per-pixel channels into an OpenEXR image, not into {output}: give -o \
             NAME.exr"
        );
    }
    match (&args.output, format) {
        (Some(output), Some(format)) if let Some(video) = format.video() => {
            if args.frames.is_none() {
                bail!(
                    "-o {}: a video needs the number of frames, --frames N",
                    output.display()
                );
            }
            if args.shard.is_some() {
                bail!(
                    "--shard renders numbered images, not a video: render the shares to -o \
                     NAME.png, then join the frames with `srt encode NAME_*.png -o {}`",
                    output.display()
                );
            }
            check_size(output, video, args.width, args.height, "--width x --height")?;
            Ok(Some(Animation::Video))
        }
        _ if args.video.fps.is_some() => bail!(
            "--fps sets a video's frame rate: give --frames N and -o NAME.mp4 or NAME.gif (numbered \
             images have none)"
        ),
        _ => match (args.frames, shard) {
            (None, Some(_)) => bail!("--shard shares the frames of an animation: give --frames N"),
            (None, None) => Ok(None),
            (Some(_), shard) => Ok(Some(Animation::Images(shard.unwrap_or(Shard::WHOLE)))),
        },
    }
}

/// The provenance entries every frame of this render shares (all but time and frame number).
/// `origin` and `observer_beta` describe the scene as loaded, `scene` the one rendered
/// (overrides applied): object velocities are relative to the observer.
fn base_record(
    origin: &SceneOrigin,
    observer_beta: DVec3,
    scene: &Scene,
    engine: &Engine,
    settings: RenderSettings,
    view: View,
) -> Provenance {
    let mut record = Provenance::new();
    record.push("scene", origin.description.clone());
    if let Some(sha256) = &origin.sha256 {
        record.push("scene sha256", sha256.clone());
    }
    // Exact (round-trip) components; + 0.0 turns a negative zero into 0.0.
    let velocity = |beta: DVec3| {
        let beta = beta + DVec3::ZERO;
        format!("({:?}, {:?}, {:?})", beta.x, beta.y, beta.z)
    };
    record.push("observer velocity", velocity(observer_beta));
    let velocities: Vec<String> = scene
        .objects
        .iter()
        .map(|object| format!("{} {}", object.name, velocity(object.frame.beta())))
        .collect();
    record.push("velocities", velocities.join("; "));
    record.push("effects", scene.effects.name());
    record.push("tone map", scene.tone_map.name());
    record.push("colour", scene.colour.name());
    record.push("exposure", format!("{:?}", scene.exposure));
    record.push("view", view.name());
    for (key, value) in engine.record_entries() {
        record.push(key, value);
    }
    record.push("size", format!("{}x{}", settings.width, settings.height));
    record.push("samples", settings.samples.to_string());
    record
}

/// "wrote PATH (DETAILS)".
fn wrote(path: &Path, settings: RenderSettings, engine: &Engine, start: Instant) -> String {
    format!(
        "wrote {} ({})",
        path.display(),
        details(settings, engine, start)
    )
}

/// "W×H, N samples per pixel, ENGINE, T s" (T: seconds since `start`).
fn details(settings: RenderSettings, engine: &Engine, start: Instant) -> String {
    format!(
        "{}x{}, {} sample{} per pixel, {}, {:.2} s",
        settings.width,
        settings.height,
        settings.samples,
        if settings.samples == 1 { "" } else { "s" },
        engine.name(),
        start.elapsed().as_secs_f64()
    )
}

/// `scene` as `view` shows it at its current observation time (applied per frame, after the
/// frame's time is set: the measured and Newtonian positions depend on the observation time).
fn viewed(view: View, scene: &Scene) -> anyhow::Result<Cow<'_, Scene>> {
    if view == View::Seen {
        // The picture srt renders anyway: no copy of the meshes per frame.
        return Ok(Cow::Borrowed(scene));
    }
    let viewed = view.apply(scene).with_context(|| {
        format!(
            "cannot draw scene {} in the {} view",
            scene.name,
            view.name()
        )
    })?;
    Ok(Cow::Owned(viewed))
}

/// The scene overrides among the options (--set, --effects, --colour, --exposure, --time,
/// --beta, --observer-beta, --projection, --cube-map-size: a `render.cube_map_size` setting
/// after the --set ones), for srt-scene's resolver to apply to the description.
fn overrides(args: &RenderArgs) -> Overrides {
    let mut settings = args.settings.clone();
    settings.extend(args.cube_map_size.map(|size| {
        format!("render.cube_map_size={size}")
            .parse::<Setting>()
            .expect("a key and a whole number")
    }));
    Overrides {
        effects: args.effects,
        colour: args.colour,
        exposure: args.exposure,
        time: args.time,
        beta: args.beta,
        observer_beta: args.observer_beta,
        projection: args.projection,
        settings,
        names: OverrideNames::COMMAND_LINE,
    }
}

/// A name usable as a file name.
fn file_safe(name: &str) -> String {
    let cleaned: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if cleaned.is_empty() {
        "render".into()
    } else {
        cleaned
    }
}

/// Picks the renderer for --backend and --method (a note on standard error when `auto` falls
/// back to the CPU or weighs a software adapter against it).
fn choose_engine(args: &RenderArgs, job: &Job, first: &Frame<'_>) -> anyhow::Result<Engine> {
    let chosen = Engine::choose(args.backend, args.method, job, first)?;
    if let Some(note) = chosen.note {
        eprintln!("note: {note}");
    }
    Ok(chosen.engine)
}

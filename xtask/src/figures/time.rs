//! Film strips of the scenes that show time (issue 21): a built-in scene rendered at a row of
//! observation times by the reference, `srt-trace`. `beacon_blinks.png`: three beacons with the
//! same clockwork, blinking by their own proper time — the approaching one is seen to blink about
//! twice as fast as the one at rest and the receding one half as fast, the Doppler factor of
//! time. `clocks_seen.png`: clocks at rest and a train of clocks passing at 0.9c — each face
//! shows the proper time of the event seen, so the passing clocks are dilated, and every fast
//! hand is bent by the light delay across its face. `shadows_late.png`: a light flying at 0.9c
//! behind a row of columns — each ground point is lit by the light as it was at its retarded
//! event, so the shadows are curved and point away from where the light was, not where it is.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use image::imageops;
use srt_scene::builtin::find_builtin;

use super::render_panel;
use crate::plot::{BLACK, Canvas, WHITE};

const TITLE_LINE: u32 = 26;
const LABEL_HEIGHT: u32 = 22;

/// One film strip: `scene` at `columns × rows` observation times `first + k · step`.
struct FilmStrip {
    scene: &'static str,
    file: &'static str,
    title: &'static [&'static str],
    panel: (u32, u32),
    columns: u32,
    rows: u32,
    first: f64,
    step: f64,
}

const STRIPS: [FilmStrip; 3] = [
    FilmStrip {
        scene: "beacon",
        file: "beacon_blinks.png",
        title: &[
            "beacon: each sphere glows for half of every unit of its own proper time ct'",
            "left: approaching at 0.6c, seen to blink ~2x as fast (D = 1.96); middle: at rest; \
             right: receding, ~1/2 as fast",
        ],
        panel: (300, 110),
        columns: 4,
        rows: 4,
        first: 0.0,
        step: 0.25,
    },
    FilmStrip {
        scene: "clocks",
        file: "clocks_seen.png",
        title: &[
            "clocks: back row at rest 9 away, front row passing at 0.9c; each face shows the \
             proper time where the light seen left it",
            "the passing clocks are seen dilated and Terrell-rotated (their trailing faces in \
             view); light delay across a face bends each fast hand",
        ],
        panel: (480, 270),
        columns: 2,
        rows: 2,
        first: 10.0,
        step: 0.25,
    },
    FilmStrip {
        scene: "shadows",
        file: "shadows_late.png",
        title: &[
            "shadows: a 5000 K light flies at 0.9c (left to right) behind five columns, a glowing \
             sphere with it",
            "each ground point is lit as the light was when its light left: shadows curve away \
             from where it was; white ahead, yellow behind",
        ],
        panel: (480, 270),
        columns: 2,
        rows: 2,
        first: 10.0,
        step: 6.0,
    },
];

/// Writes every film strip.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    STRIPS.iter().map(|strip| strip.write(out_dir)).collect()
}

impl FilmStrip {
    fn write(&self, out_dir: &Path) -> anyhow::Result<PathBuf> {
        let builtin = find_builtin(self.scene)
            .with_context(|| format!("{} is a built-in scene", self.scene))?;
        let (width, height) = self.panel;
        let title_height = TITLE_LINE * self.title.len() as u32 + 12;
        let cell_height = height + LABEL_HEIGHT;
        let mut canvas = Canvas::new(
            self.columns * (width + 10) + 10,
            title_height + self.rows * cell_height + 10,
            WHITE,
        );
        for (line, text) in self.title.iter().enumerate() {
            canvas.text(
                10.0,
                (8 + TITLE_LINE * line as u32) as f32,
                17.0,
                BLACK,
                text,
            );
        }
        for frame in 0..self.columns * self.rows {
            let ct = self.first + f64::from(frame) * self.step;
            let mut description = builtin.description();
            description.observer.ct = ct;
            let (scene, _) = builtin.build_description(&description)?;
            let panel = render_panel(&scene, width, height);
            let left = 10 + (frame % self.columns) * (width + 10);
            let top = title_height + (frame / self.columns) * cell_height;
            imageops::replace(canvas.image_mut(), &panel, i64::from(left), i64::from(top));
            canvas.text_centred(
                left as f32 + width as f32 / 2.0,
                (top + height + 3) as f32,
                15.0,
                BLACK,
                &format!("ct = {ct:.2}"),
            );
        }
        let path = out_dir.join(self.file);
        canvas.save(&path)?;
        Ok(path)
    }
}

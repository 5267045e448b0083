//! What a frame of the CPU tracer costs on this machine, measured on a few of its rows
//! ([`Tracer::measure_frame`]): the estimate `srt`'s `auto` weighs against a software GPU
//! adapter. The rows measured are rows of the frame, traced as the frame traces them, so a
//! render that follows takes them from the measure instead of tracing them again
//! ([`Tracer::render_band_reusing`]).

use glam::DVec3;
use srt_scene::Scene;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64};
use web_time::Instant;

use crate::render::{
    FrameCost, KnownRows, Output, RenderSettings, RenderedImage, Rows, Tracer, spread_rows,
};

/// Rows of a frame its cost is measured on, by `srt`'s `auto` and the viewer's: about 2 % of a
/// 720-row picture's work, kept in the picture when the CPU then draws it. Fewer miss more:
/// 8 rows put the teaser's 1280 × 720 picture up to 18 % low and Fig. 10's 200-square cube up
/// to 30 % high, where 16 rows stayed within 11 % on the five scenes tried (performance-log.md,
/// 2026-11-29, fourth entry).
pub const PROBE_ROWS: u32 = 16;

/// The most samples a pixel of a measured row traces: a picture of more samples is measured on
/// the first this many of each pixel's samples (a prefix of the same sequence,
/// [`crate::sample_offsets`]) and its rows' cost scaled by the ratio, as every sample of a pixel
/// is one more ray of the same cost. A measure of every sample would cost the same share of the
/// picture at any sample count, time thrown away where the adapter then draws it: the teaser at
/// 320 × 180 with 256 samples spent 0.17 s measuring a 1.7 s picture (docs/performance.md,
/// "auto without a hardware GPU"). Rows measured on fewer samples than the picture's are not
/// the picture's rows, and a render traces them again.
pub const MEASURED_SAMPLES: u32 = 16;

/// Rows traced untimed before a measure: the first rows of a process build shared tables and
/// touch the BVHs' memory, costs a frame pays once, which would weigh on every estimated row.
pub const WARM_UP_ROWS: u32 = 2;

/// A frame's cost measured on some of its rows, with those rows' pixels.
#[derive(Debug, Clone)]
pub struct FrameMeasure {
    /// The size and samples the rows were traced at: the frame's, with at most
    /// [`MEASURED_SAMPLES`] samples.
    settings: RenderSettings,
    /// The frame's samples a pixel for each one the rows traced (1 unless the frame has more
    /// than [`MEASURED_SAMPLES`]).
    samples_per_traced: f64,
    /// What the rows hold.
    output: Output,
    /// Seconds a frame of no rows took.
    setup_seconds: f64,
    /// The timed rows, in order.
    timed_rows: Vec<u32>,
    /// Each timed row's shortest time over the passes, in nanoseconds of its thread's work.
    row_nanoseconds: Vec<u64>,
    /// How many times the timed rows were traced.
    passes: u32,
    /// Every row traced (warm-up and timed), ascending, without repeats.
    rows: Vec<u32>,
    /// Those rows' pixels, in the same order (`height` is their number).
    image: RenderedImage,
}

impl FrameMeasure {
    /// The frame's estimated cost: the setup, and every row at the timed rows' mean, the work
    /// of one row spread over rayon's threads as a frame spreads it.
    #[must_use]
    pub fn cost(&self) -> FrameCost {
        let nanoseconds: u64 = self.row_nanoseconds.iter().sum();
        let threads = rayon::current_num_threads().max(1) as f64;
        FrameCost {
            setup_seconds: self.setup_seconds,
            row_seconds: nanoseconds as f64 * 1e-9 * self.samples_per_traced
                / self.timed_rows.len().max(1) as f64
                / threads,
            rows: self.settings.height,
        }
    }

    /// How many times the timed rows have been traced (1 after [`Tracer::measure_frame`], one
    /// more for each [`Tracer::measure_again`]).
    #[must_use]
    pub const fn passes(&self) -> u32 {
        self.passes
    }

    /// The size and samples the measured rows were traced at: the frame's size, and its samples
    /// up to [`MEASURED_SAMPLES`].
    #[must_use]
    pub const fn settings(&self) -> RenderSettings {
        self.settings
    }

    /// The rows whose pixels the measure holds, ascending.
    #[must_use]
    pub fn rows(&self) -> &[u32] {
        &self.rows
    }

    /// The pixels of row `row` of the frame, if the measure traced it.
    #[must_use]
    pub fn row_pixels(&self, row: u32) -> Option<&[DVec3]> {
        self.known().row(row).map(|(pixels, _)| pixels)
    }

    /// The rows the measure traced, as a render takes them.
    fn known(&self) -> KnownRows<'_> {
        KnownRows {
            rows: &self.rows,
            image: &self.image,
        }
    }

    /// Whether a render of `output` at `settings` is the frame measured (its rows can be
    /// taken from the measure).
    fn serves(&self, settings: RenderSettings, output: Output) -> bool {
        self.settings == settings && self.output == output
    }
}

/// A tracer built for a scene and its display picture measured ([`measure_picture`]): what the
/// viewer and the web page weigh against a software GPU adapter's frame.
pub struct MeasuredPicture<'a> {
    /// The scene's tracer, to draw the picture with.
    pub tracer: Tracer<'a>,
    /// The picture's rows measured, kept for a render that follows.
    pub measure: FrameMeasure,
    /// The picture's estimated seconds: the tracer's build and the frame ([`FrameMeasure::cost`]).
    pub seconds: f64,
}

/// Builds `scene`'s tracer and measures its display picture at `settings` on [`PROBE_ROWS`]
/// rows: the CPU's cost of a frame drawn from scratch, the tracer's build timed on the wall
/// clock (natively the standard library's, in a browser `performance.now()`).
#[must_use]
pub fn measure_picture(scene: &Scene, settings: RenderSettings) -> MeasuredPicture<'_> {
    let start = Instant::now();
    let tracer = Tracer::new(scene);
    let build_seconds = start.elapsed().as_secs_f64();
    let measure = tracer.measure_frame(settings, Output::Display, PROBE_ROWS);
    let seconds = build_seconds + measure.cost().seconds();
    MeasuredPicture {
        tracer,
        measure,
        seconds,
    }
}

impl Tracer<'_> {
    /// Measures what a frame of `output` at `settings` costs on this machine: `sample_rows`
    /// of its rows spread evenly over the image ([`spread_rows`]), each pixel on at most
    /// [`MEASURED_SAMPLES`] of its samples, are traced once, timed,
    /// after [`WARM_UP_ROWS`] rows untimed (which also make the picture's star layer, kept by
    /// the tracer for the render), and a frame of no rows gives the cost that does not grow
    /// with the rows. Each row is traced at full width, its rays as coherent as in a whole
    /// frame, and timed by the thread that traces it, so that what is measured is the rows'
    /// work and not the waking of rayon's threads. A moment in which the machine served
    /// another process can only lengthen a row; [`Tracer::measure_again`] traces the rows again
    /// where that would matter.
    #[must_use]
    pub fn measure_frame(
        &self,
        settings: RenderSettings,
        output: Output,
        sample_rows: u32,
    ) -> FrameMeasure {
        let frame_samples = settings.samples.max(1);
        let settings = RenderSettings {
            samples: frame_samples.min(MEASURED_SAMPLES),
            ..settings
        };
        let warm_up = spread_rows(settings.height, WARM_UP_ROWS);
        let warm_pixels = self.rows_of(settings, &warm_up, output, Rows::Traced);
        let start = Instant::now();
        let _ = self.rows_of(settings, &[], output, Rows::Traced);
        let setup_seconds = start.elapsed().as_secs_f64();
        let timed_rows = spread_rows(settings.height, sample_rows);
        let (timed_pixels, row_nanoseconds) = self.timed(settings, &timed_rows, output);
        // Every row traced, ascending (a warm-up row that is also timed, once).
        let width = settings.width as usize;
        let mut traced: Vec<(u32, &RenderedImage, usize)> = (warm_up.iter().enumerate())
            .map(|(index, &row)| (row, &warm_pixels, index))
            .chain((timed_rows.iter().enumerate()).map(|(index, &row)| (row, &timed_pixels, index)))
            .collect();
        traced.sort_by_key(|&(row, _, _)| row);
        traced.dedup_by_key(|&mut (row, _, _)| row);
        let image = RenderedImage {
            width: settings.width,
            height: traced.len() as u32,
            pixels: (traced.iter())
                .flat_map(|&(_, image, index)| &image.pixels[index * width..][..width])
                .copied()
                .collect(),
            coverage: (traced.iter())
                .flat_map(|&(_, image, index)| &image.coverage[index * width..][..width])
                .copied()
                .collect(),
        };
        let rows = traced.iter().map(|&(row, _, _)| row).collect();
        FrameMeasure {
            settings,
            samples_per_traced: f64::from(frame_samples) / f64::from(settings.samples),
            output,
            setup_seconds,
            timed_rows,
            row_nanoseconds,
            passes: 1,
            rows,
            image,
        }
    }

    /// Traces `measure`'s timed rows once more; each row keeps its shorter time, so that a
    /// moment in which the machine served another process is not taken for the frame's cost.
    pub fn measure_again(&self, measure: &mut FrameMeasure) {
        let (_, again) = self.timed(measure.settings, &measure.timed_rows, measure.output);
        for (kept, new) in measure.row_nanoseconds.iter_mut().zip(again) {
            *kept = (*kept).min(new);
        }
        measure.passes += 1;
    }

    /// [`Tracer::render_band`], taking the rows `known` traced when it measured this frame
    /// ([`Tracer::measure_frame`] at the same settings and output) instead of tracing them
    /// again: the same pixels, bit for bit, as every row is traced alike.
    ///
    /// # Panics
    /// If `rows` reaches past the image's height.
    #[must_use]
    pub fn render_band_reusing(
        &self,
        settings: RenderSettings,
        rows: Range<u32>,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
        known: Option<&FrameMeasure>,
    ) -> Option<RenderedImage> {
        let rows: Vec<u32> = rows.collect();
        let how = match known.filter(|measure| measure.serves(settings, output)) {
            Some(measure) => Rows::Reusing(measure.known()),
            None => Rows::Traced,
        };
        self.render_listed_rows(settings, &rows, progress, output, Some(stop), how)
    }

    /// The rows `rows` of a frame, traced timed: their pixels and each row's nanoseconds of its
    /// thread's work.
    fn timed(
        &self,
        settings: RenderSettings,
        rows: &[u32],
        output: Output,
    ) -> (RenderedImage, Vec<u64>) {
        let work: Vec<AtomicU64> = rows.iter().map(|_| AtomicU64::new(0)).collect();
        let image = self.rows_of(settings, rows, output, Rows::Timed(&work));
        (image, work.into_iter().map(AtomicU64::into_inner).collect())
    }

    /// The rows `rows` of a frame, traced as `how` says.
    fn rows_of(
        &self,
        settings: RenderSettings,
        rows: &[u32],
        output: Output,
        how: Rows<'_>,
    ) -> RenderedImage {
        self.render_listed_rows(settings, rows, &|_| {}, output, None, how)
            .unwrap_or_else(|| unreachable!("rows without a stop flag are all traced"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The teaser at a small size, for the measure's tests.
    fn teaser() -> srt_scene::Scene {
        srt_scene::builtin::find_builtin("teaser")
            .unwrap()
            .build()
            .unwrap()
            .0
    }

    /// Rows traced by themselves, in any order, are those rows of the whole image bit for bit
    /// (what a measure times is what a frame does); a measure holds its rows' pixels as the
    /// frame has them, its estimate grows with the rows' work, another pass never raises a
    /// row's time, and a render that reuses the measure's rows equals one that traces every
    /// row, bit for bit, for every band.
    #[test]
    fn a_measure_holds_the_frames_rows_and_a_render_reuses_them() {
        let scene = teaser();
        let tracer = Tracer::new(&scene);
        let settings = RenderSettings {
            width: 40,
            height: 24,
            samples: 2,
        };
        let whole = tracer.render(settings, &|_| {});
        let row_of_whole = |row: u32| &whole.pixels[row as usize * 40..][..40];
        let rows = [17, 3, 11];
        let apart = tracer
            .render_listed_rows(
                settings,
                &rows,
                &|_| {},
                Output::Display,
                None,
                Rows::Traced,
            )
            .unwrap();
        assert_eq!(apart.height, 3);
        for (band_row, &row) in rows.iter().enumerate() {
            assert_eq!(
                &apart.pixels[band_row * 40..][..40],
                row_of_whole(row),
                "row {row}"
            );
        }
        let mut measure = tracer.measure_frame(settings, Output::Display, 4);
        assert_eq!(measure.passes(), 1);
        assert_eq!(measure.rows(), [3, 6, 9, 15, 18, 21]);
        for &row in measure.rows() {
            assert_eq!(
                measure.row_pixels(row).unwrap(),
                row_of_whole(row),
                "row {row}"
            );
        }
        assert!(measure.row_pixels(4).is_none());
        let first = measure.cost();
        assert_eq!(first.rows, 24);
        assert!(
            first.setup_seconds >= 0.0 && first.row_seconds > 0.0,
            "{first:?}"
        );
        tracer.measure_again(&mut measure);
        assert_eq!(measure.passes(), 2);
        assert!(measure.cost().row_seconds <= first.row_seconds);
        let never = AtomicBool::new(false);
        for band in [0..24, 0..7, 5..19, 21..24] {
            let heard = AtomicU64::new(0);
            let progress = |done: u32| {
                heard.fetch_max(u64::from(done), std::sync::atomic::Ordering::Relaxed);
            };
            let reused = tracer
                .render_band_reusing(
                    settings,
                    band.clone(),
                    Output::Display,
                    &progress,
                    &never,
                    Some(&measure),
                )
                .unwrap();
            let traced = tracer
                .render_band(settings, band.clone(), Output::Display, &|_| {}, &never)
                .unwrap();
            assert_eq!(reused, traced, "rows {band:?}");
            assert_eq!(heard.into_inner(), band.len() as u64, "rows {band:?}");
        }
    }

    /// A picture measured from scratch holds its tracer and its rows at the settings asked,
    /// and its seconds are the frame's estimate plus the tracer's build (never less than the
    /// frame's own estimate).
    #[test]
    fn a_picture_measured_from_scratch_counts_its_tracers_build() {
        let scene = teaser();
        let settings = RenderSettings {
            width: 64,
            height: 36,
            samples: 1,
        };
        let measured = measure_picture(&scene, settings);
        assert_eq!(measured.measure.settings(), settings);
        assert_eq!(measured.measure.passes(), 1);
        let frame = measured.measure.cost().seconds();
        assert!(
            frame > 0.0 && measured.seconds >= frame && measured.seconds.is_finite(),
            "{} against {frame}",
            measured.seconds
        );
        let whole = measured.tracer.render(settings, &|_| {});
        let row = measured.measure.rows()[1];
        assert_eq!(
            measured.measure.row_pixels(row).unwrap(),
            &whole.pixels[row as usize * 64..][..64]
        );
    }

    /// The measure's rows are taken, not traced again: a measure whose pixels were changed
    /// shows through, and only for the frame it measured (other settings or output trace
    /// every row).
    #[test]
    fn a_render_takes_the_measured_rows_and_only_for_the_same_frame() {
        let scene = teaser();
        let tracer = Tracer::new(&scene);
        let settings = RenderSettings {
            width: 16,
            height: 12,
            samples: 1,
        };
        let mut measure = tracer.measure_frame(settings, Output::Display, 3);
        let marker = DVec3::new(-7.0, -7.0, -7.0);
        measure.image.pixels.fill(marker);
        let never = AtomicBool::new(false);
        let render = |settings, output| {
            tracer
                .render_band_reusing(settings, 0..12, output, &|_| {}, &never, Some(&measure))
                .unwrap()
        };
        let reused = render(settings, Output::Display);
        for row in 0..12 {
            let marked = reused.pixels[row * 16..][..16].iter().all(|&p| p == marker);
            assert_eq!(marked, measure.rows().contains(&(row as u32)), "row {row}");
        }
        let other = RenderSettings {
            samples: 2,
            ..settings
        };
        assert!(!render(other, Output::Display).pixels.contains(&marker));
        assert!(!render(settings, Output::Radiance).pixels.contains(&marker));
    }

    /// A frame of more than [`MEASURED_SAMPLES`] samples is measured on the first that many
    /// of each pixel's samples: its rows are those of a frame of that many samples, bit for
    /// bit, and not the frame's (a render of the frame traces them again); its rows' cost is
    /// what was timed times the frame's samples per traced sample.
    #[test]
    fn a_frame_of_many_samples_is_measured_on_fewer_and_scaled() {
        let scene = teaser();
        let tracer = Tracer::new(&scene);
        let frame = RenderSettings {
            width: 16,
            height: 12,
            samples: 4 * MEASURED_SAMPLES,
        };
        let traced = RenderSettings {
            samples: MEASURED_SAMPLES,
            ..frame
        };
        let mut measure = tracer.measure_frame(frame, Output::Display, 3);
        assert_eq!(measure.settings(), traced);
        let at_traced = tracer.render(traced, &|_| {});
        for &row in measure.rows() {
            assert_eq!(
                measure.row_pixels(row).unwrap(),
                &at_traced.pixels[row as usize * 16..][..16],
                "row {row}"
            );
        }
        let marker = DVec3::new(-7.0, -7.0, -7.0);
        measure.image.pixels.fill(marker);
        let never = AtomicBool::new(false);
        let picture = tracer
            .render_band_reusing(
                frame,
                0..12,
                Output::Display,
                &|_| {},
                &never,
                Some(&measure),
            )
            .unwrap();
        assert!(!picture.pixels.contains(&marker));
        // The cost from fixed row times: 3 ms a row on one thread, four samples a traced one.
        measure.row_nanoseconds.fill(3_000_000);
        let threads = rayon::current_num_threads().max(1) as f64;
        let cost = measure.cost();
        assert_eq!(cost.rows, 12);
        assert!(
            (cost.row_seconds - 4.0 * 0.003 / threads).abs() < 1e-15,
            "{cost:?}"
        );
        // At most MEASURED_SAMPLES: traced as asked, unscaled.
        let few = RenderSettings {
            samples: MEASURED_SAMPLES,
            ..frame
        };
        let mut measure = tracer.measure_frame(few, Output::Display, 3);
        assert_eq!(measure.settings(), few);
        measure.row_nanoseconds.fill(3_000_000);
        assert!((measure.cost().row_seconds - 0.003 / threads).abs() < 1e-15);
    }
}

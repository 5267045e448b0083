//! A picture rendered a band of rows at a time (how `srt render` writes a file of any size
//! without holding it whole) is the whole picture, bit for bit: colours, radiance, coverage and
//! what each pixel sees of time, stars included (they land across band edges).

use std::sync::atomic::AtomicBool;

use srt_scene::SceneSource;
use srt_trace::{Output, RenderSettings, Tracer, star_layer};

#[test]
fn bands_of_rows_put_together_are_the_whole_picture() {
    let scene = SceneSource::resolve("flythrough")
        .unwrap()
        .load(None)
        .unwrap()
        .scene;
    let tracer = Tracer::new(&scene);
    // An odd height, so that the last band is short; several samples per pixel.
    let settings = RenderSettings {
        width: 96,
        height: 61,
        samples: 3,
    };
    let stars = star_layer(&scene, settings.width, settings.height, &|_| {
        glam::DVec3::ONE
    });
    assert!(
        !stars.is_empty(),
        "the flythrough's stars land on the picture"
    );
    let never = AtomicBool::new(false);
    let band_starts = (0..settings.height).step_by(16);
    let band = |first: u32| first..(first + 16).min(settings.height);
    for output in [Output::Display, Output::Radiance] {
        let whole = tracer
            .render_stoppable(settings, output, &|_| {}, &never)
            .expect("never stopped");
        let (mut pixels, mut coverage) = (Vec::new(), Vec::new());
        for first in band_starts.clone() {
            let rows = band(first);
            let part = tracer
                .render_band(settings, rows.clone(), output, &|_| {}, &never)
                .expect("never stopped");
            assert_eq!(part.height, rows.end - rows.start);
            pixels.extend(part.pixels);
            coverage.extend(part.coverage);
        }
        assert_eq!(pixels, whole.pixels, "{output:?}");
        assert_eq!(coverage, whole.coverage, "{output:?}");
    }
    let (width, height) = (settings.width, settings.height);
    let whole = tracer
        .render_seen_events(width, height, &|_| {}, &never)
        .expect("never stopped");
    let banded: Vec<_> = band_starts
        .flat_map(|first| {
            tracer
                .render_seen_events_band(width, height, band(first), &|_| {}, &never)
                .expect("never stopped")
        })
        .collect();
    assert_eq!(banded, whole);
    assert!(
        whole.iter().any(Option::is_some),
        "some pixel sees an object"
    );
}

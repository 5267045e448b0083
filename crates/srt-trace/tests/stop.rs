//! A render can be stopped (a caller's Ctrl-C): it gives up once the flag is set, and an
//! unstopped render is exactly the ordinary one.

use std::sync::atomic::{AtomicBool, Ordering};

use srt_scene::SceneSource;
use srt_trace::{Output, RenderSettings, Tracer};

#[test]
fn a_stopped_render_gives_up_and_an_unstopped_one_is_the_render() {
    let scene = SceneSource::resolve("fig7")
        .unwrap()
        .load(None)
        .unwrap()
        .scene;
    let tracer = Tracer::new(&scene);
    let settings = RenderSettings {
        width: 48,
        height: 27,
        samples: 1,
    };
    let never = AtomicBool::new(false);
    for (output, plain) in [
        (Output::Display, tracer.render(settings, &|_| {})),
        (Output::Radiance, tracer.render_radiance(settings, &|_| {})),
    ] {
        let stoppable = tracer
            .render_stoppable(settings, output, &|_| {}, &never)
            .expect("never stopped");
        assert_eq!(stoppable.pixels, plain.pixels);
        assert_eq!(stoppable.coverage, plain.coverage);
    }
    let stop = AtomicBool::new(true);
    assert!(
        tracer
            .render_stoppable(settings, Output::Radiance, &|_| {}, &stop)
            .is_none()
    );
    // Stopped after the first row finished: rows not yet begun are skipped (at most one per
    // worker thread is under way, far fewer than 512), so no image.
    let settings = RenderSettings {
        width: 4,
        height: 512,
        samples: 1,
    };
    let stop = AtomicBool::new(false);
    let stop_after_a_row = |_rows: u32| stop.store(true, Ordering::Relaxed);
    assert!(
        tracer
            .render_stoppable(settings, Output::Radiance, &stop_after_a_row, &stop)
            .is_none()
    );
}

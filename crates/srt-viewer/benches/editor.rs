//! What the viewer's per-frame scene edit costs: one step of playing time, and one step of a
//! flight under thrust (the observer's velocity changes, so moving objects' geometry turns by
//! the Wigner rotation and is rebuilt), in the teaser and the `flythrough` (6 000 stars).

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use srt_viewer::Editor;

fn bench_frame_edits(c: &mut Criterion) {
    let mut group = c.benchmark_group("editor");
    for name in ["teaser", "flythrough"] {
        let (mut editor, _) = Editor::open(name).expect("a built-in scene");
        let mut ct = 0.0;
        group.bench_function(format!("{name}/time_step"), |b| {
            b.iter(|| {
                ct += 1e-3;
                editor.set_time(ct).expect("a valid time");
            });
        });
        let mut speed: f64 = 0.1;
        group.bench_function(format!("{name}/thrust_step"), |b| {
            b.iter(|| {
                speed = if speed > 0.5 { 0.1 } else { speed + 1e-3 };
                let event = editor.observer_event();
                editor
                    .set_observer_motion(event, DVec3::new(0.0, speed, 0.0))
                    .expect("a valid velocity");
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench_frame_edits);
criterion_main!(benches);

//! A blinking emitter is seen to blink at D times its proper rate: the observer sees each
//! surface point at its emission event, and along the line of sight the proper time there
//! advances D = √((1 + β)/(1 − β)) times as fast as the observer's time (the Doppler factor of
//! time). A sphere approaching, resting and receding on the line of sight at 0.6c (D = 2, 1,
//! 1/2) is watched through the pixel on its centre for three of its seen periods; the
//! times it switches on are found by comparing each frame with the same scene whose emission
//! never blinks (the pixel is the same exactly when the blinking emission is on).

use srt_scene::SceneDescription;
use srt_trace::{RenderSettings, Tracer};

/// Observation times: `STEPS` per unit of ct.
const STEPS: u32 = 64;

/// The centre pixel of a sphere on the line of sight moving with `beta_y` (its centre at
/// `offset_y` at ct = 0), at observer time `ct`, with the emission blinking or not.
fn centre_pixel(beta_y: f64, offset_y: f64, ct: f64, blink: bool) -> [f64; 3] {
    let blink = if blink {
        ", blink = { period = 1.0, duty = 0.5 }"
    } else {
        ""
    };
    let text = format!(
        "[observer]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 1.0, 0.0]\nct = {ct:?}\n\
         fov_y_deg = 2.0\n\
         [[object]]\nshape = {{ type = \"sphere\", radius = 0.5 }}\ncolor = [0.3, 0.3, 0.3]\n\
         emission = {{ temperature_k = 4000.0{blink} }}\n\
         beta = [0.0, {beta_y:?}, 0.0]\noffset = [0.0, {offset_y:?}, 0.0]\n"
    );
    let description = SceneDescription::from_toml_str(&text, "test").unwrap();
    let scene = description.build(std::path::Path::new(".")).unwrap().0;
    let image = Tracer::new(&scene).render(
        RenderSettings {
            width: 1,
            height: 1,
            samples: 1,
        },
        &|_| {},
    );
    image.pixels[0].to_array()
}

/// The observer times (ct in [0, `units`]) at which the blinking sphere is seen to switch on.
fn switch_on_times(beta_y: f64, offset_y: f64, units: u32) -> Vec<f64> {
    let mut times = Vec::new();
    let mut was_on = None;
    for step in 0..=STEPS * units {
        let ct = f64::from(step) / f64::from(STEPS);
        let on =
            centre_pixel(beta_y, offset_y, ct, true) == centre_pixel(beta_y, offset_y, ct, false);
        if was_on == Some(false) && on {
            times.push(ct);
        }
        was_on = Some(on);
    }
    times
}

/// The sphere is seen to switch on every 1/D of the observer's time (to the sampling step),
/// watched for three such periods.
fn assert_seen_period(beta_y: f64, offset_y: f64) {
    let doppler = ((1.0 - beta_y) / (1.0 + beta_y)).sqrt();
    let expected = 1.0 / doppler;
    let times = switch_on_times(beta_y, offset_y, (3.0 * expected).ceil() as u32);
    assert!(
        times.len() >= 2,
        "beta {beta_y}: switched on at {times:?}, expected every {expected}"
    );
    for pair in times.windows(2) {
        let period = pair[1] - pair[0];
        assert!(
            (period - expected).abs() <= 1.0 / f64::from(STEPS),
            "beta {beta_y}: switched on at {times:?}, expected every {expected}"
        );
    }
}

#[test]
fn an_approaching_beacon_blinks_twice_as_fast() {
    assert_seen_period(-0.6, 20.0);
}

#[test]
fn a_resting_beacon_blinks_at_its_proper_rate() {
    assert_seen_period(0.0, 12.0);
}

#[test]
fn a_receding_beacon_blinks_half_as_fast() {
    assert_seen_period(0.6, 10.0);
}

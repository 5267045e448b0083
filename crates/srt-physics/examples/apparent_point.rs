//! Where a point flying towards the observer is *seen*, and with which Doppler factor, at a few
//! speeds: `cargo run -p srt-physics --example apparent_point [SPEED]` (SPEED in units of c,
//! 0.9 by default, besides 0, 0.5 and 0.99).
//!
//! The point is a lamp at x′ = (1, 0, 0) in its rest frame S′, whose origin is 10 units in front
//! of the observer at t = 0 and moves straight at them. The observer sits at the origin of S and
//! looks at ct = 0. The lamp *is* (measured in S at ct = 0) 10 units away and 5.7° off the axis;
//! it is *seen* where it was when the light now arriving left it (Eq. 5–8): much farther away
//! when it approaches, so nearer the axis, and blue-shifted by D = 1/(γ(1 − β·n)) (the time-like
//! part of Eq. 4).

use glam::DVec3;
use srt_physics::{Event, Frame, doppler_factor, lorentz_factor};

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let extra = match std::env::args().nth(1) {
        Some(text) => text
            .parse::<f64>()
            .map_err(|_| format!("SPEED must be a number such as 0.9, not {text:?}"))?,
        None => 0.9,
    };
    let lamp = DVec3::new(1.0, 0.0, 0.0);
    let observer = Event::new(0.0, DVec3::ZERO);
    println!(
        "a lamp at x' = (1, 0, 0), 10 units ahead at t = 0, approaching; seen from the origin at ct = 0"
    );
    println!();
    println!(
        "  speed   gamma   measured at ct = 0      seen at (Eq. 8)          distance  angle   Doppler D"
    );
    let mut speeds = vec![0.0, 0.5, 0.9, 0.99];
    if !speeds.contains(&extra) {
        speeds.push(extra);
    }
    for speed in speeds {
        let beta = DVec3::new(0.0, 0.0, speed);
        // Frame::new refuses |β| ≥ 1 and non-finite input with a FrameError.
        let frame = Frame::new(beta, DVec3::new(0.0, 0.0, -10.0))?;
        let now = frame.event_at_time(lamp, 0.0).position;
        let seen = frame.apparent_position(lamp, observer);
        // The light travels from the apparent position to the observer.
        let propagation = (observer.position - seen).normalize();
        let doppler = doppler_factor(beta, propagation);
        println!(
            "  {speed:<5}  {:6.3}   ({:4.1}, {:4.1}, {:6.2})   ({:4.1}, {:4.1}, {:8.2})   {:8.2}  {:4.2}°   {doppler:6.3}",
            lorentz_factor(beta),
            now.x,
            now.y,
            now.z,
            seen.x,
            seen.y,
            seen.z,
            seen.length(),
            seen.x.atan2(-seen.z).to_degrees(),
        );
    }
    println!();
    println!(
        "distance = the light's travel time ct_obs - ct_emission; D > 1 is a blue shift (head-on: sqrt((1+b)/(1-b)))"
    );
    Ok(())
}

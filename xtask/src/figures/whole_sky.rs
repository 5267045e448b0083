//! The whole sky (issue 51): the `flythrough`'s observer at 0, 0.5, 0.9 and 0.99c as
//! equirectangular frames — the sky folding into the forward cone of half-angle arccos β, what
//! has passed the observer still seen ahead —, the same flight as a planetarium's dome master
//! (a 180° fisheye pointed at the zenith, the direction of flight at the top), and the ride: the
//! star field seen from a ship accelerating from rest past 0.99c (the starbow). Rendered by the
//! reference, `srt-trace`.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use srt_scene::builtin::find_builtin;
use srt_scene::description::ThrustDescription;
use srt_scene::{Projection, SceneDescription};

use super::{render_panel, write_panel_grid};

/// The side of an equirectangular panel's height (its width is twice it).
const SKY_HEIGHT: u32 = 240;
/// The side of a dome master panel.
const DOME_SIDE: u32 = 360;

/// Writes `whole_sky.png`, `dome_master.png` and `starbow.png`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let builtin = find_builtin("flythrough").context("flythrough is a built-in scene")?;
    let flying = builtin.description();
    let at_speed = |speed: f64, projection: Projection| {
        let mut description = flying.clone();
        description.observer.beta = [0.0, speed, 0.0];
        description.observer.projection = Some(projection);
        description
    };
    let mut written = Vec::new();

    let mut panels = Vec::new();
    for speed in [0.0, 0.5, 0.9, 0.99] {
        let (scene, _) =
            builtin.build_description(&at_speed(speed, Projection::Equirectangular))?;
        let cone = speed_cone_caption(speed);
        panels.push((render_panel(&scene, 2 * SKY_HEIGHT, SKY_HEIGHT), cone));
    }
    let path = out_dir.join("whole_sky.png");
    write_panel_grid(
        &path,
        "flythrough as the full sphere (flight at the centre): the sky folds into the forward cone",
        &panels,
        2,
    )?;
    written.push(path);

    let mut domes = Vec::new();
    for speed in [0.0, 0.9] {
        let mut description = at_speed(speed, Projection::Fisheye { fov_deg: 180.0 });
        // A dome master: the camera at the zenith, the dome's front (the flight) at the top.
        description.observer.direction = Some([0.0, 0.0, 1.0]);
        description.observer.up = [0.0, 1.0, 0.0];
        let (scene, _) = builtin.build_description(&description)?;
        domes.push((
            render_panel(&scene, DOME_SIDE, DOME_SIDE),
            format!("{speed}c, zenith at the centre, flight at the top"),
        ));
    }
    let path = out_dir.join("dome_master.png");
    write_panel_grid(
        &path,
        "flythrough as a planetarium dome master (180° fisheye)",
        &domes,
        2,
    )?;
    written.push(path);

    let mut ride = Vec::new();
    let stars = star_field_ride(&flying);
    for speed in [0.0, 0.5, 0.9, 0.99, 0.999] {
        let mut description = stars.clone();
        // The ship's clock when it reaches `speed`: rapidity atanh β over α = 1.
        description.observer.time = Some(f64::atanh(speed));
        let (scene, _) = builtin.build_description(&description)?;
        ride.push((
            render_panel(&scene, 2 * SKY_HEIGHT, SKY_HEIGHT),
            format!("ship's clock {:.2}: {speed}c", f64::atanh(speed)),
        ));
    }
    let path = out_dir.join("starbow.png");
    write_panel_grid(
        &path,
        "the ride: the star field from a ship accelerating at 1 (c = 1) from rest, full sphere",
        &ride,
        2,
    )?;
    written.push(path);
    Ok(written)
}

/// A panel's caption: the speed and the half-angle of the cone the sky folds into.
fn speed_cone_caption(speed: f64) -> String {
    if speed == 0.0 {
        "at rest in the world".to_owned()
    } else {
        format!(
            "{speed}c: the sideways sky at {:.1}° from ahead",
            speed.acos().to_degrees()
        )
    }
}

/// The flythrough's star field alone (no objects, no lamp), with the observer at rest in it
/// and thrusting along the flight's direction (+y) with proper acceleration 1 from its clock's
/// 0 on, seen as the full sphere.
fn star_field_ride(flying: &SceneDescription) -> SceneDescription {
    let mut description = flying.clone();
    description.objects.clear();
    // No lamp to carry: nothing is lit but the stars shine.
    description.light = None;
    description.observer.beta = [0.0; 3];
    description.observer.direction = Some([0.0, 1.0, 0.0]);
    description.observer.projection = Some(Projection::Equirectangular);
    description.observer.thrust = Some(ThrustDescription {
        proper_acceleration: [0.0, 1.0, 0.0],
        start: 0.0,
        duration: f64::INFINITY,
    });
    description
}

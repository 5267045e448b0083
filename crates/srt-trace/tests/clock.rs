//! A clock face and a flipbook show the proper time of the event each pixel sees. A clock cube
//! at rest, approaching and receding along the line of sight at 0.6c is rendered head-on, and
//! the angle of its fast hand (one turn per unit of reading), measured from the picture, equals
//! 360° × frac(τ), with τ the proper time of the emission event of the face points sampled,
//! solved here in closed form; between two observation times Δt apart the hand turns D Δt turns
//! (D = 2, 1, 1/2): the approaching clock is seen to run twice as fast, the receding one half as
//! fast. (Along the line of sight the face's image is rotationally symmetric, so angles on it
//! are the clock's own.) A flipbook's centre pixel shows the frame ⌊τ · fps⌋ mod frames of the
//! same τ.

use std::f64::consts::TAU;

use std::sync::Arc;

use srt_scene::textures::{flipbook, solid};
use srt_scene::{Scene, SceneDescription};
use srt_trace::{RenderSettings, Tracer};

const SIZE: u32 = 240;

/// A cube of edge 1 with `texture` moving along the line of sight with `beta_y`, its centre at
/// (0, `offset_y`, 0) at t = 0, seen from the origin at `ct` with an 8° field of view.
fn cube_scene(texture: &str, beta_y: f64, offset_y: f64, ct: f64) -> Scene {
    let text = format!(
        "[observer]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 1.0, 0.0]\nct = {ct:?}\n\
         fov_y_deg = 8.0\n\
         [render]\neffects = \"geometry\"\n\
         [[object]]\nshape = {{ type = \"cube\", size = 1.0 }}\ntexture = {texture}\n\
         beta = [0.0, {beta_y:?}, 0.0]\noffset = [0.0, {offset_y:?}, 0.0]\n"
    );
    let description = SceneDescription::from_toml_str(&text, "test").unwrap();
    description.build(std::path::Path::new(".")).unwrap().0
}

/// The display image (row-major, [0, 1], `size` × `size`) of `scene`, as grey values.
fn render_grey(scene: &Scene, size: u32) -> Vec<f64> {
    let image = Tracer::new(scene).render(
        RenderSettings {
            width: size,
            height: size,
            samples: 1,
        },
        &|_| {},
    );
    image.pixels.iter().map(|p| p.element_sum() / 3.0).collect()
}

/// The display image of a clock cube (see [`cube_scene`]).
fn render(beta_y: f64, offset_y: f64, ct: f64) -> Vec<f64> {
    render_grey(
        &cube_scene("{ type = \"clock\" }", beta_y, offset_y, ct),
        SIZE,
    )
}

/// The proper time τ of the emission event of a point of the face at distance `rho` from its
/// centre seen at `ct`. The face (y′ = −1/2 in S′) moves on y = s + β t with s = offset − 1/(2γ);
/// its light reaches the origin at ct when (ct − t_e)² = ρ² + (s + β t_e)², a quadratic in t_e
/// whose earlier root is the emission; τ = γ (t_e − β (y_e − offset)) (Eq. 1, the S′ origin at
/// `offset` at t = t′ = 0).
fn face_proper_time(beta: f64, offset: f64, ct: f64, rho: f64) -> f64 {
    let gamma = 1.0 / (1.0 - beta * beta).sqrt();
    let s = offset - 0.5 / gamma;
    let (a, b, c) = (
        1.0 - beta * beta,
        ct + s * beta,
        ct * ct - rho * rho - s * s,
    );
    let t_e = (b - (b * b - a * c).sqrt()) / a;
    let y_e = s + beta * t_e;
    gamma * (t_e - beta * (y_e - offset))
}

/// The fast hand's angle (radians clockwise from 12 o'clock, in [0, 2π)) measured on `image`:
/// the ring's image radius R is the median over directions of the outermost ink; then the
/// direction whose samples at [`HAND_SAMPLES`] (beyond the slow hand, inside the ticks) are
/// darkest. Directions towards the digits (below the hub) are left out.
fn fast_hand_angle(image: &[f64]) -> f64 {
    let centre = f64::from(SIZE) / 2.0;
    let at = |angle: f64, radius: f64| -> f64 {
        let x = centre + radius * angle.sin();
        let y = centre - radius * angle.cos();
        image[(y as u32 * SIZE + x as u32) as usize]
    };
    // The face's brightness: the median of the lit pixels (ink is a small part of the face).
    let mut lit: Vec<f64> = image.iter().copied().filter(|&v| v > 0.05).collect();
    lit.sort_by(f64::total_cmp);
    let face = lit[lit.len() / 2];
    // The paper's colour shows an albedo G as ½ (G + 1) (Eq. 18): the ink is about half as bright.
    let is_ink = |value: f64| value < 0.77 * face;
    let mut outermost: Vec<f64> = (0..72)
        .map(|k| {
            let angle = TAU * f64::from(k) / 72.0;
            (1..(SIZE / 2 - 1))
                .rev()
                .map(f64::from)
                .find(|&r| is_ink(at(angle, r)) && !is_ink(at(angle, r + 1.0)) && r < centre - 2.0)
                .unwrap_or(0.0)
        })
        .collect();
    outermost.sort_by(f64::total_cmp);
    // The ring's outer edge is at 0.462 of the face's half width 0.5.
    let ring = outermost[outermost.len() / 2] / (0.45 + 0.012);
    (0..720)
        .map(|k| TAU * f64::from(k) / 720.0)
        .filter(|a| !(2.0..4.3).contains(a))
        .map(|angle| {
            let darkness: f64 = (0..10)
                .map(|i| at(angle, ring * (HAND_SAMPLES.0 + 0.008 * f64::from(i))))
                .map(|v| 1.0 - v / face)
                .sum();
            (angle, darkness)
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap()
        .0
}

/// Where the fast hand is sampled, from the face's centre in texture units (= scene units on
/// the face of edge 1): ten radii from the first, 0.008 apart, and their middle.
const HAND_SAMPLES: (f64, f64) = (0.28, 0.316);

/// The difference of two angles, in (−π, π].
fn angle_difference(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    if d > std::f64::consts::PI { d - TAU } else { d }
}

/// Where the fast hand is first measured (a fraction of a turn) and how far it then turns: from
/// 5 past to 28/60 of the next turn, all outside the digits' sector.
const FIRST: f64 = 0.72;
const SWEEP: f64 = 0.56;

/// Checks the hand against τ at two observation times, near `ct` and when the hand has turned
/// [`SWEEP`] further, and returns the turns seen per unit of the observer's time.
fn seen_rate(beta: f64, offset: f64, ct: f64) -> f64 {
    // τ grows almost linearly with ct (uniform motion along the line of sight): its rate from
    // the closed form picks the times at which the hand is in the measurable sector.
    // The hand is seen where it was when light left the sampled radius (light from off the
    // centre left a little earlier).
    let tau = |t: f64| face_proper_time(beta, offset, t, HAND_SAMPLES.1);
    let rate = tau(ct + 1.0) - tau(ct);
    let start = ct + (FIRST - tau(ct)).rem_euclid(1.0) / rate;
    let times = [start, start + SWEEP / rate];
    let mut angles = [0.0; 2];
    for (angle, t) in angles.iter_mut().zip(times) {
        let seen = tau(t);
        let expected = TAU * seen.rem_euclid(1.0);
        *angle = fast_hand_angle(&render(beta, offset, t));
        let error = angle_difference(*angle, expected).abs().to_degrees();
        assert!(
            error < 1.5,
            "beta {beta} at ct {t}: hand at {:.1}°, τ = {seen:.4} puts it at {:.1}°",
            angle.to_degrees(),
            expected.to_degrees()
        );
    }
    angle_difference(angles[1], angles[0]).rem_euclid(TAU) / TAU / (times[1] - times[0])
}

/// D = √((1 − β_y)/(1 + β_y)) for motion along +y, away from the observer at the origin.
fn doppler(beta_y: f64) -> f64 {
    ((1.0 - beta_y) / (1.0 + beta_y)).sqrt()
}

#[test]
fn a_clock_at_rest_shows_the_time_its_light_left() {
    // Its face 10 away: at ct it reads ct − 10.
    let rate = seen_rate(0.0, 10.5, 10.0);
    assert!((rate - 1.0).abs() < 0.03, "seen rate {rate}");
}

#[test]
fn an_approaching_clock_is_seen_to_run_twice_as_fast() {
    // Seen 10 away at ct = 0.
    let rate = seen_rate(-0.6, 4.4, 0.0);
    assert!(
        (rate / doppler(-0.6) - 1.0).abs() < 0.03,
        "seen rate {rate}"
    );
}

#[test]
fn a_receding_clock_is_seen_to_run_half_as_fast() {
    // Seen 10 away at ct = 20.
    let rate = seen_rate(0.6, 4.4, 20.0);
    assert!((rate / doppler(0.6) - 1.0).abs() < 0.03, "seen rate {rate}");
}

/// Frames of one colour each, told apart by the grey value the paper's colour shows.
const FRAME_COLOURS: [[f64; 3]; 3] = [[1.0, 0.2, 0.2], [0.2, 1.0, 0.2], [0.2, 0.2, 1.0]];

/// The centre pixel of the cube of [`cube_scene`] wearing a flipbook of [`FRAME_COLOURS`] at
/// `fps`, or (with `still`) only that frame's colour.
fn flipbook_centre(beta_y: f64, offset_y: f64, ct: f64, fps: f64, still: Option<usize>) -> f64 {
    let mut scene = cube_scene("\"checker\"", beta_y, offset_y, ct);
    let texture = match still {
        Some(frame) => solid(FRAME_COLOURS[frame]),
        None => flipbook(&FRAME_COLOURS.map(solid), fps, "test flipbook".into()).unwrap(),
    };
    for part in &mut scene.objects[0].parts {
        part.material.texture = Some(Arc::new(texture.clone()));
    }
    render_grey(&scene, 1)[0]
}

#[test]
fn a_flipbook_shows_the_frame_of_the_proper_time_seen() {
    let fps = 4.0;
    for (beta, offset, start) in [(0.0, 10.5, 10.0), (-0.6, 4.4, 0.0), (0.6, 4.4, 20.0)] {
        let stills: Vec<f64> = (0..3)
            .map(|k| flipbook_centre(beta, offset, start, fps, Some(k)))
            .collect();
        assert!(stills[0] != stills[1] && stills[1] != stills[2] && stills[0] != stills[2]);
        for step in 0..24 {
            let ct = start + 0.05 * f64::from(step);
            let tau = face_proper_time(beta, offset, ct, 0.0);
            let shown = (tau * fps).floor();
            // Not where a frame ends: the pixel's own rounding may fall either side.
            if (tau * fps - shown).min(shown + 1.0 - tau * fps) < 1e-6 {
                continue;
            }
            let expected = shown.rem_euclid(3.0) as usize;
            let seen = flipbook_centre(beta, offset, ct, fps, None);
            assert_eq!(
                seen, stills[expected],
                "beta {beta} at ct {ct}: τ = {tau}, frame {expected} expected"
            );
        }
    }
}

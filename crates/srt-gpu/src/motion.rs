//! Bodies that spin or thrust within their rest frame (`srt_physics::motion`, docs/physics.md
//! "Spinning and accelerating bodies") on the GPU: what `shaders/motion.wgsl` reads of an
//! object's motion ([`MotionUniforms`], in `ObjectUniforms`), and the box in the object's rest
//! coordinates that holds the body at every event a backward ray can meet it
//! ([`sweep_bounds`]), whose footprints the ray tracer draws for it.
//!
//! The WGSL mirrors crates/srt-trace/src/moving.rs in f32: the backward ray's body-space curve
//! cut into pieces (≤ `srt_physics::motion::SPIN_PIECE_ANGLE` of rotation, or
//! `THRUST_PIECES_PER_SIZE` per body
//! size of a thrust's accelerating stretch; at most [`MAX_PIECES`], where the reference allows
//! 2¹⁶), each piece's box (a spinning body's chord box padded by the curve's sagitta bound, a
//! thrust's exact box of its arc) met with the BVH; on a spinning body the sign change of the
//! distance to each candidate triangle's plane narrowed to f32 precision by the Illinois method
//! ([`CROSSING_STEPS`] steps at most; the reference bisects to the f64 limit), on a
//! thrust's arc the roots of a quadratic polished by [`NEWTON_STEPS`] Newton steps. What the
//! f64 reference computes exactly — the spin phase ω·ct′₀ reduced mod 2π, the elapsed thrust
//! time — is computed here in f64, so that the shaders see small numbers.

use glam::DVec3;
use srt_physics::Event;
use srt_physics::motion::Motion;
use srt_scene::{BodyExtent, Object};

use crate::types::{ObjectUniforms, vec4};

/// Most pieces of one curved stretch of ray on the GPU (WGSL `MOTION_MAX_PIECES`).
pub const MAX_PIECES: u32 = 4096;
/// Most steps of the search for one crossing of a spinning body's piece in f32 (WGSL
/// `MOTION_CROSSING_STEPS`): the Illinois method (regula falsi, the value kept at one end twice
/// in a row halved) ends in a few steps where the curve is smooth; the cap is more than
/// bisection would take from any bracket to the 24 bits of an f32 mantissa.
pub const CROSSING_STEPS: u32 = 48;
/// Newton steps polishing each root of a thrust's crossing in f32 (WGSL `MOTION_NEWTON_STEPS`):
/// srt-trace's, from their one home.
pub const NEWTON_STEPS: u32 = srt_physics::motion::THRUST_NEWTON_STEPS;
/// Pieces of a spinning body's march that the GPU takes together first (WGSL
/// `MOTION_PIECES_PER_GROUP`): the group's chord box, padded by the sagitta bound for its span,
/// holds the curve over all of them, so where it meets no BVH leaf (no box of the triangle the
/// shading pass repeats the search on) none of its pieces is evaluated. The pieces searched,
/// and so the crossing found, are those of the reference.
pub const PIECES_PER_GROUP: u32 = 8;

/// How a body moves in its rest frame (WGSL `MOTION_*`): the LRT and polygon shaders are
/// compiled once per code (`MOTION_VARIANT`, [`crate::shaders::lrt`]) and each object is drawn
/// by its code's variant, so that no shader carries the other kinds' code.
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MotionCode(pub u32);

impl MotionCode {
    /// At rest (WGSL `MOTION_REST`).
    pub const REST: Self = Self(0);
    /// Spinning (WGSL `MOTION_SPIN`).
    pub const SPIN: Self = Self(1);
    /// Thrusting (WGSL `MOTION_THRUST`).
    pub const THRUST: Self = Self(2);
    /// Every code, in order: the index of a code is its value.
    pub const ALL: [Self; 3] = [Self::REST, Self::SPIN, Self::THRUST];

    /// The code of `motion`.
    #[must_use]
    pub fn of(motion: &Motion) -> Self {
        match motion {
            Motion::Rest => Self::REST,
            Motion::Spin(_) => Self::SPIN,
            Motion::Thrust(_) => Self::THRUST,
        }
    }

    /// The code's index in [`MotionCode::ALL`].
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The motion fields of `ObjectUniforms` for one object and observation event.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MotionUniforms {
    /// Unused (x: the kind is the pipeline variant's, WGSL `MOTION_VARIANT`), rate or α, phase
    /// or elapsed time, final rapidity (< 0: none).
    pub motion: [f32; 4],
    /// Axis or direction (xyz), reach (w).
    pub axis: [f32; 4],
    /// Spin centre (xyz).
    pub centre: [f32; 4],
    /// Box lower corner (xyz), lowest axial height (w).
    pub low: [f32; 4],
    /// Box upper corner (xyz), highest axial height (w).
    pub high: [f32; 4],
}

impl MotionUniforms {
    /// The motion of `object` (whose meshes measure `extent`) seen from the observation event
    /// `observer` (in S).
    #[must_use]
    pub fn new(object: &Object, extent: &BodyExtent, observer: Event) -> Self {
        // The object's S′ time at the observation event: where every backward ray starts.
        let now = object.proper_time(object.frame.to_rest(observer).ct);
        let (lo, hi) = extent.bounds;
        let (axial_low, axial_high) = extent.axial.unwrap_or((0.0, 0.0));
        let low = vec4(lo, axial_low);
        let high = vec4(hi, axial_high);
        match object.motion {
            Motion::Rest => Self {
                low,
                high,
                ..Self::default()
            },
            Motion::Spin(spin) => Self {
                motion: [
                    0.0,
                    spin.rate() as f32,
                    (spin.rate() * now).rem_euclid(std::f64::consts::TAU) as f32,
                    0.0,
                ],
                axis: vec4(spin.axis(), extent.reach),
                centre: vec4(spin.centre(), 0.0),
                low,
                high,
            },
            Motion::Thrust(thrust) => Self {
                motion: [
                    0.0,
                    thrust.alpha() as f32,
                    (now - thrust.start()) as f32,
                    if thrust.final_rapidity().is_finite() {
                        thrust.final_rapidity() as f32
                    } else {
                        -1.0
                    },
                ],
                axis: vec4(thrust.direction(), extent.reach),
                centre: [0.0; 4],
                low,
                high,
            },
        }
    }

    /// Writes these fields into `uniforms`.
    pub fn apply(&self, uniforms: &mut ObjectUniforms) {
        uniforms.motion = self.motion;
        uniforms.motion_axis = self.axis;
        uniforms.motion_centre = self.centre;
        uniforms.motion_low = self.low;
        uniforms.motion_high = self.high;
    }
}

/// The box in the rest coordinates of `object` (measuring `extent`) that holds every point of
/// the body at every event a backward ray from the observation event `observer` can meet it:
/// for a spinning body, the body's box turned through the angles ω·ct′ of the S′ times at
/// which the rays are inside the ball it sweeps (sampled every [`SWEEP_STEP`] radians, padded by
/// the arcs' sagitta), within the cube around its centre of half-width its reach; for a
/// thrusting one its box at rest swept along â by how far its points move during the S′ times
/// at which the rays are inside its box swept by the whole elapsed time (no point moves faster
/// than light, and earlier the body was where it rests); `None` at rest.
#[must_use]
pub fn sweep_bounds(
    object: &Object,
    extent: &BodyExtent,
    observer: Event,
) -> Option<(DVec3, DVec3)> {
    let rest = object.frame.to_rest(observer);
    let now = object.proper_time(rest.ct);
    let pad = 1e-6 * (1.0 + extent.reach);
    match object.motion {
        Motion::Rest => None,
        Motion::Spin(spin) => {
            let r = DVec3::splat(extent.reach + pad);
            let cube = (spin.centre() - r, spin.centre() + r);
            // The rays are inside the ball for s within its distance ± its reach: S′ times
            // now − s there.
            let distance = (rest.position - spin.centre()).length();
            let (near, far) = ((distance - extent.reach).max(0.0), distance + extent.reach);
            let (first, last) = (spin.rate() * (now - far), spin.rate() * (now - near));
            let arc = (last - first).abs();
            if arc.is_nan() || arc >= std::f64::consts::TAU {
                return Some(cube);
            }
            let steps = (arc / SWEEP_STEP).ceil().max(1.0);
            let step = arc / steps;
            let (lo, hi) = extent.bounds;
            let corners = (0..8).map(|k: u32| {
                DVec3::new(
                    if k & 1 == 0 { lo.x } else { hi.x },
                    if k & 2 == 0 { lo.y } else { hi.y },
                    if k & 4 == 0 { lo.z } else { hi.z },
                ) - spin.centre()
            });
            let corners: Vec<DVec3> = corners.collect();
            let (mut min, mut max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            for i in 0..=(steps as u32) {
                let angle = first.min(last) + step * f64::from(i);
                let turn = glam::DQuat::from_axis_angle(spin.axis(), angle);
                for &c in &corners {
                    let p = spin.centre() + turn * c;
                    min = min.min(p);
                    max = max.max(p);
                }
            }
            // Between two samples a point moves on an arc within its chord's sagitta.
            let sagitta = DVec3::splat(extent.reach * step * step / 8.0 + pad);
            Some(((min - sagitta).max(cube.0), (max + sagitta).min(cube.1)))
        }
        Motion::Thrust(thrust) => {
            let (lo, hi) = extent.bounds;
            let direction = thrust.direction();
            let sweep = (now - thrust.start()).max(0.0) * direction;
            let p = DVec3::splat(pad);
            let (full_lo, full_hi) = (lo.min(lo + sweep) - p, hi.max(hi + sweep) + p);
            // The rays are inside that box only for s between its nearest and farthest
            // distance: S′ times now − s there. Every point's displacement along â grows with
            // time and, at one time, is largest for the lowest point (Born rigidity): the
            // body's box corners bound it.
            let o = rest.position;
            let near = (o - o.clamp(full_lo, full_hi)).length();
            let far = (o - full_lo).abs().max((o - full_hi).abs()).length();
            let (earliest, latest) = (now - far, now - near);
            let corners: Vec<DVec3> = (0..8u32)
                .map(|k| {
                    DVec3::new(
                        if k & 1 == 0 { lo.x } else { hi.x },
                        if k & 2 == 0 { lo.y } else { hi.y },
                        if k & 4 == 0 { lo.z } else { hi.z },
                    )
                })
                .collect();
            let moved = |c: DVec3, ct: f64| (thrust.position(c, ct) - c).dot(direction);
            let least = corners
                .iter()
                .map(|&c| moved(c, earliest))
                .fold(f64::INFINITY, f64::min);
            let most = corners
                .iter()
                .map(|&c| moved(c, latest))
                .fold(0.0, f64::max);
            let (a, b) = (least.max(0.0) * direction, most * direction);
            let margin = DVec3::splat(pad + 1e-9 * (1.0 + far));
            let (window_lo, window_hi) = (lo + a.min(b) - margin, hi + a.max(b) + margin);
            Some((window_lo.max(full_lo), window_hi.min(full_hi)))
        }
    }
}

/// Radians between the turned copies of a spinning body's box in [`sweep_bounds`].
pub const SWEEP_STEP: f64 = 0.1;

//! Kernel probes: run the shared WGSL functions (`physics.wgsl`, `colour.wgsl`, `spectral.wgsl`)
//! on arrays of inputs and compare every result with its `f64` CPU original (`srt-physics`,
//! `srt-color`).
//!
//! The WGSL side is `shaders/probe.wgsl` (entry points `physics_probe`, `lut_probe` and
//! `spectral_probe`). Tests and `cargo xtask validate` use [`run_physics_probe`] with
//! [`seeded_cases`] and [`compare_physics`] to report the worst relative error of each physics
//! kernel against its tolerance, [`run_lut_probe`] with [`lut_tolerance`] for the colour table,
//! and [`run_spectral_probe`] with [`spectral_seeded_cases`], [`compare_spectral`] and
//! [`SPECTRAL_TOLERANCE`] for spectral colour.
//!
//! # How errors are measured
//!
//! The primary inputs of a case (β, offset, observation event, points, directions, s) are
//! rounded to `f32` when the case is built ([`PhysicsProbeCase::new`]), so both sides start from
//! the same numbers; what the GPU gets beyond them (Λ_±β, γ, the observer in S′) is computed in
//! `f64` and rounded once ([`GpuFrame::new`]), exactly as the render passes do. The CPU reference
//! ([`reference()`]) is `srt-physics` in `f64` on the unrounded frame.
//!
//! Per kernel the error of one case is ‖gpu − cpu‖ / max(‖cpu‖, floor) (Euclidean norm over the
//! kernel's components) and [`compare_physics`] reports the worst case. Results that are events
//! or positions have the floor L = [`case_scale`], the size of the case's input coordinates: an
//! event that happens to lie near the origin is judged by its error relative to the scene's
//! extent, which is what decides where it lands in an image. Directions, ratios and the
//! apparent distance (a product) have no floor; `apparent_tangent` has the length of its input
//! direction.
//!
//! # Tolerances
//!
//! Each tolerance is 8 u A, with u = 2⁻²⁴ the `f32` unit roundoff and A the kernel's
//! amplification of rounding errors (a condition number) at |β| ≤ 0.99, the extreme of
//! [`seeded_cases`]: D = γ(1 + |β|) ≈ 14.1 for one Lorentz transformation, D² = 199 for two or
//! for a 1 − β·n cancellation. [`PHYSICS_KERNELS`] gives the reasoning per kernel. The bounds are
//! derived, not fitted: on Mesa lavapipe the worst errors over 3 × 131 072 seeded cases are 0.02
//! (`apparent_tangent`) to 0.34 (`emission_event`) of them.

use glam::{DVec3, DVec4};
use srt_color::{
    Reflectance, TemperatureLut, ToneMap, emitted_display_rgb, reflected_display_rgb,
    searchlight_reference_ln_y, srgb_coefficient_table, srgb_decode,
};
use srt_physics::{Event, Frame, RestRay};
use wgpu::util::DeviceExt;

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::lut::{lut_params, lut_texture};
use crate::pipelines::{BindGroupSpec, PipelineSpec, Slot, TEXTURE_2D, UNIFORM, storage};
use crate::shaders::{self, WORKGROUP_SIZE};
use crate::spectral::SpectralTables;
use crate::types::{
    GpuFrame, GpuPhysicsProbeInput, GpuPhysicsProbeOutput, GpuSpectralProbeInput,
    GpuSpectralProbeOutput, ToneMapCode, event4, vec4,
};

/// The `f32` unit roundoff u = 2⁻²⁴.
pub const F32_UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

/// The arguments of every physics kernel for one probe case, in `f64` (rounded to `f32` values).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicsProbeCase {
    /// The object's rest frame S′.
    pub frame: Frame,
    /// The observation event in S.
    pub observer: Event,
    /// An event in S for `to_rest`.
    pub event: Event,
    /// An event in S′ for `to_observer`.
    pub rest_event: Event,
    /// A point at rest in S′.
    pub point: DVec3,
    /// A direction in S′ for `apparent_tangent` at `point`.
    pub direction: DVec3,
    /// A viewing direction in S for `backward_ray` (any length).
    pub view_direction: DVec3,
    /// The ray parameter s for `apparent_distance` along the backward ray.
    pub ray_parameter: f64,
    /// A propagation direction in S for `doppler_factor`.
    pub propagation: DVec3,
    /// A propagation direction in S′ for `aberrate` with the frame's β.
    pub direction_rest: DVec3,
    /// Incident propagation direction for `reflection_doppler`.
    pub incident: DVec3,
    /// Outgoing propagation direction for `reflection_doppler`.
    pub outgoing: DVec3,
}

/// The primary inputs of a [`PhysicsProbeCase`], before rounding to `f32`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicsProbeInputs {
    /// Velocity of S′ relative to S (|β| < 1).
    pub beta: DVec3,
    /// Origin of S′ in S at t = 0.
    pub offset: DVec3,
    /// The observation event in S.
    pub observer: Event,
    /// An event in S for `to_rest`.
    pub event: Event,
    /// An event in S′ for `to_observer`.
    pub rest_event: Event,
    /// A point at rest in S′.
    pub point: DVec3,
    /// A direction in S′ for `apparent_tangent`.
    pub direction: DVec3,
    /// A viewing direction in S.
    pub view_direction: DVec3,
    /// The ray parameter s.
    pub ray_parameter: f64,
    /// A propagation direction in S for `doppler_factor`.
    pub propagation: DVec3,
    /// A propagation direction in S′ for `aberrate`.
    pub direction_rest: DVec3,
    /// Incident propagation direction.
    pub incident: DVec3,
    /// Outgoing propagation direction.
    pub outgoing: DVec3,
}

fn round_f32(x: f64) -> f64 {
    f64::from(x as f32)
}

fn round_vec(v: DVec3) -> DVec3 {
    DVec3::new(round_f32(v.x), round_f32(v.y), round_f32(v.z))
}

fn round_event(e: Event) -> Event {
    Event::new(round_f32(e.ct), round_vec(e.position))
}

impl PhysicsProbeCase {
    /// The case for `inputs`, every primary input rounded to the nearest `f32` first, so that the
    /// GPU and the CPU reference see the same numbers.
    ///
    /// # Errors
    /// [`srt_physics::FrameError`] when β or the offset is invalid (after rounding).
    pub fn new(inputs: &PhysicsProbeInputs) -> Result<Self, srt_physics::FrameError> {
        Ok(Self {
            frame: Frame::new(round_vec(inputs.beta), round_vec(inputs.offset))?,
            observer: round_event(inputs.observer),
            event: round_event(inputs.event),
            rest_event: round_event(inputs.rest_event),
            point: round_vec(inputs.point),
            direction: round_vec(inputs.direction),
            view_direction: round_vec(inputs.view_direction),
            ray_parameter: round_f32(inputs.ray_parameter),
            propagation: round_vec(inputs.propagation),
            direction_rest: round_vec(inputs.direction_rest),
            incident: round_vec(inputs.incident),
            outgoing: round_vec(inputs.outgoing),
        })
    }

    /// The GPU record of this case.
    #[must_use]
    pub fn to_gpu(&self) -> GpuPhysicsProbeInput {
        GpuPhysicsProbeInput {
            frame: GpuFrame::new(&self.frame, self.observer),
            event: event4(self.event),
            rest_event: event4(self.rest_event),
            point: vec4(self.point, self.ray_parameter),
            direction: vec4(self.direction, 0.0),
            view: vec4(self.view_direction, 0.0),
            propagation: vec4(self.propagation, 0.0),
            direction_rest: vec4(self.direction_rest, 0.0),
            incident: vec4(self.incident, 0.0),
            outgoing: vec4(self.outgoing, 0.0),
        }
    }
}

/// Every physics kernel's result for one [`PhysicsProbeCase`], from the GPU ([`run_physics_probe`])
/// or the CPU ([`reference()`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicsProbeResult {
    /// `to_observer(rest_event)`.
    pub to_observer: Event,
    /// `to_rest(event)`.
    pub to_rest: Event,
    /// `emission_event(point, observer)`.
    pub emission_event: Event,
    /// `apparent_position(point, observer)`.
    pub apparent_position: DVec3,
    /// `apparent_tangent(point, direction, observer)`.
    pub apparent_tangent: DVec3,
    /// `aberrate(β, direction_rest)`.
    pub aberrate: DVec3,
    /// `backward_ray(observer, view_direction)`.
    pub backward_ray: RestRay,
    /// `doppler_factor(β, propagation)`.
    pub doppler_factor: f64,
    /// `reflection_doppler(β, incident, outgoing)`.
    pub reflection_doppler: f64,
    /// `apparent_distance(backward_ray, ray_parameter)`.
    pub apparent_distance: f64,
    /// `lorentz_factor(β)`.
    pub lorentz_factor: f64,
}

fn dvec3(v: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

fn event_of(v: [f32; 4]) -> Event {
    Event::new(
        f64::from(v[0]),
        DVec3::new(f64::from(v[1]), f64::from(v[2]), f64::from(v[3])),
    )
}

impl From<GpuPhysicsProbeOutput> for PhysicsProbeResult {
    fn from(out: GpuPhysicsProbeOutput) -> Self {
        Self {
            to_observer: event_of(out.to_observer),
            to_rest: event_of(out.to_rest),
            emission_event: event_of(out.emission_event),
            apparent_position: dvec3(out.apparent_position),
            apparent_tangent: dvec3(out.apparent_tangent),
            aberrate: dvec3(out.aberrate),
            backward_ray: RestRay {
                origin: dvec3(out.ray_origin),
                direction: dvec3(out.ray_direction),
                ct_origin: f64::from(out.ray_origin[3]),
            },
            doppler_factor: f64::from(out.scalars[0]),
            reflection_doppler: f64::from(out.scalars[1]),
            apparent_distance: f64::from(out.scalars[2]),
            lorentz_factor: f64::from(out.scalars[3]),
        }
    }
}

/// The `f64` CPU results (`srt-physics`) for `case`: what the GPU kernels approximate.
#[must_use]
pub fn reference(case: &PhysicsProbeCase) -> PhysicsProbeResult {
    let frame = &case.frame;
    let beta = frame.beta();
    let ray = frame.backward_ray(case.observer, case.view_direction);
    PhysicsProbeResult {
        to_observer: frame.to_observer(case.rest_event),
        to_rest: frame.to_rest(case.event),
        emission_event: frame.emission_event(case.point, case.observer),
        apparent_position: frame.apparent_position(case.point, case.observer),
        apparent_tangent: frame.apparent_tangent(case.point, case.direction, case.observer),
        aberrate: srt_physics::aberrate(beta, case.direction_rest),
        backward_ray: ray,
        doppler_factor: srt_physics::doppler_factor(beta, case.propagation),
        reflection_doppler: srt_physics::reflection_doppler(beta, case.incident, case.outgoing),
        apparent_distance: frame.apparent_distance(&ray, case.ray_parameter),
        lorentz_factor: frame.gamma(),
    }
}

/// SplitMix64 (Steele, Lea and Flood 2014): a tiny, fixed generator, so that seeded cases stay
/// the same across dependency upgrades.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [−half_width, half_width).
    fn symmetric(&mut self, half_width: f64) -> f64 {
        (2.0 * self.unit() - 1.0) * half_width
    }

    fn cube(&mut self, half_width: f64) -> DVec3 {
        DVec3::new(
            self.symmetric(half_width),
            self.symmetric(half_width),
            self.symmetric(half_width),
        )
    }

    /// Uniform on the unit sphere (Marsaglia's rejection in the cube).
    fn direction(&mut self) -> DVec3 {
        loop {
            let v = self.cube(1.0);
            let l2 = v.length_squared();
            if l2 > 1e-6 && l2 <= 1.0 {
                return v / l2.sqrt();
            }
        }
    }
}

/// Largest speed |β| of [`seeded_cases`].
pub const SEEDED_MAX_SPEED: f64 = 0.99;

/// `count` reproducible probe cases from `seed`.
///
/// β points in a uniformly random direction with |β| uniform in [0, 0.99], except that every
/// fourth case has |β| = 0.99 exactly (the worst conditioning); offsets, points in S′ and the
/// spatial part of the S′ event lie within ±10 per coordinate; the observer, the S event and
/// every time coordinate within ±20; the ray parameter s in [0, 40]; directions are uniform on
/// the unit sphere (the viewing direction scaled by a length in [0.5, 2]). A point closer to
/// the observer's S′ position x′_obs than ‖x′_obs‖ / D (D = [`SEEDED_MAX_DOPPLER`]) is drawn
/// again, which bounds the conditioning of `apparent_tangent` (see [`PHYSICS_KERNELS`]).
///
/// # Panics
/// Never: every generated β is below 1.
#[must_use]
pub fn seeded_cases(seed: u64, count: usize) -> Vec<PhysicsProbeCase> {
    let mut rng = SplitMix64(seed);
    (0..count)
        .map(|i| {
            let speed = if i % 4 == 0 {
                SEEDED_MAX_SPEED
            } else {
                SEEDED_MAX_SPEED * rng.unit()
            };
            let beta = speed * rng.direction();
            let mut inputs = PhysicsProbeInputs {
                beta,
                offset: rng.cube(10.0),
                observer: Event::new(rng.symmetric(20.0), rng.cube(20.0)),
                event: Event::new(rng.symmetric(20.0), rng.cube(20.0)),
                rest_event: Event::new(rng.symmetric(20.0), rng.cube(10.0)),
                point: rng.cube(10.0),
                direction: rng.direction(),
                view_direction: (0.5 + 1.5 * rng.unit()) * rng.direction(),
                ray_parameter: 40.0 * rng.unit(),
                propagation: rng.direction(),
                direction_rest: rng.direction(),
                incident: rng.direction(),
                outgoing: rng.direction(),
            };
            loop {
                let case = match PhysicsProbeCase::new(&inputs) {
                    Ok(case) => case,
                    Err(e) => unreachable!("seeded speeds are at most 0.99: {e}"),
                };
                let observer_rest = case.frame.to_rest(case.observer).position;
                if (case.point - observer_rest).length() * SEEDED_MAX_DOPPLER
                    >= observer_rest.length()
                {
                    return case;
                }
                inputs.point = rng.cube(10.0);
            }
        })
        .collect()
}

/// √((1 + β)/(1 − β)) at |β| = [`SEEDED_MAX_SPEED`]: the largest Doppler factor D = γ(1 + |β|),
/// which is also ‖Λ_±β‖₂, the largest stretch of a Lorentz matrix (√199).
pub const SEEDED_MAX_DOPPLER: f64 = 14.106_735_979_665_885;

/// D² = (1 + β)/(1 − β) = 199 at |β| = [`SEEDED_MAX_SPEED`]: the condition number ‖Λ‖‖Λ⁻¹‖ of a
/// Lorentz matrix, and the amplification of rounding in 1 − β·n (≤ 1/(1 − |β|) = 100 ≤ D²).
pub const SEEDED_MAX_DOPPLER_SQUARED: f64 = 199.0;

/// γ² = 1/(1 − β²) at |β| = [`SEEDED_MAX_SPEED`] (γ ≈ 7.09).
pub const SEEDED_MAX_GAMMA_SQUARED: f64 = 1.0 / (1.0 - SEEDED_MAX_SPEED * SEEDED_MAX_SPEED);

/// One physics kernel as [`compare_physics`] measures it.
#[derive(Debug, Clone, Copy)]
pub struct PhysicsKernel {
    /// The WGSL function's name.
    pub name: &'static str,
    /// Largest accepted relative error (see [`PHYSICS_KERNELS`] for each bound).
    pub tolerance: f64,
    /// The norm floor of the relative error for a case (see the module documentation).
    pub floor: fn(&PhysicsProbeCase) -> f64,
    /// The kernel's components in a result (unused ones 0).
    pub components: fn(&PhysicsProbeResult) -> DVec4,
}

/// The coordinate scale L of a case: the largest Euclidean norm among its events (observer,
/// `event`, `rest_event`, as four-vectors) and positions (offset, point). For
/// [`seeded_cases`] L ≤ 40.
#[must_use]
pub fn case_scale(case: &PhysicsProbeCase) -> f64 {
    [
        case.observer.to_four_vector().length(),
        case.event.to_four_vector().length(),
        case.rest_event.to_four_vector().length(),
        case.frame.offset().length(),
        case.point.length(),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

fn no_floor(_: &PhysicsProbeCase) -> f64 {
    0.0
}

fn direction_length(case: &PhysicsProbeCase) -> f64 {
    case.direction.length()
}

fn event4d(e: Event) -> DVec4 {
    e.to_four_vector()
}

fn vec3d(v: DVec3) -> DVec4 {
    v.extend(0.0)
}

fn scalar(x: f64) -> DVec4 {
    DVec4::new(x, 0.0, 0.0, 0.0)
}

const U: f64 = F32_UNIT_ROUNDOFF;
const D: f64 = SEEDED_MAX_DOPPLER;
const D2: f64 = SEEDED_MAX_DOPPLER_SQUARED;

/// Every physics kernel with its floor and tolerance.
///
/// Each tolerance is 8 · u · A: u = 2⁻²⁴, and A the kernel's amplification of relative rounding
/// errors (its condition number with respect to the `f32` roundings it suffers) at
/// |β| ≤ 0.99, where D = γ(1 + |β|) = ‖Λ_±β‖₂ ≈ 14.1, D² = 199 and γ² ≈ 50.3. The factor 8 counts
/// the roundings on each kernel's critical path (3 to 8) with margin for their partial
/// alignment; measured worst errors are 0.15 to 2.7 u · A (the tests print them).
///
/// - `to_observer`, `to_rest` (floor L): one 4×4 product with `f32`-rounded Λ entries, plus or
///   minus the offset; the rounding of the input and of Λ is stretched by ‖Λ‖ = D. A = D.
/// - `emission_event` (floor L): ct′_obs − ‖p − x′_obs‖ where ct′_obs and x′_obs are S′
///   coordinates (up to 2DL) rounded to `f32`. A = D.
/// - `apparent_position` (floor L): Λ_β applied to the emission event, whose error (above) is
///   stretched by D once more. A = D² (8 u D² ≈ 9.5e-5: 1e-4 of the scene scale).
/// - `apparent_tangent` (floor ‖direction‖): dct = −direction·(p − x′_obs)/‖p − x′_obs‖ is a
///   cosine, but x′_obs is rounded at size ‖x′_obs‖, which tilts the unit vector by
///   u ‖x′_obs‖/‖p − x′_obs‖ ≤ u D ([`seeded_cases`] keeps points that far from the observer),
///   then Λ_β stretches by D. A = D².
/// - `aberrate`, `backward_ray` (unit results, no floor): the numerator
///   γβ + n′ + γ²/(γ + 1)(β·n′)β has terms of size γ but length only γ(1 + β·n′) ≥ γ(1 − |β|) =
///   1/D, and 1 + β·n′ ≥ 1 − |β| loses as many digits. A = γ D ≤ D².
/// - `doppler_factor`, `reflection_doppler` (no floor): 1 − β·n ≥ 1 − |β| loses digits
///   (1/(1 − |β|) = 100 ≤ D²), and γ (computed from β in `f32`) adds γ² u. A = D².
/// - `apparent_distance` (no floor; a product, exactly 0 at s = 0): γ s (1 − β·d′) with d′ the
///   GPU's ray direction (error ≲ u D², above), of which only the part across β enters
///   (|β_⊥| ≤ √(2(1 − β·d′))), and 1 − β·d′ ≥ 0.01 as above. A = D².
/// - `lorentz_factor` (no floor): 1 − β·β ≥ 1/γ² loses digits; relative error ≈ (1.5 β²γ² + 2) u.
///   A = γ², with c = 4 instead of 8 (the estimate is already a sum over the roundings).
pub const PHYSICS_KERNELS: &[PhysicsKernel] = &[
    PhysicsKernel {
        name: "to_observer",
        tolerance: 8.0 * U * D,
        floor: case_scale,
        components: |r| event4d(r.to_observer),
    },
    PhysicsKernel {
        name: "to_rest",
        tolerance: 8.0 * U * D,
        floor: case_scale,
        components: |r| event4d(r.to_rest),
    },
    PhysicsKernel {
        name: "emission_event",
        tolerance: 8.0 * U * D,
        floor: case_scale,
        components: |r| event4d(r.emission_event),
    },
    PhysicsKernel {
        name: "apparent_position",
        tolerance: 8.0 * U * D2,
        floor: case_scale,
        components: |r| vec3d(r.apparent_position),
    },
    PhysicsKernel {
        name: "apparent_tangent",
        tolerance: 8.0 * U * D2,
        floor: direction_length,
        components: |r| vec3d(r.apparent_tangent),
    },
    PhysicsKernel {
        name: "aberrate",
        tolerance: 8.0 * U * D2,
        floor: no_floor,
        components: |r| vec3d(r.aberrate),
    },
    PhysicsKernel {
        name: "backward_ray",
        tolerance: 8.0 * U * D2,
        floor: no_floor,
        components: |r| vec3d(r.backward_ray.direction),
    },
    PhysicsKernel {
        name: "doppler_factor",
        tolerance: 8.0 * U * D2,
        floor: no_floor,
        components: |r| scalar(r.doppler_factor),
    },
    PhysicsKernel {
        name: "reflection_doppler",
        tolerance: 8.0 * U * D2,
        floor: no_floor,
        components: |r| scalar(r.reflection_doppler),
    },
    PhysicsKernel {
        name: "apparent_distance",
        tolerance: 8.0 * U * D2,
        floor: no_floor,
        components: |r| scalar(r.apparent_distance),
    },
    PhysicsKernel {
        name: "lorentz_factor",
        tolerance: 4.0 * U * SEEDED_MAX_GAMMA_SQUARED,
        floor: no_floor,
        components: |r| scalar(r.lorentz_factor),
    },
];

/// The worst error of one kernel over a set of cases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KernelError {
    /// The WGSL function's name.
    pub kernel: &'static str,
    /// Worst ‖gpu − cpu‖ / max(‖cpu‖, floor) over the cases (NaN when a result was not finite).
    pub worst_relative: f64,
    /// Index of the case with the worst error.
    pub worst_case: usize,
    /// The kernel's tolerance.
    pub tolerance: f64,
}

impl KernelError {
    /// Whether the worst error is within the tolerance (false for NaN).
    #[must_use]
    pub fn passes(&self) -> bool {
        self.worst_relative <= self.tolerance
    }
}

impl std::fmt::Display for KernelError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:<20} worst {:.2e} = {:>5.0} u (case {:>5}), tolerance {:.2e} = {:>5.0} u: {}",
            self.kernel,
            self.worst_relative,
            self.worst_relative / F32_UNIT_ROUNDOFF,
            self.worst_case,
            self.tolerance,
            self.tolerance / F32_UNIT_ROUNDOFF,
            if self.passes() { "ok" } else { "FAILED" }
        )
    }
}

/// ‖gpu − cpu‖ / max(‖cpu‖, floor): 0 when both are equal (0/0 included), NaN when either is not
/// finite.
#[must_use]
pub fn relative_error(gpu: DVec4, cpu: DVec4, floor: f64) -> f64 {
    if !(gpu.is_finite() && cpu.is_finite()) {
        return f64::NAN;
    }
    let difference = (gpu - cpu).length();
    if difference == 0.0 {
        0.0
    } else {
        difference / cpu.length().max(floor)
    }
}

/// The worst error of each kernel in [`PHYSICS_KERNELS`] of the GPU `results` against the `f64`
/// [`reference()`] of `cases` (see the module documentation for the measure).
///
/// # Panics
/// If `cases` and `results` differ in length.
#[must_use]
pub fn compare_physics(
    cases: &[PhysicsProbeCase],
    results: &[PhysicsProbeResult],
) -> Vec<KernelError> {
    assert_eq!(cases.len(), results.len(), "one result per case");
    let references: Vec<PhysicsProbeResult> = cases.iter().map(reference).collect();
    PHYSICS_KERNELS
        .iter()
        .map(|kernel| {
            let mut worst = KernelError {
                kernel: kernel.name,
                worst_relative: 0.0,
                worst_case: 0,
                tolerance: kernel.tolerance,
            };
            for (index, ((case, cpu), gpu)) in
                cases.iter().zip(&references).zip(results).enumerate()
            {
                let error = relative_error(
                    (kernel.components)(gpu),
                    (kernel.components)(cpu),
                    (kernel.floor)(case),
                );
                if error.is_nan() || error > worst.worst_relative {
                    worst.worst_relative = error;
                    worst.worst_case = index;
                    if error.is_nan() {
                        break;
                    }
                }
            }
            worst
        })
        .collect()
}

/// The probe's bindings in group 0 (`probe.wgsl`), by WGSL name.
pub mod slots {
    use super::{Slot, TEXTURE_2D, UNIFORM, storage};
    use wgpu::ShaderStages;

    /// `probe_inputs`: the physics cases.
    pub const PROBE_INPUTS: Slot = Slot {
        wgsl_name: "probe_inputs",
        binding: 0,
        visibility: ShaderStages::COMPUTE,
        ty: storage(true),
    };
    /// `probe_outputs`: the physics results.
    pub const PROBE_OUTPUTS: Slot = Slot {
        wgsl_name: "probe_outputs",
        binding: 1,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// `lut_temperatures`: the temperatures to sample.
    pub const LUT_TEMPERATURES: Slot = Slot {
        wgsl_name: "lut_temperatures",
        binding: 2,
        visibility: ShaderStages::COMPUTE,
        ty: storage(true),
    };
    /// `lut_colours`: the sampled colours.
    pub const LUT_COLOURS: Slot = Slot {
        wgsl_name: "lut_colours",
        binding: 3,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// `lut_table`: the colour table.
    pub const LUT_TABLE: Slot = Slot {
        wgsl_name: "lut_table",
        binding: 4,
        visibility: ShaderStages::COMPUTE,
        ty: TEXTURE_2D,
    };
    /// `lut_params`: the table's parameters.
    pub const LUT_PARAMS: Slot = Slot {
        wgsl_name: "lut_params",
        binding: 5,
        visibility: ShaderStages::COMPUTE,
        ty: UNIFORM,
    };
    /// `spectral_inputs`: the spectral cases.
    pub const SPECTRAL_INPUTS: Slot = Slot {
        wgsl_name: "spectral_inputs",
        binding: 6,
        visibility: ShaderStages::COMPUTE,
        ty: storage(true),
    };
    /// `spectral_outputs`: the spectral results.
    pub const SPECTRAL_OUTPUTS: Slot = Slot {
        wgsl_name: "spectral_outputs",
        binding: 7,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// `spectral_params`: ln Y(1500 K).
    pub const SPECTRAL_PARAMS: Slot = Slot {
        wgsl_name: "spectral_params",
        binding: 11,
        visibility: ShaderStages::COMPUTE,
        ty: UNIFORM,
    };
    /// `spectral_tables`, as the render passes bind it, for the compute stage.
    pub const SPECTRAL_TABLES: Slot = Slot {
        visibility: ShaderStages::COMPUTE,
        ..crate::pipelines::slots::SPECTRAL_TABLES
    };
    /// `spectral_cie`, as the render passes bind it, for the compute stage.
    pub const SPECTRAL_CIE: Slot = Slot {
        visibility: ShaderStages::COMPUTE,
        ..crate::pipelines::slots::SPECTRAL_CIE
    };
}

/// The bind group of the `physics_probe` entry point.
pub const PHYSICS_PROBE_GROUP: BindGroupSpec = BindGroupSpec {
    label: "physics probe",
    index: 0,
    slots: &[slots::PROBE_INPUTS, slots::PROBE_OUTPUTS],
};

/// The bind group of the `lut_probe` entry point.
pub const LUT_PROBE_GROUP: BindGroupSpec = BindGroupSpec {
    label: "lut probe",
    index: 0,
    slots: &[
        slots::LUT_TEMPERATURES,
        slots::LUT_COLOURS,
        slots::LUT_TABLE,
        slots::LUT_PARAMS,
    ],
};

/// The bind group of the `spectral_probe` entry point.
pub const SPECTRAL_PROBE_GROUP: BindGroupSpec = BindGroupSpec {
    label: "spectral probe",
    index: 0,
    slots: &[
        slots::SPECTRAL_INPUTS,
        slots::SPECTRAL_OUTPUTS,
        slots::SPECTRAL_TABLES,
        slots::SPECTRAL_CIE,
        slots::SPECTRAL_PARAMS,
    ],
};

/// The three probe pipelines (`physics_probe`, `lut_probe`, `spectral_probe`) as their bindings
/// see them.
#[must_use]
pub fn specs() -> [PipelineSpec; 3] {
    [
        PipelineSpec {
            label: "physics_probe",
            shader: shaders::probe(),
            entry_points: &["physics_probe"],
            groups: vec![PHYSICS_PROBE_GROUP],
        },
        PipelineSpec {
            label: "lut_probe",
            shader: shaders::probe(),
            entry_points: &["lut_probe"],
            groups: vec![LUT_PROBE_GROUP],
        },
        PipelineSpec {
            label: "spectral_probe",
            shader: shaders::probe(),
            entry_points: &["spectral_probe"],
            groups: vec![SPECTRAL_PROBE_GROUP],
        },
    ]
}

/// Workgroups for `count` invocations in one row.
fn workgroups(ctx: &GpuContext, count: usize) -> Result<u32, GpuError> {
    let limits = DeviceLimits::of(ctx);
    let groups = (count as u64).div_ceil(u64::from(WORKGROUP_SIZE));
    limits.at_most(
        || format!("the dispatch of {count} probe inputs"),
        groups,
        "workgroups",
        u64::from(limits.limits.max_compute_workgroups_per_dimension),
        "max_compute_workgroups_per_dimension",
    )?;
    Ok(groups as u32)
}

/// Checks a probe storage buffer of `bytes` (`what` names it) against the device's limits.
fn check_storage(ctx: &GpuContext, what: &str, bytes: usize) -> Result<(), GpuError> {
    DeviceLimits::of(ctx)
        .check_storage_buffer(|| format!("the probe's {what} buffer"), bytes as u64)
}

/// Builds the compute pipeline of `spec` (one entry point; `group`, its only bind group),
/// binds `resources` to `group`, dispatches `count` invocations and copies `output` back.
fn dispatch(
    ctx: &GpuContext,
    spec: &PipelineSpec,
    group: BindGroupSpec,
    resources: &[wgpu::BindGroupEntry<'_>],
    count: usize,
    output: &wgpu::Buffer,
) -> Result<Vec<u8>, GpuError> {
    let groups = workgroups(ctx, count)?;
    let device = &ctx.device;
    let module = spec.shader.module(device);
    let layout = group.create_layout(device);
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(spec.label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(spec.label),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: spec.entry_points.first().copied(),
        compilation_options: spec.shader.compilation_options(),
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(spec.label),
        layout: &layout,
        entries: resources,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("probe readback"),
        size: output.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some(spec.label),
    });
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(spec.label),
            timestamp_writes: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(group.index, &bind_group, &[]);
        pass.dispatch_workgroups(groups, 1, 1);
    }
    encoder.copy_buffer_to_buffer(output, 0, &readback, 0, output.size());
    ctx.queue.submit([encoder.finish()]);
    let bytes = ctx.read_buffer(&readback)?;
    ctx.take_errors()?;
    Ok(bytes)
}

/// Evaluates every physics kernel of `physics.wgsl` on the GPU for each case.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when the cases exceed the device's buffer or dispatch limits,
/// [`GpuError::Wgpu`] for wgpu validation errors, [`GpuError::Readback`] when reading fails.
pub fn run_physics_probe(
    ctx: &GpuContext,
    cases: &[PhysicsProbeCase],
) -> Result<Vec<PhysicsProbeResult>, GpuError> {
    if cases.is_empty() {
        return Ok(Vec::new());
    }
    let inputs: Vec<GpuPhysicsProbeInput> = cases.iter().map(PhysicsProbeCase::to_gpu).collect();
    let output_size = cases.len() * size_of::<GpuPhysicsProbeOutput>();
    check_storage(ctx, "input", size_of_val(inputs.as_slice()))?;
    check_storage(ctx, "output", output_size)?;
    let input = ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("physics probe inputs"),
            contents: bytemuck::cast_slice(&inputs),
            usage: wgpu::BufferUsages::STORAGE,
        });
    let output = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("physics probe outputs"),
        size: output_size as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let [physics, _, _] = specs();
    let bytes = dispatch(
        ctx,
        &physics,
        PHYSICS_PROBE_GROUP,
        &[
            slots::PROBE_INPUTS.entry(input.as_entire_binding()),
            slots::PROBE_OUTPUTS.entry(output.as_entire_binding()),
        ],
        cases.len(),
        &output,
    )?;
    let outputs: Vec<GpuPhysicsProbeOutput> = bytemuck::pod_collect_to_vec(&bytes);
    Ok(outputs.into_iter().map(PhysicsProbeResult::from).collect())
}

/// Samples `lut` on the GPU (`lut_sample` of `colour.wgsl`) at each temperature in kelvin.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when the table or the inputs exceed the device's limits,
/// [`GpuError::Wgpu`] for wgpu validation errors, [`GpuError::Readback`] when reading fails.
pub fn run_lut_probe(
    ctx: &GpuContext,
    lut: &TemperatureLut,
    temperatures: &[f32],
) -> Result<Vec<[f32; 4]>, GpuError> {
    if temperatures.is_empty() {
        return Ok(Vec::new());
    }
    let output_size = temperatures.len() * size_of::<[f32; 4]>();
    check_storage(ctx, "temperature", size_of_val(temperatures))?;
    check_storage(ctx, "colour", output_size)?;
    let texture = lut_texture(ctx, lut)?;
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let device = &ctx.device;
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("LUT probe temperatures"),
        contents: bytemuck::cast_slice(temperatures),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("LUT probe parameters"),
        contents: bytemuck::cast_slice(&lut_params(lut)),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("LUT probe colours"),
        size: output_size as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let [_, lut_spec, _] = specs();
    let bytes = dispatch(
        ctx,
        &lut_spec,
        LUT_PROBE_GROUP,
        &[
            slots::LUT_TEMPERATURES.entry(input.as_entire_binding()),
            slots::LUT_COLOURS.entry(output.as_entire_binding()),
            slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(&view)),
            slots::LUT_PARAMS.entry(params.as_entire_binding()),
        ],
        temperatures.len(),
        &output,
    )?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// How far (in texels) the GPU's table position x = u (N − 1) may stray from the CPU's for
/// `lut`: (N − 1) E / ln(T_max / T_min) + 2 u (N − 1).
///
/// E bounds the GPU's error in ln T − ln T_min, in the range where u is not clamped
/// (|ln T| ≤ M = max(|ln T_min|, |ln T_max|)): WGSL's `log` is accurate to 3 ulp ≤ 6 u M (plus
/// 2⁻²¹ absolute for T in [0.5, 2]), ln T_min and ln T_max are stored rounded (u M each), and the
/// subtraction and the division by ln T_max − ln T_min round at 2 M: E = 12 u M (+ 2⁻²¹). The
/// last term covers the rounding of the quotient and of x itself. For the default table
/// (100 K to 10⁶ K, 4096 texels) this is 0.005 texels.
#[must_use]
pub fn lut_position_tolerance(lut: &TemperatureLut) -> f64 {
    let (ln_min, ln_max) = (lut.t_min().ln(), lut.t_max().ln());
    let m = ln_min.abs().max(ln_max.abs());
    let near_one = if lut.t_min() < 2.0 && lut.t_max() > 0.5 {
        2f64.powi(-21)
    } else {
        0.0
    };
    let e = 12.0 * F32_UNIT_ROUNDOFF * m + near_one;
    let last = (lut.size() - 1) as f64;
    last * e / (ln_max - ln_min) + 2.0 * F32_UNIT_ROUNDOFF * last
}

/// The largest change of any channel between neighbouring texels of `lut`.
#[must_use]
pub fn lut_max_step(lut: &TemperatureLut) -> f32 {
    lut.texels()
        .windows(2)
        .flat_map(|w| (0..4).map(move |k| (w[1][k] - w[0][k]).abs()))
        .fold(0.0, f32::max)
}

/// Per-channel tolerance of [`run_lut_probe`] against [`TemperatureLut::sample`]: the colour
/// change over [`lut_position_tolerance`] texels at the steepest step of the table
/// ([`lut_max_step`]), plus the rounding of the lerp itself (2 u, on values ≤ 1).
#[must_use]
pub fn lut_tolerance(lut: &TemperatureLut) -> f32 {
    (lut_position_tolerance(lut) * f64::from(lut_max_step(lut)) + 2.0 * F32_UNIT_ROUNDOFF) as f32
}

/// One case of the spectral kernels (`spectral.wgsl`): a surface colour and the light, Doppler
/// factors and tone map it is seen with, every number already an `f32` value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralProbeCase {
    /// sRGB-encoded surface colour in [0, 1]³ (texel × base × vertex colour).
    pub albedo: DVec3,
    /// Light temperature in kelvin, also the emitter's.
    pub temperature_k: f64,
    /// Doppler factor light → surface.
    pub d_in: f64,
    /// Doppler factor surface → observer.
    pub d_out: f64,
    /// Exposure (the renderer's times the Phong factor).
    pub exposure: f64,
    /// The tone map.
    pub tone_map: ToneMap,
    /// Reflectance below 380 nm, if the material has one.
    pub ultraviolet: Option<f64>,
    /// Reflectance above 780 nm, if the material has one.
    pub infrared: Option<f64>,
    /// The emitter's brightness.
    pub brightness: f64,
}

impl SpectralProbeCase {
    /// The WGSL input.
    #[must_use]
    pub fn to_gpu(&self) -> GpuSpectralProbeInput {
        let code = f64::from(ToneMapCode::from(self.tone_map).0);
        GpuSpectralProbeInput {
            rgb_temperature: vec4(self.albedo, self.temperature_k),
            factors: [self.d_in, self.d_out, self.exposure, code].map(|v| v as f32),
            bands: [
                self.ultraviolet.unwrap_or(-1.0),
                self.infrared.unwrap_or(-1.0),
                self.brightness,
                0.0,
            ]
            .map(|v| v as f32),
        }
    }

    /// The CPU's display colours in `f64`: reflected (as srt-trace's shade: decode, clamp,
    /// table lookup, bands, [`reflected_display_rgb`]) and emitted ([`emitted_display_rgb`]),
    /// black where the CPU reports an error.
    #[must_use]
    pub fn reference(&self) -> [DVec3; 2] {
        let linear = self.albedo.map(srgb_decode).clamp(DVec3::ZERO, DVec3::ONE);
        let reflected = srgb_coefficient_table()
            .lookup(linear)
            .and_then(|p| Reflectance::with_bands(p, self.ultraviolet, self.infrared))
            .and_then(|r| {
                reflected_display_rgb(
                    self.tone_map,
                    &r,
                    self.temperature_k,
                    self.d_in,
                    self.d_out,
                    self.exposure,
                )
            })
            .unwrap_or(DVec3::ZERO);
        let emitted = emitted_display_rgb(
            self.tone_map,
            self.temperature_k,
            self.brightness,
            self.d_out,
            self.exposure,
        )
        .unwrap_or(DVec3::ZERO);
        [reflected, emitted]
    }
}

/// `count` reproducible spectral cases from `seed`: colours uniform in the cube, every fourth a
/// grey (the table's special case) and every eighth on the cube's edge; temperatures
/// log-uniform in 1000–20 000 K; D_in and D_out log-uniform within 1/D … D for
/// D = [`SEEDED_MAX_DOPPLER`] (|β| ≤ 0.99); exposures log-uniform in 0.05–20; both tone maps;
/// band constants on half the cases; brightness in [0, 4].
#[must_use]
pub fn spectral_seeded_cases(seed: u64, count: usize) -> Vec<SpectralProbeCase> {
    let mut rng = SplitMix64(seed);
    let f32_value = |v: f64| f64::from(v as f32);
    let log_uniform = |rng: &mut SplitMix64, lo: f64, hi: f64| {
        f32_value((lo.ln() + rng.unit() * (hi.ln() - lo.ln())).exp())
    };
    (0..count)
        .map(|i| {
            let mut albedo = DVec3::new(rng.unit(), rng.unit(), rng.unit()).map(f32_value);
            if i % 4 == 1 {
                albedo = DVec3::splat(albedo.x);
            } else if i % 8 == 2 {
                albedo.y = if rng.unit() < 0.5 { 0.0 } else { 1.0 };
            }
            let band = |rng: &mut SplitMix64| (rng.unit() < 0.5).then(|| f32_value(rng.unit()));
            SpectralProbeCase {
                albedo,
                temperature_k: log_uniform(&mut rng, 1000.0, 20_000.0),
                d_in: log_uniform(&mut rng, 1.0 / SEEDED_MAX_DOPPLER, SEEDED_MAX_DOPPLER),
                d_out: log_uniform(&mut rng, 1.0 / SEEDED_MAX_DOPPLER, SEEDED_MAX_DOPPLER),
                exposure: log_uniform(&mut rng, 0.05, 20.0),
                tone_map: ToneMap::ALL[i % 2],
                ultraviolet: band(&mut rng),
                infrared: band(&mut rng),
                brightness: f32_value(4.0 * rng.unit()),
            }
        })
        .collect()
}

/// Largest difference per display channel (values in [0, 1]) accepted between
/// [`run_spectral_probe`] and [`SpectralProbeCase::reference`]: a quarter of the image metric's
/// 2/255, so that the kernel alone cannot move a pixel across it. Not derived from a rounding
/// analysis: the sum's own `f32` error is small (relative errors of order 10⁻⁵ in XYZ, amplified
/// at most 12.92× by the sRGB curve), but the trilinear interpolation and the sigmoid polynomial
/// cancel terms of the coefficients' size, and a driver's `exp`/`log` may be less accurate than
/// lavapipe's; on Mesa lavapipe the worst over 4096 seeded cases is 2.5 × 10⁻⁵ (reflected) and
/// 2.6 × 10⁻⁵ (emitted), 75× inside it.
pub const SPECTRAL_TOLERANCE: f64 = 0.5 / 255.0;

/// Evaluates `spectral_reflected_display` and `spectral_emitted_display` on the GPU for each
/// case: [reflected, emitted] display sRGB.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when the cases exceed the device's buffer or dispatch limits,
/// [`GpuError::Wgpu`] for wgpu validation errors, [`GpuError::Readback`] when reading fails.
pub fn run_spectral_probe(
    ctx: &GpuContext,
    cases: &[SpectralProbeCase],
) -> Result<Vec<[DVec3; 2]>, GpuError> {
    if cases.is_empty() {
        return Ok(Vec::new());
    }
    let inputs: Vec<GpuSpectralProbeInput> = cases.iter().map(SpectralProbeCase::to_gpu).collect();
    let output_size = cases.len() * size_of::<GpuSpectralProbeOutput>();
    check_storage(ctx, "spectral input", size_of_val(inputs.as_slice()))?;
    check_storage(ctx, "spectral output", output_size)?;
    let tables = SpectralTables::new(ctx)?;
    let device = &ctx.device;
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("spectral probe inputs"),
        contents: bytemuck::cast_slice(&inputs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("spectral probe parameters"),
        contents: bytemuck::cast_slice(&[searchlight_reference_ln_y() as f32, 0.0, 0.0, 0.0]),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("spectral probe outputs"),
        size: output_size as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let [_, _, spectral] = specs();
    let [spectral_words, spectral_cie] = tables.entries();
    let bytes = dispatch(
        ctx,
        &spectral,
        SPECTRAL_PROBE_GROUP,
        &[
            slots::SPECTRAL_INPUTS.entry(input.as_entire_binding()),
            slots::SPECTRAL_OUTPUTS.entry(output.as_entire_binding()),
            spectral_words,
            spectral_cie,
            slots::SPECTRAL_PARAMS.entry(params.as_entire_binding()),
        ],
        cases.len(),
        &output,
    )?;
    let outputs: Vec<GpuSpectralProbeOutput> = bytemuck::pod_collect_to_vec(&bytes);
    let rgb = |v: [f32; 4]| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
    Ok(outputs
        .into_iter()
        .map(|o| [rgb(o.reflected), rgb(o.emitted)])
        .collect())
}

/// The worst per-channel difference of the GPU's spectral `results` from the CPU's
/// ([`SpectralProbeCase::reference`]): (reflected, emitted), each with the index of its case.
///
/// # Panics
/// If `cases` and `results` differ in length.
#[must_use]
pub fn compare_spectral(cases: &[SpectralProbeCase], results: &[[DVec3; 2]]) -> [(f64, usize); 2] {
    assert_eq!(cases.len(), results.len(), "one result per case");
    let mut worst = [(0.0, 0); 2];
    for (index, (case, gpu)) in cases.iter().zip(results).enumerate() {
        let cpu = case.reference();
        for (w, (g, c)) in worst.iter_mut().zip(gpu.iter().zip(cpu)) {
            let difference = (*g - c).abs().max_element();
            // NaN counts as the worst.
            if difference.is_nan() || difference > w.0 {
                *w = (
                    if difference.is_nan() {
                        f64::INFINITY
                    } else {
                        difference
                    },
                    index,
                );
            }
        }
    }
    worst
}

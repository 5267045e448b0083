// physics.wgsl — special relativity in f32, the GPU mirror of crates/srt-physics (f64).
// Conventions as in docs/physics.md: c = 1, events (ct, x, y, z) stored in vec4 as (x, y, z, w)
// = (ct, x, y, z), matrices act on column vectors, light four-vectors k = ω(1, n) with n the
// propagation direction, D = ω_received / ω_emitted.
//
// Composed in front of the pass shaders by srt-gpu (WGSL has no includes).

// The rest frame S′ of one object (srt_physics::Frame), prepared on the CPU in f64.
struct Frame {
    // Λ_β (Eq. 2): S′ four-vectors → S.
    rest_to_observer: mat4x4<f32>,
    // Λ_−β: S four-vectors → S′.
    observer_to_rest: mat4x4<f32>,
    // β in xyz, γ in w.
    beta_gamma: vec4<f32>,
    // The paper's a (S′ origin in S at t = 0) in xyz, 0 in w.
    offset: vec4<f32>,
    // The observation event in S′ (Eq. 5), (ct′, x′, y′, z′), computed in f64 on the CPU.
    observer_rest: vec4<f32>,
}

// Lorentz factor γ = 1/√(1 − β·β) (below Eq. 2).
fn lorentz_factor(beta: vec3<f32>) -> f32 {
    return 1.0 / sqrt(1.0 - dot(beta, beta));
}

// Poincaré transformation S′ → S: x = Λ_β x′ + a (Eq. 1).
fn to_observer(frame: Frame, rest_event: vec4<f32>) -> vec4<f32> {
    return frame.rest_to_observer * rest_event + vec4<f32>(0.0, frame.offset.xyz);
}

// Poincaré transformation S → S′: x′ = Λ_−β (x − a) (Eq. 1, Eq. 5).
fn to_rest(frame: Frame, event: vec4<f32>) -> vec4<f32> {
    return frame.observer_to_rest * (event - vec4<f32>(0.0, frame.offset.xyz));
}

// Emission event in S′ of a point at rest in S′ (Eq. 7): ct′_p = ct′_obs − ‖x′_p − x′_obs‖.
fn emission_event(frame: Frame, point: vec3<f32>) -> vec4<f32> {
    let d = distance(point, frame.observer_rest.yzw);
    return vec4<f32>(frame.observer_rest.x - d, point);
}

// Apparent position in S of a point at rest in S′: the photo-object map R (Eq. 8).
fn apparent_position(frame: Frame, point: vec3<f32>) -> vec3<f32> {
    return to_observer(frame, emission_event(frame, point)).yzw;
}

// Derivative of R along `direction` at `point` (Eq. 7–8 differentiated).
fn apparent_tangent(frame: Frame, point: vec3<f32>, direction: vec3<f32>) -> vec3<f32> {
    let from_observer = point - frame.observer_rest.yzw;
    let dct = -dot(direction, from_observer) / length(from_observer);
    return (frame.rest_to_observer * vec4<f32>(dct, direction)).yzw;
}

// Doppler factor of light reaching an observer at rest in S along `propagation` (in S) from a
// source moving with `beta` (Eq. 4, time-like part): D = 1 / (γ (1 − β·n)).
fn doppler_factor(beta: vec3<f32>, propagation: vec3<f32>) -> f32 {
    return 1.0 / (lorentz_factor(beta) * (1.0 - dot(beta, propagation)));
}

// Doppler factor with which a receiver moving with `beta` through S sees light propagating along
// `propagation` (in S) from a source at rest in S (Eq. 3, time-like part): D = γ (1 − β·n); the
// first factor of Eq. 17. Mirror of srt_physics::receiver_doppler.
fn receiver_doppler(beta: vec3<f32>, propagation: vec3<f32>) -> f32 {
    return lorentz_factor(beta) * (1.0 - dot(beta, propagation));
}

// Aberration (Eq. 4, space-like part): direction in S of light propagating along
// `direction_rest` in S′ moving with `beta`.
fn aberrate(beta: vec3<f32>, direction_rest: vec3<f32>) -> vec3<f32> {
    let gamma = lorentz_factor(beta);
    return aberration_numerator(beta, gamma, direction_rest) / (gamma * (1.0 + dot(beta, direction_rest)));
}

// Eq. 4's numerator: the spatial part of the photon four-vector (1, n′) boosted by β (Lorentz
// factor γ), a positive multiple of aberrate's direction.
fn aberration_numerator(beta: vec3<f32>, gamma: f32, direction_rest: vec3<f32>) -> vec3<f32> {
    return gamma * beta + direction_rest + (gamma * gamma / (gamma + 1.0)) * dot(beta, direction_rest) * beta;
}

// Where a star at infinity is seen from S and its Doppler factor: a source at rest in a frame
// moving with `beta`, in the unit direction `direction_rest` there (observer → star). Mirror of
// srt_physics::distant_source_image (Eq. 4).
struct DistantSourceImage {
    direction: vec3<f32>,
    doppler: f32,
}

fn distant_source_image(beta: vec3<f32>, direction_rest: vec3<f32>) -> DistantSourceImage {
    let propagation = normalize(aberrate(beta, -direction_rest));
    return DistantSourceImage(-propagation, doppler_factor(beta, propagation));
}

// Combined reflection Doppler factor (Eq. 17 in our convention): D = (1 − β·n_in)/(1 − β·n_out).
fn reflection_doppler(beta: vec3<f32>, incident: vec3<f32>, outgoing: vec3<f32>) -> f32 {
    return (1.0 - dot(beta, incident)) / (1.0 - dot(beta, outgoing));
}

// A backward viewing ray in S′: origin + s·direction at time ct_origin − s.
struct RestRay {
    origin: vec3<f32>,
    direction: vec3<f32>,
    ct_origin: f32,
}

// The change (Δct′, Δx′) in S′ of an event moved by the spatial displacement `shift` in S at
// the same S time: the pure boost Λ_−β of (0, shift) (Eq. 2), from β and γ (`beta_gamma`).
fn rest_displacement(beta_gamma: vec4<f32>, shift: vec3<f32>) -> vec4<f32> {
    let beta = beta_gamma.xyz;
    let gamma = beta_gamma.w;
    let along = dot(beta, shift);
    let b2 = dot(beta, beta);
    var stretch = 0.0;
    if (b2 > 0.0) {
        stretch = (gamma - 1.0) / b2;
    }
    return vec4<f32>(-gamma * along, shift + stretch * along * beta);
}

// The backward viewing ray in S′ for the observer looking along `view_direction` (in S).
fn backward_ray(frame: Frame, view_direction: vec3<f32>) -> RestRay {
    return backward_ray_of(frame.beta_gamma, frame.observer_rest, view_direction);
}

// backward_ray given the only parts of the frame it needs: β and γ (`beta_gamma`) and the
// observation event in S′ (`observer_rest`).
fn backward_ray_of(beta_gamma: vec4<f32>, observer_rest: vec4<f32>, view_direction: vec3<f32>) -> RestRay {
    let propagation = -normalize(view_direction);
    let propagation_rest = normalize(aberrate(-beta_gamma.xyz, propagation));
    return RestRay(observer_rest.yzw, -propagation_rest, observer_rest.x);
}

// A positive multiple of the direction in S′ in which light seen along `view_direction` (in S)
// propagates, i.e. of −backward_ray(frame, view_direction).direction: aberrate's numerator
// (Eq. 4) with the frame's γ, without its division and the normalisation. For what a ray's
// length does not change (where it meets a plane, in barycentric coordinates).
fn rest_propagation_unscaled(frame: Frame, view_direction: vec3<f32>) -> vec3<f32> {
    return aberration_numerator(-frame.beta_gamma.xyz, frame.beta_gamma.w, -normalize(view_direction));
}

// Apparent distance of the point at parameter s on `ray`: γ s (1 − β·d′).
fn apparent_distance(frame: Frame, ray: RestRay, s: f32) -> f32 {
    return apparent_distance_of(frame.beta_gamma, ray, s);
}

// apparent_distance given the frame's β and γ (`beta_gamma`) only.
fn apparent_distance_of(beta_gamma: vec4<f32>, ray: RestRay, s: f32) -> f32 {
    return beta_gamma.w * s * (1.0 - dot(beta_gamma.xyz, ray.direction));
}

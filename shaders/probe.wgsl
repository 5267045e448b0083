// probe.wgsl — evaluates the shared WGSL functions on arrays of inputs so that tests and
// `cargo xtask validate` can measure each f32 kernel against its f64 CPU original
// (crates/srt-gpu/src/probe.rs runs it and does the comparing).
//
// Composed after physics.wgsl and colour.wgsl. Each struct here has a #[repr(C)] twin in
// crates/srt-gpu/src/probe.rs whose layout tests/layout.rs checks.

// One set of arguments for every physics kernel.
struct PhysicsProbeInput {
    frame: Frame,
    // An event in S (ct, x, y, z) for to_rest.
    event: vec4<f32>,
    // An event in S′ (ct′, x′, y′, z′) for to_observer.
    rest_event: vec4<f32>,
    // A point at rest in S′ (xyz) for emission_event, apparent_position and apparent_tangent;
    // the ray parameter s for apparent_distance (w).
    point: vec4<f32>,
    // A direction in S′ (xyz) for apparent_tangent; w unused.
    direction: vec4<f32>,
    // A viewing direction in S (xyz, any length) for backward_ray; w unused.
    view: vec4<f32>,
    // A propagation direction in S (xyz) for doppler_factor; w unused.
    propagation: vec4<f32>,
    // A propagation direction in S′ (xyz) for aberrate with the frame's β; w unused.
    direction_rest: vec4<f32>,
    // Incident propagation direction (xyz) for reflection_doppler; w unused.
    incident: vec4<f32>,
    // Outgoing propagation direction (xyz) for reflection_doppler; w unused.
    outgoing: vec4<f32>,
}

// Every physics kernel's result for one PhysicsProbeInput.
struct PhysicsProbeOutput {
    to_observer: vec4<f32>,
    to_rest: vec4<f32>,
    emission_event: vec4<f32>,
    // xyz; w = 0.
    apparent_position: vec4<f32>,
    // xyz; w = 0.
    apparent_tangent: vec4<f32>,
    // xyz; w = 0.
    aberrate: vec4<f32>,
    // backward_ray(frame, view): origin (xyz) and ct_origin (w).
    ray_origin: vec4<f32>,
    // backward_ray(frame, view): direction (xyz); w = 0.
    ray_direction: vec4<f32>,
    // doppler_factor, reflection_doppler, apparent_distance (along the ray above at s),
    // lorentz_factor.
    scalars: vec4<f32>,
}

@group(0) @binding(0) var<storage, read> probe_inputs: array<PhysicsProbeInput>;
@group(0) @binding(1) var<storage, read_write> probe_outputs: array<PhysicsProbeOutput>;

@compute @workgroup_size(64)
fn physics_probe(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&probe_inputs) {
        return;
    }
    let c = probe_inputs[index];
    let beta = c.frame.beta_gamma.xyz;
    let ray = backward_ray(c.frame, c.view.xyz);
    var out: PhysicsProbeOutput;
    out.to_observer = to_observer(c.frame, c.rest_event);
    out.to_rest = to_rest(c.frame, c.event);
    out.emission_event = emission_event(c.frame, c.point.xyz);
    out.apparent_position = vec4<f32>(apparent_position(c.frame, c.point.xyz), 0.0);
    out.apparent_tangent = vec4<f32>(apparent_tangent(c.frame, c.point.xyz, c.direction.xyz), 0.0);
    out.aberrate = vec4<f32>(aberrate(beta, c.direction_rest.xyz), 0.0);
    out.ray_origin = vec4<f32>(ray.origin, ray.ct_origin);
    out.ray_direction = vec4<f32>(ray.direction, 0.0);
    out.scalars = vec4<f32>(
        doppler_factor(beta, c.propagation.xyz),
        reflection_doppler(beta, c.incident.xyz, c.outgoing.xyz),
        apparent_distance(c.frame, ray, c.point.w),
        lorentz_factor(beta),
    );
    probe_outputs[index] = out;
}

@group(0) @binding(2) var<storage, read> lut_temperatures: array<f32>;
@group(0) @binding(3) var<storage, read_write> lut_colours: array<vec4<f32>>;
@group(0) @binding(4) var lut_table: texture_2d<f32>;
// (ln T_min, ln T_max, N, unused), as lut_sample takes it.
@group(0) @binding(5) var<uniform> lut_params: vec4<f32>;

@compute @workgroup_size(64)
fn lut_probe(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&lut_temperatures) {
        return;
    }
    lut_colours[index] = lut_sample(lut_table, lut_params, lut_temperatures[index]);
}

// probe.wgsl — evaluates the shared WGSL functions on arrays of inputs so that tests and
// `cargo xtask validate` can measure each f32 kernel against its f64 CPU original
// (crates/srt-gpu/src/probe.rs runs it and does the comparing).
//
// Composed after physics.wgsl, types.wgsl (PhysicsProbeInput, PhysicsProbeOutput) and
// colour.wgsl.

// Invocations per workgroup of both entry points: set at pipeline creation from
// srt_gpu::shaders::WORKGROUP_SIZE.
override WORKGROUP_SIZE: u32;

@group(0) @binding(0) var<storage, read> probe_inputs: array<PhysicsProbeInput>;
@group(0) @binding(1) var<storage, read_write> probe_outputs: array<PhysicsProbeOutput>;

@compute @workgroup_size(WORKGROUP_SIZE)
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

@compute @workgroup_size(WORKGROUP_SIZE)
fn lut_probe(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&lut_temperatures) {
        return;
    }
    lut_colours[index] = lut_sample(lut_table, lut_params, lut_temperatures[index]);
}

// probe.wgsl — evaluates the shared WGSL functions on arrays of inputs so that tests and
// `cargo xtask validate` can measure each f32 kernel against its f64 CPU original
// (crates/srt-gpu/src/probe.rs runs it and does the comparing).
//
// Composed after physics.wgsl, types.wgsl (the probe structs), colour.wgsl and spectral.wgsl.

// Invocations per workgroup of every entry point: set at pipeline creation from
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

@group(0) @binding(6) var<storage, read> spectral_inputs: array<SpectralProbeInput>;
@group(0) @binding(7) var<storage, read_write> spectral_outputs: array<SpectralProbeOutput>;
// ln Y(1500 K) (srt_color::searchlight_reference_ln_y) in x; yzw unused.
@group(0) @binding(11) var<uniform> spectral_params: vec4<f32>;

// The spectral kernels of spectral.wgsl (its tables in group 0, bindings 8–10).
@compute @workgroup_size(WORKGROUP_SIZE)
fn spectral_probe(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&spectral_inputs) {
        return;
    }
    let c = spectral_inputs[index];
    let view = SpectralView(u32(c.factors.w), c.factors.z, spectral_params.x);
    var out: SpectralProbeOutput;
    out.reflected = vec4<f32>(spectral_reflected_display(c.rgb_temperature.xyz, c.bands.x, c.bands.y, c.rgb_temperature.w, c.factors.x, c.factors.y, view), 0.0);
    out.emitted = vec4<f32>(spectral_emitted_display(c.rgb_temperature.w, c.bands.z, c.factors.y, view), 0.0);
    spectral_outputs[index] = out;
}

// shadows.wgsl — lights on their own worldlines and their late shadows (docs/physics.md,
// "Moving lights"), in f32: the mirror of srt_physics::RetardedLight (where a moving light's
// worldline crosses the past light cone of a surface event, the direction its light arrives
// in, the distance it travelled in the light's rest frame and the light's Doppler factor into S)
// and of srt_trace's Tracer::shadowed and PreparedObject::blocks (the null ray from the
// retarded event to the surface event, a straight segment in every object's rest frame, tested
// against each non-emitting object's triangles there). surface.wgsl's surface_output adds the
// lights up as srt_trace::shade::arriving_unless_shadowed does.
//
// Composed into the passes that shade (lrt, polygon), with bvh.wgsl (the slab test) and
// surface.wgsl (the triangle test). The values are srt_gpu::shadows': the lights in
// FrameUniforms.lights always, `shadow_scene` read only while a scene has moving lights.

// Every object's BVH, in rows of 16 bytes (srt_gpu::shadows): LightUniforms.counts.y
// ShadowObjects, then from row counts.z the BVH nodes (BvhNode), from row counts.w the triangles
// (RtTriangle's layout).
@group(0) @binding(12) var<storage, read> shadow_scene: array<vec4<u32>>;

// The shadow test's relative margin at both ends of a segment (set from
// srt_gpu::shadows::SHADOW_MARGIN, which says why it is what it is).
override SHADOW_MARGIN: f32;

// Whether the pipeline draws moving lights at all (srt_gpu::shaders::lrt's `lit`): false for a
// scene without them, so that their code is compiled out (llvmpipe and lavapipe pay for the code
// of a branch that no pixel takes).
override MOVING_LIGHTS: bool;

// Whether the pipeline tests the moving lights' light for late shadows
// (srt_gpu::shaders::ObjectVariant's `shadowed`): false for a frame without shadow casters, so
// that the test is compiled out instead of running once per light with no lane active.
override MOVING_LIGHT_SHADOWS: bool;

// The light of a moving light that reaches an event (srt_physics::RetardedLight).
struct RetardedLight {
    // False where the event is on the light's worldline or the numbers are not finite.
    found: bool,
    // The light's retarded event (ct, x, y, z) in S: where and when the arriving light left it.
    source_event: vec4<f32>,
    // Unit propagation direction n in S (light → event).
    direction: vec3<f32>,
    // r_L, the distance the light travelled in the light's rest frame.
    source_distance: f32,
    // The light's Doppler factor into S, 1 / (γ_L (1 − β_L·n)) (doppler_factor(β_L, n)).
    source_doppler: f32,
}

// The light of `light` reaching the event `receiver` (ct, x, y, z) in S, in closed form in S:
// with d = x_E − a − β·ct_E (the event's separation from the light at the same time ct_E) and
// τ = ct_E − ct_L the light's travel time, the light cone gives (1 − β²)τ² − 2(β·d)τ − d·d = 0,
// so with q = √((β·d)² + (1 − β²) d·d): τ = (β·d + q) / (1 − β²), taken as d·d / (q − β·d) where
// β·d < 0 (the same root without cancellation). Then x_L = a + β(ct_E − τ),
// n = (x_E − x_L) / τ = d/τ + β, r_L = γ τ (1 − β·n) = γ q, and the light's Doppler factor
// 1 / (γ (1 − β·n)) = τ / r_L. Mirror of RetardedLight::reaching (which boosts into the light's
// frame instead).
fn retarded_light(light: MovingLight, receiver: vec4<f32>) -> RetardedLight {
    let offset = light.offset_temperature.xyz;
    let beta = light.beta_gamma.xyz;
    let d = receiver.yzw - offset - beta * receiver.x;
    let beta_d = dot(beta, d);
    let d_d = dot(d, d);
    let q = sqrt(beta_d * beta_d + light.strength.y * d_d);
    var tau = d_d / (q - beta_d);
    if (beta_d >= 0.0) {
        tau = (beta_d + q) / light.strength.y;
    }
    let r = light.beta_gamma.w * q;
    let ct = receiver.x - tau;
    let found = tau > 0.0 && tau < 3.0e38 && r > 0.0 && r < 3.0e38;
    return RetardedLight(found, vec4<f32>(ct, offset + beta * ct), normalize(d + beta * tau), r, tau / r);
}

// Shadow caster `index` of shadow_scene.
fn shadow_object(index: u32) -> ShadowObject {
    let row = SHADOW_OBJECT_ROWS * index;
    let m = mat4x4<f32>(
        bitcast<vec4<f32>>(shadow_scene[row]),
        bitcast<vec4<f32>>(shadow_scene[row + 1u]),
        bitcast<vec4<f32>>(shadow_scene[row + 2u]),
        bitcast<vec4<f32>>(shadow_scene[row + 3u]),
    );
    return ShadowObject(m, bitcast<vec4<f32>>(shadow_scene[row + 4u]), shadow_scene[row + 5u]);
}

// BVH node `index` (among every caster's nodes) of shadow_scene.
fn shadow_node(index: u32) -> BvhNode {
    let row = frame_uniforms.lights.counts.z + SHADOW_NODE_ROWS * index;
    let a = shadow_scene[row];
    let b = shadow_scene[row + 1u];
    return BvhNode(bitcast<vec3<f32>>(a.xyz), a.w, bitcast<vec3<f32>>(b.xyz), b.w);
}

// The corners of triangle `index` (among every caster's triangles) of shadow_scene.
fn shadow_triangle(index: u32) -> array<vec3<f32>, 3> {
    let row = frame_uniforms.lights.counts.w + SHADOW_TRIANGLE_ROWS * index;
    return array<vec3<f32>, 3>(
        bitcast<vec3<f32>>(shadow_scene[row].xyz),
        bitcast<vec3<f32>>(shadow_scene[row + 1u].xyz),
        bitcast<vec3<f32>>(shadow_scene[row + 2u].xyz),
    );
}

// Whether a triangle of the BVH rooted at node `root` crosses the segment from `start` to `end`
// (rest coordinates of its object) strictly inside: more than SHADOW_MARGIN · (1 + length +
// max|start|) from either end, which keeps the lit point's own surface and the light out of it
// (mirror of PreparedObject::blocks, whose margin is 10⁻⁹ in f64). Any hit will do: the walk
// stops at the first (bvh.wgsl's walk, on its one stack).
fn shadow_segment_blocked(root: u32, start: vec3<f32>, end: vec3<f32>) -> bool {
    let delta = end - start;
    let span = length(delta);
    let magnitude = abs(start);
    let margin = SHADOW_MARGIN * (1.0 + span + max(magnitude.x, max(magnitude.y, magnitude.z)));
    if (!(span > 2.0 * margin)) {
        return false;
    }
    let direction = delta / span;
    let inverse = safe_inverse(direction);
    let far = span - margin;
    let root_node = shadow_node(root);
    if (slab_entry(root_node.min, root_node.max, start, inverse, far) < 0.0) {
        return false;
    }
    var walk = bvh_walk(root);
    loop {
        let node = shadow_node(walk.node);
        if (node.primitive_count > 0u) {
            for (var k = node.first; k < node.first + node.primitive_count; k++) {
                let hit = intersect_triangle(start, direction, shadow_triangle(k));
                if (hit.found && hit.distance > margin && hit.distance < far) {
                    return true;
                }
            }
            bvh_leave(&walk);
        } else {
            let a = shadow_node(node.first);
            let b = shadow_node(node.first + 1u);
            let ea = slab_entry(a.min, a.max, start, inverse, far);
            let eb = slab_entry(b.min, b.max, start, inverse, far);
            // The nearer first: a blocker near the lit point is found sooner.
            bvh_step(&walk, node.first, ea >= 0.0, eb >= 0.0, ea <= eb);
        }
        if (walk.done) {
            break;
        }
    }
    return false;
}

// Whether an object blocks `light` on its null ray to the surface event `receiver` (in S): the
// segment from the event to the light's retarded event, taken into each non-emitting caster's
// rest frame (emitters, the lamps' visible bulbs, cast no shadow). For the object being shaded
// (scene index `own`) the event's rest coordinates `receiver_rest` are used as they are, rather
// than rounded once more through S. Mirror of Tracer::shadowed.
fn moving_light_shadowed(light: RetardedLight, receiver: vec4<f32>, own: u32, receiver_rest: vec4<f32>) -> bool {
    if (!MOVING_LIGHT_SHADOWS) {
        return false;
    }
    for (var i = 0u; i < frame_uniforms.lights.counts.y; i++) {
        let caster = shadow_object(i);
        if (caster.bvh.y != 0u) {
            continue;
        }
        let offset = vec4<f32>(0.0, caster.offset.xyz);
        var start = (caster.observer_to_rest * (receiver - offset)).yzw;
        if (caster.bvh.z == own) {
            start = receiver_rest.yzw;
        }
        let end = (caster.observer_to_rest * (light.source_event - offset)).yzw;
        if (shadow_segment_blocked(caster.bvh.x, start, end)) {
            return true;
        }
    }
    return false;
}

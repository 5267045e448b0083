// bvh.wgsl — the slab test of BVH traversal, shared by the ray tracer's nearest hit (rt.wgsl,
// bvh_nearest_hit) and the shadow test's any hit (shadows.wgsl, shadow_segment_blocked); the
// Rust mirror is srt_gpu::bvh (safe_inverse, box_entry).

// Factor on the slab test's exit distance: 1 + 2γ₃, rounded up (set from
// srt_gpu::bvh::SLAB_TOLERANCE).
override SLAB_TOLERANCE: f32;

// 1 / direction per axis, components nearer 0 than 10⁻²⁰ replaced by 10⁻²⁰ (no ∞, no 0 × ∞).
fn safe_inverse(direction: vec3<f32>) -> vec3<f32> {
    return 1.0 / select(direction, vec3<f32>(1e-20), abs(direction) < vec3<f32>(1e-20));
}

// Where the ray origin + s·direction (`inverse` = safe_inverse(direction)) enters the box
// [lo, hi] (0 if it starts inside), or −1 if it misses the box or meets it only beyond `limit`.
// The exit is taken a few rounding units late.
fn slab_entry(lo_corner: vec3<f32>, hi_corner: vec3<f32>, origin: vec3<f32>, inverse: vec3<f32>, limit: f32) -> f32 {
    let a = (lo_corner - origin) * inverse;
    let b = (hi_corner - origin) * inverse;
    let lo = min(a, b);
    let hi = max(a, b);
    let near = max(max(lo.x, lo.y), max(lo.z, 0.0));
    let far = min(min(hi.x, hi.y), hi.z);
    return select(-1.0, near, near <= far * SLAB_TOLERANCE && near <= limit);
}

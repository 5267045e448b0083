// bvh.wgsl — the one BVH walk and its slab test, shared by every traversal: the ray tracer's
// nearest hit (rt.wgsl, bvh_nearest_hit), a moving body's piece search and leaf test (rt.wgsl,
// piece_nearest_hit, box_meets_leaf) and the shadow test's any hit (shadows.wgsl,
// shadow_segment_blocked). Each traversal reads its own nodes and does its own leaf work; the walk
// (bvh_step) decides where to go next. The Rust mirror is srt_gpu::bvh (safe_inverse, box_entry,
// ObjectBvh::nearest_hit).

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

// The one traversal stack of this invocation, shared by its walks, which never nest (each runs
// to its end before the next begins). A module-scope variable rather than a parameter: GLSL
// (wgpu's GL backend) passes a pointer parameter by copying it in and out, which for 64 entries at
// every step of a walk cost llvmpipe several times the walk itself; and it is zeroed once per
// invocation, not once per walk.
var<private> bvh_stack: array<u32, BVH_STACK_SIZE>;

// Where a walk through a BVH stands: the node to visit, the entries on bvh_stack, and whether it
// is over. Nodes are indices into the traversal's own node array; an inner node's children are
// `first` and `first + 1`.
struct BvhWalk {
    node: u32,
    top: u32,
    done: bool,
}

// A walk that starts at `root`.
fn bvh_walk(root: u32) -> BvhWalk {
    return BvhWalk(root, 0u, false);
}

// The walk's next node, once the current one is judged: for an inner node whose children are
// `first` and `first + 1`, `enter_a` and `enter_b` say which to enter (`a_first`: `first` before
// `first + 1` when both, the other kept on bvh_stack); a leaf, or an inner node entering neither,
// resumes from the stack, and the walk is over when the stack is empty.
fn bvh_step(
    walk: ptr<function, BvhWalk>,
    first: u32,
    enter_a: bool,
    enter_b: bool,
    a_first: bool,
) {
    if (enter_a && enter_b) {
        bvh_stack[(*walk).top] = select(first, first + 1u, a_first);
        (*walk).top++;
        (*walk).node = select(first + 1u, first, a_first);
    } else if (enter_a || enter_b) {
        (*walk).node = select(first + 1u, first, enter_a);
    } else if ((*walk).top == 0u) {
        (*walk).done = true;
    } else {
        (*walk).top--;
        (*walk).node = bvh_stack[(*walk).top];
    }
}

// bvh_step after a leaf: resume from the stack.
fn bvh_leave(walk: ptr<function, BvhWalk>) {
    bvh_step(walk, 0u, false, false, true);
}

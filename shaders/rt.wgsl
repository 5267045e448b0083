// rt.wgsl — the GPU ray tracer (`--method rt`): the second exact method beside the LRT's
// footprints. Per object, its visibility pass draws the footprints of the object's box (the
// proxy pass run over the box's 12 triangles, wound inward so that the faces turned towards the
// observer are culled when it is clearly outside the box): a pixel's ray that reaches anything
// inside the box leaves it through a face that is drawn. Each
// fragment traces its viewing ray in the object's rest frame S′ (Eq. 3, 5) through the object's
// BVH and keeps the nearest triangle hit (Eq. 15–16), written as lrt.wgsl's visibility pass
// writes it (`visible`: id, apparent distance as depth). The LRT's shading pass then shades each
// pixel once.
//
// So a pixel costs one BVH walk per object whose box it sees, however many triangles lie behind
// each other there: the reference's algorithm (srt-trace), where the LRT pays one ray test per
// footprint covering the pixel.
//
// A body that spins or thrusts in S′ (motion.wgsl) is drawn through the box that holds it at
// every event a backward ray can meet it (srt_gpu::motion::sweep_bounds), and each fragment
// marches the ray's body-space curve piece by piece, each piece's candidates from the BVH by box
// overlap (moving_nearest_hit; mirror: crates/srt-trace/src/moving.rs).
//
// Mirror: srt_gpu::bvh::ObjectBvh::nearest_hit (the traversal, tested against a test of every
// triangle) and crates/srt-trace (the image, compared by `cargo xtask validate`).
// Composed after lrt.wgsl (it uses `fragment_count`, `box_vertex`, `LrtVarying`, `LeanVarying`,
// `full_varying`, `varying_ray`, `VisibilityOutput`, `visible`),
// bvh.wgsl (the slab test) and motion.wgsl (the moving bodies' curves and pieces).

// The object's BVH nodes (srt_gpu::bvh::ObjectBvh::nodes), root first.
@group(3) @binding(3) var<storage, read> bvh_nodes: array<BvhNode>;
// The object's triangles in leaf order, with their ids.
@group(3) @binding(4) var<storage, read> bvh_triangles: array<RtTriangle>;

// Where the ray enters the node's box (bvh.wgsl's slab_entry: 0 if it starts inside), or −1 if
// it misses the box or meets it only beyond `limit`.
fn box_entry(node: u32, origin: vec3<f32>, inverse: vec3<f32>, limit: f32) -> f32 {
    return slab_entry(bvh_nodes[node].min, bvh_nodes[node].max, origin, inverse, limit);
}

// The nearest hit of the ray with the object's triangles at a distance in [lower, limit), through
// its BVH; `triangle` is the hit's entry in bvh_triangles. Ties keep the triangle found first.
struct BvhHit {
    found: bool,
    distance: f32,
    triangle: u32,
}

fn bvh_nearest_hit(origin: vec3<f32>, direction: vec3<f32>, lower: f32, limit: f32) -> BvhHit {
    var best = BvhHit(false, limit, 0u);
    let inverse = safe_inverse(direction);
    if (box_entry(0u, origin, inverse, best.distance) < 0.0) {
        return best;
    }
    var walk = bvh_walk(0u);
    loop {
        let count = bvh_nodes[walk.node].primitive_count;
        let first = bvh_nodes[walk.node].first;
        if (count > 0u) {
            for (var k = first; k < first + count; k++) {
                let t = bvh_triangles[k];
                let hit = intersect_triangle(origin, direction, array<vec3<f32>, 3>(t.p0, t.p1, t.p2));
                if (hit.found && hit.distance < best.distance && hit.distance >= lower) {
                    best = BvhHit(true, hit.distance, k);
                }
            }
            bvh_leave(&walk);
        } else {
            let ea = box_entry(first, origin, inverse, best.distance);
            let eb = box_entry(first + 1u, origin, inverse, best.distance);
            bvh_step(&walk, first, ea >= 0.0, eb >= 0.0, ea <= eb);
        }
        if (walk.done) {
            break;
        }
    }
    return best;
}

// Whether the node's box overlaps the box [lo, hi].
fn box_overlaps(node: u32, lo: vec3<f32>, hi: vec3<f32>) -> bool {
    return all(bvh_nodes[node].min <= hi) && all(bvh_nodes[node].max >= lo);
}

// Whether the crossing `hit` of triangle entry `k` is nearer than `best`: by distance, then by the
// lower (part, triangle), as the reference breaks ties.
fn crossing_closer(hit: TriangleHit, k: u32, best: BvhHit) -> bool {
    if (!best.found || hit.distance < best.distance) {
        return true;
    }
    if (hit.distance > best.distance) {
        return false;
    }
    let a = bvh_triangles[k];
    let b = bvh_triangles[best.triangle];
    return a.part < b.part || (a.part == b.part && a.triangle < b.triangle);
}

// Whether the box [lo, hi] may overlap the box of some BVH leaf: false only where it overlaps
// none. The walk descends while exactly one child's box overlaps [lo, hi] and answers true at a
// leaf or where both do. It keeps no stack: on llvmpipe's GL driver a stack walk here (on
// bvh_stack or on an array of its own, to the end or stopping at the first leaf) lost the crossings
// of whole blocks of 4×2 pixels in the later pieces' walks, even where its answer was not used
// (validate's wheel-passing; lavapipe drew them right).
fn box_meets_leaf(lo: vec3<f32>, hi: vec3<f32>) -> bool {
    if (!box_overlaps(0u, lo, hi)) {
        return false;
    }
    var node = 0u;
    var met = true;
    loop {
        if (bvh_nodes[node].primitive_count > 0u) {
            break;
        }
        let first = bvh_nodes[node].first;
        let a = box_overlaps(first, lo, hi);
        let b = box_overlaps(first + 1u, lo, hi);
        if (a && b) {
            break;
        }
        if (!a && !b) {
            met = false;
            break;
        }
        node = select(first + 1u, first, a);
    }
    return met;
}

// The nearest crossing on one piece of a moving body's curve among the triangles whose BVH boxes
// overlap the piece's padded box (mirror of the reference's traverse_iterator over the query box).
fn piece_nearest_hit(ray: RestRay, piece: MotionPiece) -> BvhHit {
    var best = BvhHit(false, 3.4e38, 0u);
    if (!box_overlaps(0u, piece.lo, piece.hi)) {
        return best;
    }
    var walk = bvh_walk(0u);
    loop {
        let count = bvh_nodes[walk.node].primitive_count;
        let first = bvh_nodes[walk.node].first;
        if (count > 0u) {
            for (var k = first; k < first + count; k++) {
                let t = bvh_triangles[k];
                let hit = motion_crossing(ray, piece, array<vec3<f32>, 3>(t.p0, t.p1, t.p2));
                if (hit.found && crossing_closer(hit, k, best)) {
                    best = BvhHit(true, hit.distance, k);
                }
            }
            bvh_leave(&walk);
        } else {
            let a = box_overlaps(first, piece.lo, piece.hi);
            let b = box_overlaps(first + 1u, piece.lo, piece.hi);
            bvh_step(&walk, first, a, b, true);
        }
        if (walk.done) {
            break;
        }
    }
    return best;
}

// The nearest crossing of the backward ray with the spinning or thrusting body (mirror of
// PreparedObject::closest_hit_moving): the coasting line, the march, the ray before the start.
fn moving_nearest_hit(ray: RestRay) -> BvhHit {
    let plan = motion_plan(ray);
    if (plan.coast_end > 0.0) {
        var hit = bvh_nearest_hit(plan.line_origin, plan.line_direction, 0.0, plan.coast_end * plan.speed);
        if (hit.found) {
            hit.distance /= plan.speed;
            return hit;
        }
    }
    var start = motion_march_start(ray, plan);
    for (var k = 1u; k <= plan.pieces; k++) {
        if (motion_grouped(plan) && k % MOTION_PIECES_PER_GROUP == 1u) {
            let group = motion_group(ray, plan, k, start);
            if (!box_meets_leaf(group.lo, group.hi)) {
                start = group.end;
                k = group.last;
                continue;
            }
        }
        let piece = motion_piece(ray, plan, k, start);
        start = piece.end;
        let hit = piece_nearest_hit(ray, piece);
        if (hit.found) {
            return hit;
        }
    }
    if (plan.rest_from >= 0.0) {
        return bvh_nearest_hit(ray.origin, ray.direction, plan.rest_from, 3.4e38);
    }
    return BvhHit(false, 3.4e38, 0u);
}

@fragment
fn rt_visibility(in: LrtVarying) -> VisibilityOutput {
    return rt_visible(in);
}

@fragment
fn rt_visibility_lean(in: LeanVarying) -> VisibilityOutput {
    return rt_visible(full_varying(in, false));
}

// The ray tracer's visibility fragment: its ray's nearest hit in the object's BVH, or a discard.
fn rt_visible(in: LrtVarying) -> VisibilityOutput {
    if (COUNT_FRAGMENTS) {
        atomicAdd(&fragment_count[0], 1u);
    }
    if (sees_nothing(in.position.xy)) {
        discard;
    }
    let ray = varying_ray(in);
    var hit: BvhHit;
    if (motion_kind() == MOTION_REST) {
        hit = bvh_nearest_hit(ray.origin, ray.direction, 0.0, 3.4e38);
    } else {
        hit = moving_nearest_hit(ray);
    }
    if (!hit.found) {
        discard;
    }
    let t = bvh_triangles[hit.triangle];
    return visible(in, vec2<u32>(t.part, t.triangle), ray, hit.distance);
}

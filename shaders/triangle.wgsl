// triangle.wgsl — the one ray–triangle test (Eq. 15–16) of every pass that meets triangles: the
// ray tracer's BVH walk (rt.wgsl), LRT's visibility and shading (lrt.wgsl), a moving body's
// crossings (motion.wgsl) and the shadow test (shadows.wgsl). Watertight (Woop, Benthin and Wald
// 2013, "Watertight Ray/Triangle Intersection", JCGT 2(1)): a ray through an edge or a corner the
// mesh's triangles share meets at least one of them, so a closed mesh has no pinholes in f32.
// The CPU reference (srt_trace::intersect_triangle) makes the same test in f64 and takes the
// same Cramer's-rule distance and barycentrics; crates/srt-gpu/tests/watertight.rs shoots rays
// at shared edges and corners through this code.

struct TriangleHit {
    found: bool,
    distance: f32,
    zeta: f32,
    xi: f32,
}

// a·b − c·d, to within about an ulp of the exact value (Kahan's difference of products with
// fma: w = c·d, its rounding error e = c·d − w exactly where fma is fused), so that its sign is
// right wherever the exact value is not 0.
fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let w = c * d;
    let e = fma(-c, d, w);
    let f = fma(a, b, -w);
    return f + e;
}

// The edge function of the directed edge p → q (2D points in the ray's sheared frame, the ray
// at their origin): p.x·q.y − p.y·q.x, > 0 where the ray passes to the left of the edge. It is
// evaluated on the two points in one order whichever way round they are given (the
// lexicographically smaller first), so two triangles that share the edge, one walking it p → q
// and the other q → p, get exactly opposite values, even where the compiler fuses or reorders
// the products: no ray slips between them.
fn edge_function(p: vec2<f32>, q: vec2<f32>) -> f32 {
    let swapped = q.x < p.x || (q.x == p.x && q.y < p.y);
    let first = select(p, q, swapped);
    let second = select(q, p, swapped);
    let e = difference_of_products(first.x, second.y, first.y, second.x);
    return select(e, -e, swapped);
}

// The corner `a` (relative to the ray's origin) in the ray's sheared frame: axes kx, ky, kz
// with kz the direction's longest, sheared by `shear` = (d[kx], d[ky], 1) / d[kz] so that the ray
// runs along z, z scaled to ψ. Every corner goes through the same operations, so a corner two
// triangles share has the same sheared coordinates in both.
fn sheared_corner(a: vec3<f32>, kx: u32, ky: u32, kz: u32, shear: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(a[kx] - shear.x * a[kz], a[ky] - shear.y * a[kz], shear.z * a[kz]);
}

// The hit of the ray origin + ψ·direction (ψ > 0) with the triangle, edges and corners included,
// both faces (mirror of srt_trace::intersect_triangle): distance ψ and barycentric (ζ, ξ) of
// p[1] and p[2]. Woop et al.'s test: the axis the direction is longest along becomes z, the
// corners relative to the origin are sheared so that the ray is the z axis, and the ray meets
// the triangle where the three edge functions of the sheared corners (U, V, W, each the weight
// of the corner opposite its edge) do not differ in sign. A ray in the triangle's plane (all
// three 0) meets nothing. The distance and barycentrics of a hit are Cramer's, as before.
fn intersect_triangle(origin: vec3<f32>, direction: vec3<f32>, p: array<vec3<f32>, 3>) -> TriangleHit {
    let none = TriangleHit(false, 0.0, 0.0, 0.0);
    let size = abs(direction);
    var kz = 2u;
    if (size.x > size.y && size.x > size.z) {
        kz = 0u;
    } else if (size.y > size.z) {
        kz = 1u;
    }
    let kx = (kz + 1u) % 3u;
    let ky = (kz + 2u) % 3u;
    let shear = vec3<f32>(direction[kx], direction[ky], 1.0) / direction[kz];
    let a = sheared_corner(p[0] - origin, kx, ky, kz, shear);
    let b = sheared_corner(p[1] - origin, kx, ky, kz, shear);
    let c = sheared_corner(p[2] - origin, kx, ky, kz, shear);
    let u = edge_function(b.xy, c.xy);
    let v = edge_function(c.xy, a.xy);
    let w = edge_function(a.xy, b.xy);
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) {
        return none;
    }
    let det = u + v + w;
    if (det == 0.0) {
        return none;
    }
    // Where the ray meets the plane, as the plane's equations relative to p[0] give it
    // (Cramer's rule, the CPU's): the sheared frame's ψ sums terms as large as the corners'
    // distances along the ray, which loses f32 digits on a long triangle seen at a grazing
    // angle (a floor), where this does not. The test above alone decides whether it is a hit.
    let sigma = p[1] - p[0];
    let tau = p[2] - p[0];
    let from_corner = origin - p[0];
    let q1 = cross(direction, tau);
    let m = dot(sigma, q1);
    if (m == 0.0) {
        let distance = (u * a.z + v * b.z + w * c.z) / det;
        return TriangleHit(distance > 0.0, distance, v / det, w / det);
    }
    let q2 = cross(from_corner, sigma);
    let distance = dot(tau, q2) / m;
    return TriangleHit(distance > 0.0, distance, dot(from_corner, q1) / m, dot(direction, q2) / m);
}

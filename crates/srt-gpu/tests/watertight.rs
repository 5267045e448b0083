//! The GPU's ray–triangle test (shaders/triangle.wgsl's `intersect_triangle`, the one every pass
//! that meets triangles calls) is watertight: rays aimed in f32 at the edges and corners that
//! the triangles of closed meshes share (a cube, spheres of several segment counts, the embedded
//! spider) meet one of the triangles around the point they aim at, at the distance the f64 CPU
//! test (`srt_trace::intersect_triangle`) finds, at several scales and offsets of the mesh: no
//! ray slips through to the mesh's far side. The shader's own code runs, through a small compute
//! kernel that tests one ray against one triangle per invocation.

use std::collections::HashMap;
use std::path::Path;

use glam::{DVec3, Vec3};
use srt_gpu::shaders::{TRIANGLE, compose};
use srt_gpu::{GpuContext, context_or_skip};
use srt_scene::{SceneDescription, builtin::find_builtin};
use wgpu::util::DeviceExt as _;

/// The test kernel: pair `i` is one ray and one triangle; its output is (found, ψ, ζ, ξ).
const KERNEL: &str = r"
struct Pair {
    origin: vec4<f32>,
    direction: vec4<f32>,
    p0: vec4<f32>,
    p1: vec4<f32>,
    p2: vec4<f32>,
}
@group(0) @binding(0) var<storage, read> pairs: array<Pair>;
@group(0) @binding(1) var<storage, read_write> hits: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * 4194240u;
    if (i >= arrayLength(&pairs)) {
        return;
    }
    let q = pairs[i];
    let h = intersect_triangle(q.origin.xyz, q.direction.xyz, array<vec3<f32>, 3>(q.p0.xyz, q.p1.xyz, q.p2.xyz));
    hits[i] = vec4<f32>(select(0.0, 1.0, h.found), h.distance, h.zeta, h.xi);
}
";

/// Invocations per row of the dispatch (65 535 workgroups of 64), as the kernel's `i` counts.
const ROW: usize = 65_535 * 64;

/// One ray and one triangle, as the kernel reads them.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Pair {
    origin: [f32; 4],
    direction: [f32; 4],
    corners: [[f32; 4]; 3],
}

/// Runs the kernel over `pairs`: (found, ψ, ζ, ξ) per pair.
fn run_kernel(ctx: &GpuContext, pairs: &[Pair]) -> Vec<[f32; 4]> {
    let device = &ctx.device;
    let source = compose(&[("triangle.wgsl", TRIANGLE), ("watertight kernel", KERNEL)]);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("watertight"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("watertight"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: wgpu::PipelineCompilationOptions::default(),
        cache: None,
    });
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("watertight pairs"),
        contents: bytemuck::cast_slice(pairs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (pairs.len() * size_of::<[f32; 4]>()) as u64;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("watertight hits"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("watertight readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("watertight"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        let groups = pairs.len().div_ceil(64);
        let rows = groups.div_ceil(65_535);
        let columns = groups.min(65_535);
        pass.dispatch_workgroups(columns as u32, rows as u32, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let bytes = ctx.read_buffer(&readback).expect("the hits read back");
    ctx.take_errors().expect("no wgpu errors");
    bytemuck::pod_collect_to_vec(&bytes)
}

/// A closed mesh as the GPU holds it: f32 corners, triangles as indices into its distinct
/// corners (corners with the same f32 bits are one, as a shared edge is for the GPU).
struct Mesh32 {
    name: String,
    corners: Vec<Vec3>,
    triangles: Vec<[usize; 3]>,
}

impl Mesh32 {
    /// `positions` of `triangles`, scaled by `scale` and moved by `offset` in f64, then rounded
    /// to f32 and welded by their bits.
    fn new(name: String, triangles: &[[DVec3; 3]], scale: f64, offset: DVec3) -> Self {
        let mut index: HashMap<[u32; 3], usize> = HashMap::new();
        let mut corners = Vec::new();
        let triangles = triangles
            .iter()
            .map(|t| {
                t.map(|p| {
                    let p = (p * scale + offset).as_vec3();
                    *index
                        .entry(p.to_array().map(f32::to_bits))
                        .or_insert_with(|| {
                            corners.push(p);
                            corners.len() - 1
                        })
                })
            })
            .collect();
        Self {
            name,
            corners,
            triangles,
        }
    }

    /// Triangle `t`'s corners.
    fn corners_of(&self, t: usize) -> [Vec3; 3] {
        self.triangles[t].map(|k| self.corners[k])
    }

    /// Triangle `t`'s unit normal (f64), or `None` if it is degenerate.
    fn normal(&self, t: usize) -> Option<DVec3> {
        let [a, b, c] = self.corners_of(t).map(Vec3::as_dvec3);
        (b - a).cross(c - a).try_normalize()
    }

    /// Every edge shared by exactly two triangles that walk it in opposite directions (wound
    /// alike, so that seen from one side they lie on either side of it), with them, and every
    /// corner all of whose edges are such, with its triangles: the points a ray must not slip
    /// through.
    fn shared_features(&self) -> Vec<(Vec<Vec3>, Vec<usize>)> {
        let mut edges: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        let mut forward: HashMap<(usize, usize), usize> = HashMap::new();
        let mut around: HashMap<usize, Vec<usize>> = HashMap::new();
        for (t, corners) in self.triangles.iter().enumerate() {
            if corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0] {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (corners[k], corners[(k + 1) % 3]);
                edges.entry((a.min(b), a.max(b))).or_default().push(t);
                *forward.entry((a.min(b), a.max(b))).or_default() += usize::from(a < b);
                around.entry(a).or_default().push(t);
            }
        }
        let manifold = |a: usize, b: usize| {
            let key = (a.min(b), a.max(b));
            edges.get(&key).map(Vec::len) == Some(2) && forward.get(&key) == Some(&1)
        };
        let mut features: Vec<(Vec<Vec3>, Vec<usize>)> = Vec::new();
        let mut sorted: Vec<_> = edges
            .iter()
            .filter(|(key, _)| manifold(key.0, key.1))
            .collect();
        sorted.sort();
        for (&(a, b), ts) in sorted {
            let (p, q) = (self.corners[a], self.corners[b]);
            // Points along the edge, in f32: the middle, a third of the way, and near an end.
            let points = [0.5, 1.0 / 3.0, 0.9].map(|s| p + (q - p) * s).to_vec();
            features.push((points, ts.clone()));
        }
        let mut vertices: Vec<_> = around.into_iter().collect();
        vertices.sort();
        for (v, ts) in vertices {
            let closed = ts.iter().all(|&t| {
                let c = self.triangles[t];
                c.iter().filter(|&&k| k != v).all(|&k| manifold(v, k))
            });
            if closed {
                features.push((vec![self.corners[v]], ts));
            }
        }
        features
    }
}

/// What the rays at one mesh found.
#[derive(Debug, Default)]
struct Tally {
    rays: usize,
    /// Rays that met none of the triangles around the point they aim at.
    misses: usize,
    /// Rays whose nearest hit there is not at the f64 test's distance.
    wrong_distance: usize,
    /// Rays the f64 CPU test (not watertight: Cramer's rule) found no triangle for, for the
    /// report only.
    cpu_misses: usize,
    /// A missing ray, for the report.
    example: Option<String>,
}

/// The rays at `mesh`'s shared edges and corners, from outside along the mean normal of the
/// triangles around each point, tilted, with `every`-th feature kept; their pairs with the
/// triangles around the point.
fn rays_at(mesh: &Mesh32, every: usize, size: f64) -> Vec<(Vec3, Vec3, Vec<usize>)> {
    let tilts = [
        DVec3::ZERO,
        DVec3::new(0.31, -0.17, 0.05),
        DVec3::new(-0.12, 0.23, -0.29),
    ];
    let mut rays = Vec::new();
    for (points, triangles) in mesh.shared_features().into_iter().step_by(every) {
        let normals: Option<Vec<DVec3>> = triangles.iter().map(|&t| mesh.normal(t)).collect();
        let Some(normals) = normals else { continue };
        let Some(mean) = normals.iter().sum::<DVec3>().try_normalize() else {
            continue;
        };
        for point in points {
            for tilt in tilts {
                let Some(back) = (mean + tilt).try_normalize() else {
                    continue;
                };
                // Only rays that cross every triangle around the point from the same side.
                if normals.iter().any(|n| n.dot(back) < 0.05) {
                    continue;
                }
                let origin = point.as_dvec3() + back * (3.0 * size);
                let origin32 = origin.as_vec3();
                let direction = (point.as_dvec3() - origin32.as_dvec3()).as_vec3();
                rays.push((origin32, direction, triangles.clone()));
            }
        }
    }
    rays
}

/// Shoots `rays` (origin, direction, triangles around the aimed point) at `mesh` on the GPU and
/// compares each with the f64 test of the same f32 numbers.
fn shoot(ctx: &GpuContext, mesh: &Mesh32, rays: &[(Vec3, Vec3, Vec<usize>)]) -> Tally {
    let four = |v: Vec3| [v.x, v.y, v.z, 0.0];
    let pairs: Vec<Pair> = rays
        .iter()
        .flat_map(|(origin, direction, triangles)| {
            triangles.iter().map(move |&t| Pair {
                origin: four(*origin),
                direction: four(*direction),
                corners: mesh.corners_of(t).map(four),
            })
        })
        .collect();
    assert!(pairs.len() < ROW * 8, "a dispatch of at most 8 rows");
    let hits = run_kernel(ctx, &pairs);
    let mut tally = Tally::default();
    let mut next = 0;
    for (origin, direction, triangles) in rays {
        let found = &hits[next..next + triangles.len()];
        next += triangles.len();
        tally.rays += 1;
        let gpu = found
            .iter()
            .filter(|h| h[0] == 1.0)
            .map(|h| h[1])
            .fold(f32::INFINITY, f32::min);
        let (o, d) = (origin.as_dvec3(), direction.as_dvec3());
        let nearest = |test: fn(DVec3, DVec3, [DVec3; 3]) -> Option<srt_trace::TriangleHit>| {
            triangles
                .iter()
                .filter_map(|&t| test(o, d, mesh.corners_of(t).map(Vec3::as_dvec3)))
                .map(|h| h.distance)
                .fold(f64::INFINITY, f64::min)
        };
        let mut cpu = nearest(srt_trace::intersect_triangle);
        if cpu == f64::INFINITY {
            tally.cpu_misses += 1;
            cpu = nearest(srt_trace::plane_hit);
        }
        if gpu == f32::INFINITY {
            tally.misses += 1;
            tally.example.get_or_insert_with(|| {
                format!(
                    "{} origin {origin:?} direction {direction:?} triangles {triangles:?}",
                    mesh.name
                )
            });
        } else if (f64::from(gpu) - cpu).abs() > 1e-4 * cpu {
            tally.wrong_distance += 1;
        }
    }
    tally
}

/// The meshes: a cube, spheres of 7, 64, 333 and 900 segments, the embedded spider; each as
/// f64 triangles and the stride of its features to test.
fn meshes() -> Vec<(String, Vec<[DVec3; 3]>, usize)> {
    let shape = |name: &str, shape: &str| {
        let text = format!(
            "[observer]\nposition = [0.0, -10.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n[[object]]\nshape = {shape}\n"
        );
        let (scene, _) = SceneDescription::from_toml_str(&text, name)
            .and_then(|d| d.build(Path::new("/")))
            .expect("the test's shape builds");
        triangles_of(&scene)
    };
    let spider = find_builtin("spider").expect("the spider is a built-in scene");
    let (spider, _) = spider.build().expect("the spider builds");
    let mut meshes = vec![(
        "cube".to_owned(),
        shape("cube", r#"{ type = "cube", size = 1.0, subdivisions = 3 }"#),
        1,
    )];
    for (segments, every) in [(7, 1), (64, 3), (333, 41), (900, 301)] {
        meshes.push((
            format!("sphere-{segments}"),
            shape(
                "sphere",
                &format!(r#"{{ type = "sphere", radius = 1.5, segments = {segments} }}"#),
            ),
            every,
        ));
    }
    meshes.push(("spider".to_owned(), triangles_of(&spider), 7));
    meshes
}

/// Every triangle of `scene`'s objects, in their rest frames.
fn triangles_of(scene: &srt_scene::Scene) -> Vec<[DVec3; 3]> {
    scene
        .objects
        .iter()
        .flat_map(|o| &o.parts)
        .flat_map(|p| (0..p.mesh.triangles().len()).map(|t| p.mesh.triangle_positions(t)))
        .collect()
}

#[test]
fn rays_at_shared_edges_and_corners_of_closed_meshes_never_miss() {
    let Some(ctx) = context_or_skip("rays_at_shared_edges_and_corners_of_closed_meshes_never_miss")
    else {
        return;
    };
    let mut failures = Vec::new();
    let mut total = 0;
    for (name, triangles, every) in meshes() {
        for scale in [1e-3, 1.0, 1e4] {
            for offset in [DVec3::ZERO, DVec3::new(37.5, -81.25, 12.0)] {
                let mesh = Mesh32::new(
                    format!("{name}×{scale}+{offset}"),
                    &triangles,
                    scale,
                    offset * scale,
                );
                let rays = rays_at(&mesh, every, scale);
                let tally = shoot(&ctx, &mesh, &rays);
                total += tally.rays;
                println!(
                    "{}: rays={} misses={} wrong_distance={} cpu_misses={}",
                    mesh.name, tally.rays, tally.misses, tally.wrong_distance, tally.cpu_misses
                );
                assert!(
                    tally.rays > 50,
                    "{}: too few rays to say anything ({})",
                    mesh.name,
                    tally.rays
                );
                if tally.misses > 0 || tally.wrong_distance > 0 {
                    failures.push(format!("{tally:?}"));
                }
            }
        }
    }
    println!("rays at shared edges and corners: {total}");
    assert!(
        failures.is_empty(),
        "rays slipped through:\n{}",
        failures.join("\n")
    );
}

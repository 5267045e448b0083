//! GPU images against the exact CPU reference: every built-in scene with the exact methods (local
//! ray tracing, the BVH ray tracer and `auto`, which mixes them per object: must agree) and the
//! polygon baseline (reported, expected to differ), with the paper's colour and with spectral
//! colour; moving lights and their late shadows in every colour and effect.

use std::sync::atomic::AtomicBool;

use glam::DVec3;
use srt_gpu::pipelines::Varyings;
use srt_gpu::{FootprintShape, GpuRenderer, Method, context_or_skip};
use srt_scene::{
    Effects, Material, Mesh, Part, Scene, SceneDescription, SurfaceColour, builtin_scenes,
};
use srt_trace::compare::{compare, compare_radiance, compare_seen};
use srt_trace::{Output, RenderSettings, Tracer};

use crate::common;

use common::{HEIGHT, WIDTH, cpu_image};

#[test]
fn exact_methods_match_the_cpu_reference_on_every_builtin_scene() {
    let Some(ctx) = context_or_skip("exact_methods_match_the_cpu_reference_on_every_builtin_scene")
    else {
        return;
    };
    for builtin in builtin_scenes() {
        let (scene, _) = builtin.build().unwrap();
        let moving = scene.objects.iter().any(|o| !o.motion.is_rest());
        let reference = cpu_image(&scene);
        let mut renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
        renderer.set_fragment_counting(true);
        let mut line = format!("scene={}", builtin.name);
        for (method, shape) in [
            (Method::Lrt, FootprintShape::Hull),
            (Method::Lrt, FootprintShape::Rectangle),
            (Method::Rt, FootprintShape::Hull),
            (Method::Auto, FootprintShape::Hull),
            (Method::Polygon, FootprintShape::Hull),
        ] {
            let (image, stats) = renderer.render(&ctx, &scene, method, shape).unwrap();
            let mismatch = compare(&reference, &image.to_rgb8(), 2, 1);
            line += &format!(
                " {}/{:?}: mismatch={:.5} max={} fragments={:?}",
                method.name(),
                shape,
                mismatch.fraction(),
                mismatch.max_difference,
                stats.fragments
            );
            if method.is_exact() {
                assert!(mismatch.fraction() <= 0.001, "{line}");
                // Every footprint was drawn at or in front of every hit its fragments found:
                // what the visibility passes declare to the GPU (shaders::ConservativeDepth).
                let fragments = stats.fragments.expect("counting");
                assert!(fragments.run > 0, "{line}");
                assert_eq!(fragments.nearer_than_footprint, 0, "{line}");
            } else if moving {
                // Spinning and thrusting bodies, vertex by vertex: drawn, not exactly.
                let mut rest = scene.clone();
                rest.objects.retain(|o| o.motion.is_rest());
                let drawn = compare(&cpu_image(&rest), &image.to_rgb8(), 2, 1).fraction();
                line += &format!(" (the moving bodies cover {drawn:.4})");
                assert!(drawn > 0.002, "{line}");
            }
        }
        println!("{line}");
    }
    ctx.take_errors().unwrap();
}

/// The GPU's radiance (what an EXR holds: linear, unclamped, before the tone map) agrees with the
/// CPU reference's, relative to each pixel's brightness, on every built-in scene with the
/// searchlight effect (where radiance leaves [0, 1] furthest: fig7's 200 K lamp makes the
/// Doppler-shifted cube 10⁴⁰ times its unit, held at the target's largest value) and in
/// spectral colour; and it exceeds 1 far (display colours end at 1).
#[test]
fn radiance_matches_the_cpu_reference() {
    let Some(ctx) = context_or_skip("radiance_matches_the_cpu_reference") else {
        return;
    };
    let largest = f64::from(srt_gpu::formats::largest_value(ctx.color_format));
    let settings = RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        samples: 1,
    };
    for builtin in builtin_scenes() {
        let (mut scene, _) = builtin.build().unwrap();
        scene.set_effects(Effects::Searchlight);
        for colour in [SurfaceColour::Paper, SurfaceColour::Spectral] {
            scene.colour = colour;
            let tracer = Tracer::new(&scene);
            let mut reference = tracer.render_radiance(settings, &|_| {});
            for pixel in &mut reference.pixels {
                *pixel = pixel.clamp(DVec3::splat(-largest), DVec3::splat(largest));
            }
            let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
            let (image, _) = renderer
                .render_as(
                    &ctx,
                    &scene,
                    Method::Auto,
                    FootprintShape::Hull,
                    Output::Radiance,
                )
                .unwrap();
            let radiance: Vec<DVec3> = image
                .pixels
                .iter()
                .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
                .collect();
            let mismatch = compare_radiance(&reference, &radiance, 0.02, 0.01, 1);
            let line = format!(
                "scene={} colour={colour:?}: radiance mismatch={:.5} max={:.3}",
                builtin.name,
                mismatch.fraction(),
                mismatch.max_difference
            );
            println!("{line}");
            assert!(mismatch.fraction() <= 0.001, "{line}");
            assert!(radiance.iter().all(|p| p.is_finite()), "{line}");
            if builtin.name == "teaser" && colour == SurfaceColour::Paper {
                // The approaching spider, at most 1 on screen, is far brighter than 1.
                let brightest = radiance.iter().map(|p| p.max_element()).fold(0.0, f64::max);
                assert!(brightest > 10.0, "{line}: brightest pixel {brightest}");
            }
        }
    }
    ctx.take_errors().unwrap();
}

#[test]
fn seen_events_match_the_cpu_reference() {
    let Some(ctx) = context_or_skip("seen_events_match_the_cpu_reference") else {
        return;
    };
    // The passes compute in f32; a half-float colour target (GL) rounds each value to 11 bits.
    let half_float = srt_gpu::formats::largest_value(ctx.color_format) < f32::MAX;
    let tolerance = if half_float { 2e-3 } else { 1e-3 };
    for builtin in builtin_scenes() {
        let (scene, _) = builtin.build().unwrap();
        let reference = cpu_image(&scene);
        let events = Tracer::new(&scene)
            .render_seen_events(WIDTH, HEIGHT, &|_| {}, &AtomicBool::new(false))
            .unwrap();
        let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
        for method in [Method::Lrt, Method::Rt] {
            let seen = renderer
                .render_seen(&ctx, &scene, method, FootprintShape::Hull)
                .unwrap();
            let mismatch = compare_seen(&reference, &events, &seen, tolerance, 1);
            let line = format!(
                "scene={} method={method:?}: seen-event mismatch={:.5} max={:.2e} (tolerance {tolerance})",
                builtin.name,
                mismatch.fraction(),
                mismatch.max_difference,
            );
            println!("{line}");
            assert!(mismatch.fraction() <= 0.001, "{line}");
            let objects = seen.iter().filter(|v| v[4] >= 0.0).count();
            assert!(objects > 0, "{line}: no pixel sees an object");
        }
    }
    ctx.take_errors().unwrap();
}

#[test]
fn flipbooks_match_the_cpu_reference() {
    let Some(ctx) = context_or_skip("flipbooks_match_the_cpu_reference") else {
        return;
    };
    // A cube at rest 4.5 away wearing three checkerboards, one per unit of proper time: at
    // ct = 4 + k + ½ its face (4 away) shows frame k mod 3 (its light left ½ into frame k).
    let frames = [
        ([1.0, 0.9, 0.7], [0.2, 0.2, 0.3]),
        ([0.9, 0.2, 0.2], [1.0, 1.0, 1.0]),
        ([0.1, 0.6, 0.2], [0.0, 0.0, 0.0]),
    ]
    .map(|(a, b)| srt_scene::textures::checker(64, 4, a, b));
    let book = std::sync::Arc::new(
        srt_scene::textures::flipbook(&frames, 1.0, "test flipbook".into()).unwrap(),
    );
    let mut scene = SceneDescription::from_toml_str(
        "[observer]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.3, 4.5, 0.2]\nfov_y_deg = 20.0\n\
         [[object]]\nshape = { type = \"cube\", size = 1.0 }\noffset = [0.0, 4.5, 0.0]\n\
         rotate_deg = [0.0, 0.0, 20.0]\n",
        "test",
    )
    .unwrap()
    .build(std::path::Path::new("."))
    .unwrap()
    .0;
    for part in &mut scene.objects[0].parts {
        part.material.texture = Some(book.clone());
    }
    let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
    let mut seen = Vec::new();
    for frame in 0..4 {
        scene.observer.time = 4.5 + f64::from(frame);
        let reference = cpu_image(&scene);
        let (image, _) = renderer
            .render(&ctx, &scene, Method::Lrt, FootprintShape::Hull)
            .unwrap();
        let mismatch = compare(&reference, &image.to_rgb8(), 2, 1);
        let line = format!(
            "ct={}: mismatch={:.5} max={}",
            scene.observer.time,
            mismatch.fraction(),
            mismatch.max_difference
        );
        println!("{line}");
        assert!(mismatch.fraction() <= 0.001, "{line}");
        seen.push(reference.pixels[(HEIGHT / 2 * WIDTH + WIDTH / 2) as usize]);
    }
    // The frames differ, and the fourth unit shows the first frame again.
    assert!(seen[0] != seen[1] && seen[1] != seen[2], "{seen:?}");
    assert_eq!(seen[0], seen[3]);
    ctx.take_errors().unwrap();
}

/// A stack of `layers` parallel squares 0.05 apart, side 1, facing +z, centred at the origin:
/// an object deep enough (its surface over its box's about `layers` / 2) for `auto` to trace it.
fn stack_of_squares(layers: u32) -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for layer in 0..layers {
        let z = 0.05 * (f64::from(layer) - f64::from(layers - 1) / 2.0);
        let first = positions.len() as u32;
        for (x, y) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
            positions.push(DVec3::new(x, y, z));
        }
        triangles.push([first, first + 1, first + 2]);
        triangles.push([first, first + 2, first + 3]);
    }
    Mesh::new(positions, triangles).unwrap()
}

/// The teaser, and a new object `name` moving as its first object does, made of `mesh`
/// (default material, no wireframe).
fn teaser_and_object(name: &str, mesh: Mesh) -> (Scene, srt_scene::Object) {
    let (scene, _) = builtin_scenes()
        .iter()
        .find(|b| b.name == "teaser")
        .expect("teaser is built in")
        .build()
        .unwrap();
    let mut object = scene.objects[0].clone();
    object.name = name.into();
    object.wireframe = None;
    object.parts = vec![Part {
        mesh,
        material: Material::default(),
    }];
    (scene, object)
}

/// Renders `scene` with each exact method (LRT, RT, auto) and asserts that each matches
/// `reference` under validate's rule (2/255, 1 px edge margin, at most 0.1 % of pixels);
/// returns the images in that order. `what` names the case in a failure.
fn exact_methods_match(
    ctx: &srt_gpu::GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    reference: &srt_trace::RenderedImage,
    what: &str,
) -> Vec<Vec<[u8; 3]>> {
    [Method::Lrt, Method::Rt, Method::Auto]
        .into_iter()
        .map(|method| {
            let (image, _) = renderer
                .render(ctx, scene, method, FootprintShape::Hull)
                .unwrap();
            let rgb = image.to_rgb8();
            let mismatch = compare(reference, &rgb, 2, 1);
            println!(
                "{what}, {}: mismatch={:.5} max={}",
                method.name(),
                mismatch.fraction(),
                mismatch.max_difference
            );
            assert!(
                mismatch.fraction() <= 0.001,
                "{what}, {}: {mismatch:?}",
                method.name()
            );
            rgb
        })
        .collect()
}

#[test]
fn auto_traces_deep_objects_and_the_mix_matches_the_cpu_reference() {
    let Some(ctx) =
        context_or_skip("auto_traces_deep_objects_and_the_mix_matches_the_cpu_reference")
    else {
        return;
    };
    // The teaser (shallow objects: footprints) with a deep stack flying through it (traced),
    // in front of and behind the others in different pixels.
    let (mut scene, stack) = teaser_and_object("stack", stack_of_squares(12));
    scene.objects.push(stack);
    let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
    let loads = renderer.object_loads(&scene);
    let stack_load = loads.last().unwrap().unwrap();
    assert!(stack_load.layers > 2.0, "{loads:?}");
    assert!(
        loads.iter().rev().skip(1).flatten().all(|l| l.layers < 2.0),
        "{loads:?}"
    );
    // Which objects auto should trace, worked out here from each object's figures and the
    // adapter's fitted costs (RT's work, per traced pixel × box layers × seen pixels + per
    // object, below LRT's, triangles + per layer pixel × layers × seen pixels; a tie to LRT) as
    // `srt_gpu::auto` documents the rule, not by the rule's code (`MethodCosts::traces`). A
    // CPU adapter traces the deep stack and draws the teaser's spider by LRT (a mix); a
    // hardware GPU's costs decide by the objects' triangles per seen pixel.
    let costs = if ctx.adapter_info.device_type == wgpu::DeviceType::Cpu {
        srt_gpu::auto::CPU_ADAPTER_COSTS
    } else {
        srt_gpu::auto::HARDWARE_COSTS
    };
    let traced: Vec<bool> = loads
        .iter()
        .map(|load| {
            load.is_some_and(|l| {
                let lrt = l.triangles as f64 + costs.per_layer_pixel * l.layers * l.seen_pixels;
                let rt = costs.per_traced_pixel * f64::from(l.box_layers) * l.seen_pixels
                    + costs.per_traced_object;
                rt < lrt
            })
        })
        .collect();
    assert_eq!(
        renderer.auto_traced_objects(&scene),
        traced.iter().filter(|&&t| t).count(),
        "{traced:?} {loads:?}"
    );
    if ctx.adapter_info.device_type == wgpu::DeviceType::Cpu {
        assert!(
            traced[traced.len() - 1] && !traced[0],
            "{traced:?} {loads:?}"
        );
    }
    let reference = cpu_image(&scene);
    let images = exact_methods_match(&ctx, &renderer, &scene, &reference, "the mix");
    // Not vacuous: the stack is on screen (removing it changes the picture).
    let without = cpu_image(&Scene {
        objects: scene.objects[..scene.objects.len() - 1].to_vec(),
        ..scene.clone()
    });
    let changed = compare(&without, &images[2], 2, 0).fraction();
    assert!(
        changed > 0.005,
        "the stack covers only {changed} of the image"
    );
    ctx.take_errors().unwrap();
}

/// `count` open tubes of `sides` flat sides, radii r = 1 to `count`, 40 r long, centred on
/// `centre` along `axis` (each the last scaled): an observer at `centre` sees every triangle
/// reach beside and behind it, and every tube alike.
fn nested_tubes(centre: DVec3, axis: DVec3, count: u32, sides: u32) -> Mesh {
    let (u, v) = axis.any_orthonormal_pair();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for tube in 1..=count {
        let radius = f64::from(tube);
        for side in 0..sides {
            let first = positions.len() as u32;
            for k in [side, side + 1] {
                // Turned by 0.3 so that no seam runs along a pixel diagonal (where f32 and f64
                // may break the tie between the two sides differently).
                let angle = 0.3 + std::f64::consts::TAU * f64::from(k) / f64::from(sides);
                let rim = centre + radius * (angle.cos() * u + angle.sin() * v);
                positions.extend([rim - 20.0 * radius * axis, rim + 20.0 * radius * axis]);
            }
            triangles.push([first, first + 2, first + 3]);
            triangles.push([first, first + 3, first + 1]);
        }
    }
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn triangles_split_beyond_the_piece_slots_are_drawn_by_the_rectangle_of_their_pieces() {
    let Some(ctx) = context_or_skip(
        "triangles_split_beyond_the_piece_slots_are_drawn_by_the_rectangle_of_their_pieces",
    ) else {
        return;
    };
    // Eight tubes around the teaser's observer, along its view: each of the 128 triangles is
    // split into pieces (about 200 per tube at this size), more than the batch's 1 088 piece
    // slots. (The first version of this test found footprint points 2·10⁸ pixels out, whose
    // f32 hulls missed the triangle: MAX_SCREEN_REACH.)
    let (mut scene, mut tubes) = teaser_and_object("tubes", stack_of_squares(1));
    let observer = &scene.observer;
    tubes.parts[0].mesh = nested_tubes(observer.position, observer.direction.normalize(), 8, 8);
    let triangles = tubes.parts[0].mesh.triangles().len() as u64;
    tubes.frame = srt_physics::Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
    scene.objects = vec![tubes];
    let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
    let footprints = renderer.read_footprints(&ctx, &scene).unwrap();
    let drawn = &footprints[0][0];
    let pieces: usize = drawn.iter().map(|t| t.pieces.len()).sum();
    let slots = srt_gpu::types::footprint_slots(triangles) - triangles;
    assert_eq!(pieces as u64, slots, "every piece slot is taken");
    // So some triangle ran out of piece slots, and its own slot holds the rectangle around all
    // its pieces: the ones stored before the slots ran out included. Which triangles run out,
    // and how many of their pieces were stored first, depends on the order in which GPU
    // threads take slots (it differs from run to run on llvmpipe), so the test checks what
    // holds in every order.
    // The rectangle holds the on-screen part of what each stored piece draws.
    let (width, height) = (WIDTH as f32, HEIGHT as f32);
    let holds = |outer: [f32; 4], inner: [f32; 4]| {
        outer[0] <= inner[0].max(0.0)
            && outer[1] <= inner[1].max(0.0)
            && outer[2] >= inner[2].min(width)
            && outer[3] >= inner[3].min(height)
    };
    let overflowed: Vec<_> = drawn.iter().filter(|t| t.own.pieces_overflowed()).collect();
    assert!(
        !overflowed.is_empty(),
        "no triangle fell back to the rectangle of its pieces"
    );
    for t in &overflowed {
        assert_eq!(t.own.hull_len(), 4, "a fallback is a rectangle: {t:?}");
        let own = t.own.bounds().unwrap();
        assert!(
            (t.pieces.iter()).all(|p| p.bounds().is_some_and(|piece| holds(own, piece))),
            "a fallback rectangle misses a stored piece: {t:?}"
        );
    }
    let (image, _) = renderer
        .render(&ctx, &scene, Method::Lrt, FootprintShape::Hull)
        .unwrap();
    let reference = cpu_image(&scene);
    let mismatch = compare(&reference, &image.to_rgb8(), 2, 1);
    println!(
        "{pieces} pieces in {slots} slots: mismatch={:.5} max={}",
        mismatch.fraction(),
        mismatch.max_difference
    );
    assert!(mismatch.fraction() <= 0.001, "{mismatch:?}");
    ctx.take_errors().unwrap();
}

/// LRT with spectral colour agrees with the CPU: `scene`'s mismatch (2/255, 1 px edge margin).
fn assert_spectral_lrt_agrees(ctx: &srt_gpu::GpuContext, name: &str, scene: &Scene) {
    let reference = cpu_image(scene);
    let renderer = GpuRenderer::new(ctx, scene, WIDTH, HEIGHT).unwrap();
    let (image, _) = renderer
        .render(ctx, scene, Method::Lrt, FootprintShape::Hull)
        .unwrap();
    let rgb = image.to_rgb8();
    let mismatch = compare(&reference, &rgb, 2, 1);
    println!(
        "scene={name} spectral mismatch={:.5} max={}",
        mismatch.fraction(),
        mismatch.max_difference
    );
    assert!(mismatch.fraction() <= 0.001, "{name}: {mismatch:?}");
    // Not vacuous: the objects are lit (or glow), not black.
    let lit = rgb.iter().filter(|p| p.iter().any(|&c| c > 40)).count();
    assert!(lit > rgb.len() / 100, "{name}: only {lit} lit pixels");
}

#[test]
fn lrt_matches_the_cpu_reference_with_spectral_colour() {
    let Some(ctx) = context_or_skip("lrt_matches_the_cpu_reference_with_spectral_colour") else {
        return;
    };
    for (builtin, effects) in builtin_scenes()
        .iter()
        .zip([Effects::Doppler, Effects::Searchlight].into_iter().cycle())
    {
        let (mut scene, _) = builtin.build().unwrap();
        scene.set_effects(effects);
        scene.colour = SurfaceColour::Spectral;
        scene.exposure = 1.5;
        assert_spectral_lrt_agrees(&ctx, builtin.name, &scene);
    }
    // An emitter beside a surface with band constants, both moving.
    let text = r#"
        name = "glow"
        [observer]
        position = [0.0, -6.0, 0.5]
        look_at = [0.0, 0.0, 0.0]
        [render]
        colour = "spectral"
        exposure = 2.0
        [[object]]
        shape = { type = "sphere", radius = 1.0, segments = 24 }
        emission = { temperature_k = 3000, brightness = 0.7 }
        beta = [0.0, -0.6, 0.0]
        offset = [-1.5, -3.7, 0.0]
        [[object]]
        shape = { type = "cube", size = 1.5 }
        texture = { type = "checker", squares = 4, colors = [[0.9, 0.1, 0.1], [0.1, 0.2, 0.9]] }
        infrared = 0.9
        ultraviolet = 0.1
        beta = [0.0, -0.5, 0.0]
        offset = [1.5, -3.1, 0.0]
    "#;
    let (scene, _) = SceneDescription::from_toml_str(text, "glow")
        .unwrap()
        .build(std::path::Path::new("/"))
        .unwrap();
    assert_spectral_lrt_agrees(&ctx, "glow", &scene);
    ctx.take_errors().unwrap();
}

/// A ground, a column and a ball all moving (casters and receivers with β ≠ 0: their shadows are
/// tested in moving rest frames), lit by a dimmed lamp and two lights on their own worldlines.
const MOVING_SHADOWS: &str = r#"
    name = "moving shadows"
    [observer]
    position = [0.0, -14.0, 6.0]
    look_at = [0.0, 0.0, 0.5]
    up = [0.0, 0.0, 1.0]
    fov_y_deg = 50.0
    ct = 10.0
    [[light]]
    position = [0.0, -14.0, 6.0]
    temperature_k = 6000.0
    strength = 0.3
    carried = true
    [[light]]
    position = [-2.0, 5.0, 3.0]
    beta = [0.8, 0.0, 0.0]
    temperature_k = 4000.0
    strength = 40.0
    [[light]]
    position = [0.0, 4.0, 4.0]
    beta = [-0.3, -0.4, 0.0]
    temperature_k = 9000.0
    strength = 25.0
    [[object]]
    shape = { type = "cube", size = 1.0, subdivisions = 1 }
    scale = [30.0, 20.0, 0.2]
    translate = [0.0, 0.0, -0.1]
    beta = [0.0, 0.2, 0.0]
    offset = [0.0, -2.0, 0.0]
    [[object]]
    shape = { type = "cube", size = 1.0 }
    scale = [0.6, 0.6, 3.0]
    translate = [0.0, 0.0, 1.5]
    beta = [0.6, 0.0, 0.0]
    offset = [-4.0, 0.0, 0.0]
    [[object]]
    shape = { type = "sphere", radius = 1.0, segments = 24 }
    beta = [-0.5, 0.0, 0.0]
    offset = [2.0, 1.0, 1.5]
"#;

/// Lights on their own worldlines, their late shadows and the lamp's strength agree with the CPU
/// reference in every exact method: the built-in `shadows` (a light flying at 0.9c behind
/// columns at rest) and [`MOVING_SHADOWS`], with the paper's colour and spectral colour,
/// geometry only, the Doppler effect and the searchlight effect (whose colour table takes
/// D_in⁻² off a moving light's strength), with and without shadows, as display colours and as
/// radiance.
#[test]
fn moving_lights_and_late_shadows_match_the_cpu_reference() {
    let Some(ctx) = context_or_skip("moving_lights_and_late_shadows_match_the_cpu_reference")
    else {
        return;
    };
    let (shadows, _) = builtin_scenes()
        .iter()
        .find(|b| b.name == "shadows")
        .expect("shadows is built in")
        .build()
        .unwrap();
    assert!(!shadows.lights.is_empty() && shadows.light.strength < 1.0);
    let (moving, _) = SceneDescription::from_toml_str(MOVING_SHADOWS, "moving shadows")
        .unwrap()
        .build(std::path::Path::new("/"))
        .unwrap();
    assert_eq!(moving.lights.len(), 2);
    let settings = RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        samples: 1,
    };
    let largest = f64::from(srt_gpu::formats::largest_value(ctx.color_format));
    let variants = [
        (Effects::Doppler, SurfaceColour::Paper, true),
        (Effects::Searchlight, SurfaceColour::Paper, true),
        (Effects::Geometry, SurfaceColour::Paper, true),
        (Effects::Doppler, SurfaceColour::Spectral, true),
        (Effects::Searchlight, SurfaceColour::Spectral, true),
        (Effects::Doppler, SurfaceColour::Paper, false),
    ];
    for base in [&shadows, &moving] {
        let renderer = GpuRenderer::new(&ctx, base, WIDTH, HEIGHT).unwrap();
        for (effects, colour, cast) in variants {
            let mut scene = base.clone();
            scene.set_effects(effects);
            scene.colour = colour;
            scene.shadows = cast;
            let reference = cpu_image(&scene);
            let mut line = format!("{} {effects:?} {colour:?} shadows={cast}:", scene.name);
            for method in [Method::Lrt, Method::Rt, Method::Auto, Method::Polygon] {
                let (image, _) = renderer
                    .render(&ctx, &scene, method, FootprintShape::Hull)
                    .unwrap();
                let rgb = image.to_rgb8();
                let mismatch = compare(&reference, &rgb, 2, 1);
                line += &format!(
                    " {} mismatch={:.5} max={}",
                    method.name(),
                    mismatch.fraction(),
                    mismatch.max_difference
                );
                if method.is_exact() {
                    assert!(mismatch.fraction() <= 0.001, "{line}");
                }
                if method == Method::Lrt {
                    // Not vacuous: the moving lights change a good part of the picture.
                    let unlit = cpu_image(&Scene {
                        lights: Vec::new(),
                        ..scene.clone()
                    });
                    let changed = compare(&unlit, &rgb, 2, 1).fraction();
                    line += &format!(" (the lights change {changed:.3})");
                    assert!(changed > 0.05, "{line}");
                }
            }
            let mut expected = Tracer::new(&scene).render_radiance(settings, &|_| {});
            for pixel in &mut expected.pixels {
                *pixel = pixel.clamp(DVec3::splat(-largest), DVec3::splat(largest));
            }
            let (image, _) = renderer
                .render_as(
                    &ctx,
                    &scene,
                    Method::Auto,
                    FootprintShape::Hull,
                    Output::Radiance,
                )
                .unwrap();
            let radiance: Vec<DVec3> = image
                .pixels
                .iter()
                .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
                .collect();
            let mismatch = compare_radiance(&expected, &radiance, 0.02, 0.01, 1);
            line += &format!(
                " radiance mismatch={:.5} max={:.1e}",
                mismatch.fraction(),
                mismatch.max_difference
            );
            println!("{line}");
            assert!(mismatch.fraction() <= 0.001, "{line}");
        }
    }
    // The shadows are drawn: without them the picture differs.
    let mut unshadowed = shadows.clone();
    unshadowed.shadows = false;
    let renderer = GpuRenderer::new(&ctx, &shadows, WIDTH, HEIGHT).unwrap();
    let (image, _) = renderer
        .render(&ctx, &shadows, Method::Lrt, FootprintShape::Hull)
        .unwrap();
    let changed = compare(&cpu_image(&unshadowed), &image.to_rgb8(), 2, 1).fraction();
    println!("the shadows change {changed:.3} of the picture");
    assert!(changed > 0.05, "the shadows change only {changed}");
    // A renderer made for a scene without moving lights has no shadow casters to draw them with.
    let unlit = Scene {
        lights: Vec::new(),
        ..shadows.clone()
    };
    let without = GpuRenderer::new(&ctx, &unlit, WIDTH, HEIGHT).unwrap();
    assert!(matches!(
        without.render(&ctx, &shadows, Method::Lrt, FootprintShape::Hull),
        Err(srt_gpu::GpuError::SceneChanged)
    ));
    ctx.take_errors().unwrap();
}

/// The LRT pass counts its fragments only when asked to, and then shades at least one per
/// covered pixel and runs more than it shades (footprints are conservative); counting changes
/// no pixel.
#[test]
fn fragments_are_counted_only_when_measuring() {
    let Some(ctx) = context_or_skip("fragments_are_counted_only_when_measuring") else {
        return;
    };
    let (scene, _) = builtin_scenes()
        .iter()
        .find(|b| b.name == "fig4")
        .expect("fig4 is built in")
        .build()
        .unwrap();
    let mut renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
    let render = |renderer: &GpuRenderer| {
        renderer
            .render(&ctx, &scene, Method::Lrt, FootprintShape::Hull)
            .unwrap()
    };
    let (plain, stats) = render(&renderer);
    assert_eq!(stats.fragments, None);
    renderer.set_fragment_counting(true);
    let (counted, stats) = render(&renderer);
    let covered = plain.to_rgb8().iter().filter(|p| **p != [0, 0, 0]).count() as u64;
    let fragments = stats.fragments.expect("counting");
    assert!(
        covered > 0 && fragments.shaded >= covered && fragments.run > fragments.shaded,
        "{fragments:?}, {covered} covered"
    );
    assert_eq!(plain.to_rgb8(), counted.to_rgb8());
    renderer.set_fragment_counting(false);
    assert_eq!(render(&renderer).1.fragments, None);
    ctx.take_errors().unwrap();
}

/// An object whose picture covers no pixel's centre is skipped
/// (`culling::ball_between_pixel_centres`) and the picture is the CPU reference's, which does
/// not see it either: a speck of radius 0.002 two units from the camera, centred on the corner
/// between four pixels (about an eighth of a pixel across). Grown to 0.03 (about two pixels),
/// the same speck is kept and drawn. Its ball is the one around its vertices
/// (`BodyExtent::ball`), the sphere's own radius, not the ball around its box.
#[test]
fn objects_between_pixel_centres_are_skipped_and_larger_ones_are_drawn() {
    let Some(ctx) =
        context_or_skip("objects_between_pixel_centres_are_skipped_and_larger_ones_are_drawn")
    else {
        return;
    };
    let (base, template) = teaser_and_object("speck", srt_scene::shapes::uv_sphere(1.0, 16));
    let corner = glam::DVec2::new(
        2.0 * 40.0 / f64::from(WIDTH) - 1.0,
        1.0 - 2.0 * 30.0 / f64::from(HEIGHT),
    );
    let aspect = f64::from(WIDTH) / f64::from(HEIGHT);
    let direction = base.observer.view_direction(corner, aspect).normalize();
    let with_speck = |radius: f64| {
        let mut scene = base.clone();
        let mut speck = template.clone();
        speck.frame = srt_physics::Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
        let at = glam::DMat4::from_translation(base.observer.position + 2.0 * direction);
        speck.parts[0].mesh = srt_scene::shapes::uv_sphere(radius, 16)
            .transformed(at)
            .unwrap();
        scene.objects.push(speck);
        scene
    };
    let without = cpu_image(&base);
    for (radius, seen) in [(0.002, false), (0.03, true)] {
        let scene = with_speck(radius);
        let speck = scene.objects.len() - 1;
        let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
        assert_eq!(
            renderer.objects_in_view(&scene).contains(&speck),
            seen,
            "radius {radius}"
        );
        let reference = cpu_image(&scene);
        // The reference sees the speck exactly where it is kept.
        let changed = compare(&without, &reference.to_rgb8(), 0, 0).fraction();
        assert_eq!(changed > 0.0, seen, "radius {radius}: {changed}");
        exact_methods_match(
            &ctx,
            &renderer,
            &scene,
            &reference,
            &format!("radius {radius}"),
        );
    }
    ctx.take_errors().unwrap();
}

/// Objects out of view are skipped (`GpuRenderer::objects_in_view`) and the picture is still
/// the exact one: the teaser with two cubes of side 3, 8 units behind the camera, 110° from its
/// viewing direction. One rests with the observer and is culled; the other recedes at 0.99c,
/// and aberration brings it to about 12° from the viewing direction, into view: it is kept,
/// drawn, and every exact method agrees with the CPU reference.
#[test]
fn objects_out_of_view_are_skipped_and_those_aberrated_into_view_are_drawn() {
    let Some(ctx) =
        context_or_skip("objects_out_of_view_are_skipped_and_those_aberrated_into_view_are_drawn")
    else {
        return;
    };
    let (mut scene, template) = teaser_and_object("behind", srt_scene::shapes::cube(1.0, 1));
    let (forward, right, _) = scene.observer.basis();
    let behind = 110f64.to_radians();
    let direction = behind.cos() * forward + behind.sin() * right;
    for beta in [DVec3::ZERO, -0.99 * forward] {
        let frame = srt_physics::Frame::new(beta, DVec3::ZERO).unwrap();
        let observer_rest = frame.to_rest(scene.observer.event()).position;
        let at = glam::DMat4::from_translation(observer_rest + 8.0 * direction);
        let mut object = template.clone();
        object.frame = frame;
        object.parts[0].mesh = srt_scene::shapes::cube(3.0, 1).transformed(at).unwrap();
        scene.objects.push(object);
    }
    let (resting, receding) = (scene.objects.len() - 2, scene.objects.len() - 1);
    let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
    let shown = renderer.objects_in_view(&scene);
    assert!(!shown.contains(&resting), "{shown:?}");
    assert!(shown.contains(&receding), "{shown:?}");
    let reference = cpu_image(&scene);
    exact_methods_match(&ctx, &renderer, &scene, &reference, "out of view");
    // Not vacuous: the receding cube is on screen, the resting one is not.
    let without = |index: usize| {
        let mut fewer = scene.clone();
        fewer.objects.remove(index);
        compare(&reference, &cpu_image(&fewer).to_rgb8(), 2, 0).fraction()
    };
    assert!(
        without(receding) > 0.001,
        "the receding cube covers {}",
        without(receding)
    );
    assert_eq!(without(resting), 0.0);
    ctx.take_errors().unwrap();
}

#[test]
fn lean_varyings_draw_the_flat_varyings_images_bit_for_bit() {
    let Some(mut ctx) = context_or_skip("lean_varyings_draw_the_flat_varyings_images_bit_for_bit")
    else {
        return;
    };
    for builtin in builtin_scenes() {
        let (scene, _) = builtin.build().unwrap();
        let reference = cpu_image(&scene);
        let [flat, lean] = [Varyings::Flat, Varyings::Lean].map(|varyings| {
            ctx.varyings = varyings;
            let mut renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
            // The counting variant is other code: one method counts.
            [Method::Lrt, Method::Rt, Method::Auto].map(|method| {
                renderer.set_fragment_counting(method == Method::Rt);
                let (image, stats) = renderer
                    .render(&ctx, &scene, method, FootprintShape::Hull)
                    .unwrap();
                (image.to_rgb8(), stats.fragments)
            })
        });
        for ((method, (flat, flat_fragments)), (lean, lean_fragments)) in
            [Method::Lrt, Method::Rt, Method::Auto]
                .iter()
                .zip(flat)
                .zip(lean)
        {
            let what = format!("{}, {}", builtin.name, method.name());
            assert!(flat == lean, "{what}: the lean varyings' image differs");
            assert_eq!(flat_fragments, lean_fragments, "{what}");
            let mismatch = compare(&reference, &lean, 2, 1);
            assert!(mismatch.fraction() <= 0.001, "{what}: {mismatch:?}");
        }
        println!("scene={}: lean = flat for LRT, RT and auto", builtin.name);
    }
    ctx.take_errors().unwrap();
}

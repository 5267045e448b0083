//! The scenes `validate` and `bench` run: the built-in scenes and models from Debian's
//! assimp-testmodels package, at chosen speeds, and scenes in motion (objects passing beside,
//! through and behind the camera, an object around it).

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use srt_physics::Frame;
use srt_scene::placement::{VIEW_DISTANCE, approach_velocity};
use srt_scene::sky::SkyImage;
use srt_scene::{
    Effects, Projection, Scene, SceneDescription, Stereo, SurfaceColour, View, builtin_scenes,
};

/// A named scene to render.
pub struct Case {
    /// Name for the report (built-in name or model file name).
    pub name: String,
    /// The scene.
    pub scene: Scene,
}

/// Path of a model in the assimp corpus, or an error saying how to install it.
///
/// # Errors
/// If the file is missing.
pub fn assimp_model(relative: &str) -> anyhow::Result<PathBuf> {
    let path = srt_scene::corpus::folder().join(relative);
    anyhow::ensure!(
        path.exists(),
        "{} is missing: {}",
        path.display(),
        srt_scene::corpus::HOW_TO_GET_IT
    );
    Ok(path)
}

/// A bare model placed in front of the observer, approaching at `speed`, as the paper's
/// comparisons place it (3.5 from the observer, the paper's colour), so that every recorded
/// figure measures the same picture; `srt render MODEL` now stands back until the seen model fits
/// and keeps its colours (`SceneDescription::for_model`).
///
/// # Errors
/// If the model cannot be loaded.
pub fn model_case(relative: &str, speed: f64) -> anyhow::Result<Case> {
    let path = assimp_model(relative)?;
    let placement = SceneDescription::for_model_at(&path, approach_velocity(speed), VIEW_DISTANCE);
    let (scene, _) = placement
        .build(Path::new("/"))
        .with_context(|| format!("cannot load {}", path.display()))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(Case { name, scene })
}

/// Every built-in scene as it is defined.
///
/// # Errors
/// If a built-in scene fails to build (a bug).
pub fn builtin_cases() -> anyhow::Result<Vec<Case>> {
    builtin_scenes()
        .iter()
        .map(|b| {
            let (scene, _) = b
                .build()
                .with_context(|| format!("built-in scene {}", b.name))?;
            Ok(Case {
                name: b.name.to_string(),
                scene,
            })
        })
        .collect()
}

/// `scene` with every moving object's speed set to `speed` (directions kept; objects at rest
/// stay at rest). Each object's offset is changed so that the apparent position of its S′ origin
/// stays where it was: the new worldline passes through the old emission event of the origin.
///
/// # Errors
/// If `speed` is not below 1.
pub fn with_speed(scene: &Scene, speed: f64) -> anyhow::Result<Scene> {
    let mut scene = scene.clone();
    let observer = scene.observer.event();
    for object in &mut scene.objects {
        let frame = object.frame;
        if let Some(direction) = frame.beta().try_normalize() {
            let emission = frame.to_observer(frame.emission_event(glam::DVec3::ZERO, observer));
            let beta = direction * speed;
            object.frame = Frame::new(beta, emission.position - beta * emission.ct)?;
        }
    }
    Ok(scene)
}

/// The 2CylinderEngine model (121 496 triangles) of the assimp corpus.
pub const ENGINE: &str = "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

/// `scene` seen at observation time `ct`, named `NAME@ct=CT`.
#[must_use]
pub fn at_time(name: &str, scene: &Scene, ct: f64) -> Case {
    let mut scene = scene.clone();
    scene.observer.time = ct;
    Case {
        name: format!("{name}@ct={ct}"),
        scene,
    }
}

/// `scene` with every object's path moved by `shift` (in S): the same motion, passing
/// elsewhere.
#[must_use]
pub fn shifted(scene: &Scene, shift: glam::DVec3) -> Scene {
    let mut scene = scene.clone();
    for object in &mut scene.objects {
        object.frame = Frame::new(object.frame.beta(), object.frame.offset() + shift)
            .expect("the velocity was valid already");
    }
    scene
}

/// The teaser's sweep of the issue that found whole-screen footprints: 12 frames from
/// ct = −20 to 20 (the spider passes the camera from frame 7 on).
#[must_use]
pub fn teaser_sweep_times() -> Vec<f64> {
    (0..12)
        .map(|k| -20.0 + 40.0 * f64::from(k) / 11.0)
        .collect()
}

/// The engine approaching at 0.9c passes through the camera at ct ≈ 0.39: a sweep from in
/// front of the camera, through it, to behind it.
#[must_use]
pub fn engine_sweep_times() -> Vec<f64> {
    (0..12).map(|k| -2.0 + 0.5 * f64::from(k)).collect()
}

/// The `flythrough`'s observer flying on for 11 time units (0.9c: about 25 of the world's
/// length units, past five pairs of columns and over the seams between ground slabs), 12 frames.
#[must_use]
pub fn flythrough_sweep_times() -> Vec<f64> {
    (0..12).map(f64::from).collect()
}

/// Sideways shift of the engine's path so that it passes beside and above the camera instead
/// of through it.
pub const ENGINE_BESIDE: glam::DVec3 = glam::DVec3::new(1.2, 0.4, 1.0);

/// A corridor: a long checkered box around the observer, moving at 0.5c along it, seen from
/// inside along its length; its walls' few triangles reach from beside the camera far ahead
/// and behind it (the camera inside an object of big triangles).
///
/// # Errors
/// If the scene does not build (a bug).
pub fn corridor_case() -> anyhow::Result<Case> {
    let text = r#"
        name = "corridor"
        [observer]
        position = [0.0, 0.0, 0.0]
        look_at = [0.1, 1.0, 0.05]
        fov_y_deg = 70.0
        [[object]]
        shape = { type = "cube", size = 1.0 }
        texture = { type = "checker", squares = 8 }
        scale = [2.0, 40.0, 1.6]
        beta = [0.0, -0.5, 0.0]
        offset = [0.3, 0.0, 0.1]
    "#;
    toml_case("corridor", text)
}

/// The case `name` of the scene description `text`.
fn toml_case(name: &str, text: &str) -> anyhow::Result<Case> {
    let (scene, _) = SceneDescription::from_toml_str(text, name)?.build(Path::new("/"))?;
    Ok(Case {
        name: name.to_owned(),
        scene,
    })
}

/// A checkered sphere of radius 5 around the observer, moving at 0.5c: the camera inside an
/// object.
///
/// # Errors
/// If the scene does not build (a bug).
pub fn enclosing_case() -> anyhow::Result<Case> {
    let text = r#"
        name = "enclosing"
        [observer]
        position = [0.0, 0.0, 0.0]
        look_at = [0.0, 1.0, 0.2]
        fov_y_deg = 70.0
        [[object]]
        shape = { type = "sphere", radius = 5.0, segments = 48 }
        texture = { type = "checker", squares = 12 }
        beta = [0.5, 0.0, 0.0]
        offset = [0.0, 0.0, 0.0]
    "#;
    toml_case("enclosing", text)
}

/// The picture size of [`pinhole_case`], as it was reported.
pub const PINHOLE_SIZE: (u32, u32) = (160, 120);

/// A sphere of 900 segments (radius 1.5) passing at β = (0.2, 0.95, 0), seen at ct = 10 from
/// (0, −10, 0.5) along (0, 1, −0.05) with a 40° field of view, at [`PINHOLE_SIZE`]: a closed
/// mesh whose shared edges are packed under every pixel, where a ray that slipped between two
/// f32 triangle tests (issue 68) showed the background (LRT) or the sphere's far side (the ray
/// tracer and `auto`) at column 86, row 58.
///
/// # Errors
/// If the scene does not build (a bug).
pub fn pinhole_case() -> anyhow::Result<Case> {
    let text = r#"
        name = "sphere-900"
        [observer]
        position = [0.0, -10.0, 0.5]
        direction = [0.0, 1.0, -0.05]
        fov_y_deg = 40.0
        ct = 10.0
        [[object]]
        shape = { type = "sphere", radius = 1.5, segments = 900 }
        beta = [0.2, 0.95, 0.0]
        offset = [0.0, 0.0, 0.0]
    "#;
    toml_case("sphere-900", text)
}

/// Scenes in motion for `validate`: the teaser while the spider passes the camera, the engine
/// passing through and beside the camera, the flythrough's observer further on (columns and
/// ground passing beside and under it), bodies spinning and thrusting in their frames
/// ([`moving_body_cases`]), the camera inside a sphere and inside a long box, and the wide
/// projections ([`projection_cases`]).
///
/// # Errors
/// If the engine model is missing.
pub fn fly_by_cases() -> anyhow::Result<Vec<Case>> {
    let teaser = builtin_cases()?
        .into_iter()
        .find(|c| c.name == "teaser")
        .context("the teaser is a built-in scene")?;
    let mut cases: Vec<Case> = teaser_sweep_times()[6..]
        .iter()
        .step_by(2)
        .map(|&ct| at_time("teaser", &teaser.scene, ct))
        .collect();
    let engine = model_case(ENGINE, 0.9)?;
    let beside = shifted(&engine.scene, ENGINE_BESIDE);
    for ct in [0.2, 0.5, 1.5] {
        cases.push(at_time("engine-through", &engine.scene, ct));
        cases.push(at_time("engine-beside", &beside, ct));
    }
    let flythrough = builtin_cases()?
        .into_iter()
        .find(|c| c.name == "flythrough")
        .context("flythrough is a built-in scene")?;
    for &ct in flythrough_sweep_times().iter().skip(3).step_by(4) {
        cases.push(at_time("flythrough", &flythrough.scene, ct));
    }
    cases.extend(moving_body_cases()?);
    cases.push(enclosing_case()?);
    cases.push(corridor_case()?);
    cases.extend(sky_cases()?);
    cases.extend(spectral_cases()?);
    cases.extend(projection_cases()?);
    Ok(cases)
}

/// The wide projections (docs/scene-format.md, "Projections"), drawn by the ray tracer (and
/// `auto`): the flythrough's whole sky as the full sphere (stars folded forward, columns
/// passing on both sides and behind) and through a 220° fisheye, the teaser after the spider
/// has passed the camera (seen behind the observer, at the picture's edges) as the full
/// sphere, the teaser's dome master (a 180° fisheye) and the rolling wheel (a body moving in
/// its frame) as the full sphere; and stereo pairs, top-bottom as the full sphere (the
/// flythrough) and side by side (the teaser).
///
/// # Errors
/// If a built-in scene does not build (a bug).
pub fn projection_cases() -> anyhow::Result<Vec<Case>> {
    let builtin = |name: &str| -> anyhow::Result<Scene> {
        let built = srt_scene::builtin::find_builtin(name)
            .with_context(|| format!("{name} is a built-in scene"))?;
        Ok(built.build()?.0)
    };
    let teaser_after = *teaser_sweep_times().last().context("the sweep has times")?;
    let teaser = at_time("teaser", &builtin("teaser")?, teaser_after).scene;
    let fisheye = |fov_deg| Projection::Fisheye { fov_deg };
    let cases = [
        (
            "flythrough",
            builtin("flythrough")?,
            Projection::Equirectangular,
        ),
        ("flythrough", builtin("flythrough")?, fisheye(220.0)),
        ("teaser-passed", teaser.clone(), Projection::Equirectangular),
        ("teaser", teaser, fisheye(180.0)),
        (
            "rolling-wheel",
            builtin("rolling-wheel")?,
            Projection::Equirectangular,
        ),
    ];
    let mut cases: Vec<Case> = cases
        .into_iter()
        .map(|(name, mut scene, projection)| {
            scene.observer.projection = projection;
            Case {
                name: format!("{name}-{projection}"),
                scene,
            }
        })
        .collect();
    // Stereo pairs: omni-directional top-bottom (the flythrough) and side by side (the teaser).
    let stereo = Some(Stereo {
        eye_separation: 1.0,
    });
    for (name, projection) in [
        ("flythrough", Projection::Equirectangular),
        ("teaser", Projection::Perspective),
    ] {
        let mut scene = builtin(name)?;
        scene.observer.projection = projection;
        scene.observer.stereo = stereo;
        cases.push(Case {
            name: format!("{name}-{projection}-stereo"),
            scene,
        });
    }
    Ok(cases)
}

/// Bodies moving within their frames, in motion past the camera: the rolling wheel passing
/// 3 units in front of it (`wheel-passing`, the camera moved up to the ground's edge) before,
/// while and after it crosses the line of sight, the rocket before its start, accelerating and
/// far off, and Bell's ships while the thread falls behind.
///
/// # Errors
/// If a built-in scene does not build (a bug).
pub fn moving_body_cases() -> anyhow::Result<Vec<Case>> {
    let builtin = |name: &str| {
        srt_scene::builtin::find_builtin(name).with_context(|| format!("{name} is built in"))
    };
    let wheel = builtin("rolling-wheel")?;
    let mut description = wheel.description();
    description.observer.position = [0.0, -3.0, 1.0];
    let (passing, _) = wheel.build_description(&description)?;
    // The axle is at x = 0 at t = −8, seen from 3 away at ct = −5.
    let mut cases: Vec<Case> = [-9.0, -6.0, -5.0, -3.0]
        .iter()
        .map(|&ct| at_time("wheel-passing", &passing, ct))
        .collect();
    let (rocket, _) = builtin("rocket")?.build()?;
    cases.extend([3.0, 10.0, 25.0].map(|ct| at_time("rocket", &rocket, ct)));
    let (bell, _) = builtin("bell")?.build()?;
    cases.extend([16.0, 24.0].map(|ct| at_time("bell", &bell, ct)));
    Ok(cases)
}

/// Spectral surface colour (docs/colour.md): the teaser; Fig. 7 (D_out up to 20, so the
/// visible light comes from far beyond the fitted 360–830 nm) with exposure 2 under the luminance
/// tone map and 0.5 under the searchlight tone map; and [`spectral_emitter_case`].
///
/// # Errors
/// If a scene does not build (a bug).
pub fn spectral_cases() -> anyhow::Result<Vec<Case>> {
    let builtins = builtin_cases()?;
    let builtin = |name: &str| {
        builtins
            .iter()
            .find(|c| c.name == name)
            .with_context(|| format!("{name} is a built-in scene"))
    };
    let spectral = |name: &str, effects: Effects, exposure: f64| -> anyhow::Result<Case> {
        let mut scene = builtin(name)?.scene.clone();
        scene.set_effects(effects);
        scene.colour = SurfaceColour::Spectral;
        scene.exposure = exposure;
        Ok(Case {
            name: format!("{name}-spectral-{}-x{exposure}", effects.name()),
            scene,
        })
    };
    Ok(vec![
        spectral("teaser", Effects::Doppler, 1.0)?,
        spectral("fig7", Effects::Doppler, 2.0)?,
        spectral("fig7", Effects::Searchlight, 0.5)?,
        spectral("shadows", Effects::Searchlight, 0.03)?,
        spectral_emitter_case()?,
    ])
}

/// Spectral colour with the per-object optics: a glowing sphere (3000 K) passing at 0.6c, a
/// red-and-blue checkered cube approaching at 0.7c (the visible light it sends back comes from
/// 0.9–2 µm, where its `infrared` reflectance 0.9 holds) and one receding at 0.7c (seen in its
/// ultraviolet, `ultraviolet` 0.1), exposure 2. Each offset puts the object's S′ origin where it
/// is seen at ct = 0: offset = A + β·|A − observer|.
///
/// # Errors
/// If the scene does not build (a bug).
pub fn spectral_emitter_case() -> anyhow::Result<Case> {
    let text = r#"
        name = "spectral-emitter"
        [observer]
        position = [0.0, -10.0, 1.0]
        look_at = [0.0, 0.0, 0.5]
        up = [0.0, 0.0, 1.0]
        fov_y_deg = 40.0
        [light]
        position = [4.0, -9.0, 6.0]
        temperature_k = 5000.0
        [render]
        colour = "spectral"
        exposure = 2.0
        [[object]]
        shape = { type = "sphere", radius = 1.0, segments = 32 }
        emission = { temperature_k = 3000, brightness = 1.0 }
        beta = [0.6, 0.0, 0.0]
        offset = [4.15, 0.0, 0.0]
        [[object]]
        shape = { type = "cube", size = 1.6, subdivisions = 2 }
        texture = { type = "checker", squares = 4, colors = [[0.9, 0.1, 0.1], [0.1, 0.2, 0.9]] }
        infrared = 0.9
        ultraviolet = 0.1
        beta = [0.0, -0.7, 0.0]
        offset = [2.0, -7.17, 0.0]
        [[object]]
        shape = { type = "cube", size = 1.6, subdivisions = 2 }
        texture = { type = "checker", squares = 4, colors = [[0.9, 0.1, 0.1], [0.1, 0.2, 0.9]] }
        infrared = 0.9
        ultraviolet = 0.1
        beta = [0.0, 0.7, 0.0]
        offset = [0.0, 12.1, 1.5]
    "#;
    let (scene, _) =
        SceneDescription::from_toml_str(text, "spectral-emitter")?.build(Path::new("/"))?;
    Ok(Case {
        name: "spectral-emitter".to_owned(),
        scene,
    })
}

/// The sky of the `flythrough` scene (observer at 0.9c through a star field): its stars with the
/// effect modes its file does not use (geometry only; the searchlight: stars ahead brightened by
/// D², behind dimmed), and with a sky image behind them ([`test_sky_image`]) in the paper's and
/// in spectral colour, and in the measured view (the sky at rest, contracted).
///
/// # Errors
/// If the built-in scene does not build (a bug).
pub fn sky_cases() -> anyhow::Result<Vec<Case>> {
    let flythrough = builtin_cases()?
        .into_iter()
        .find(|c| c.name == "flythrough")
        .context("flythrough is a built-in scene")?;
    let variant = |name: &str, effects: Effects, colour: SurfaceColour, image: bool| {
        let mut scene = flythrough.scene.clone();
        scene.set_effects(effects);
        scene.colour = colour;
        if image {
            scene.sky.image = Some(test_sky_image());
        }
        Case {
            name: format!("flythrough-{name}"),
            scene,
        }
    };
    let mut cases = vec![
        variant("geometry", Effects::Geometry, SurfaceColour::Paper, false),
        variant(
            "searchlight",
            Effects::Searchlight,
            SurfaceColour::Paper,
            false,
        ),
        variant("image", Effects::Doppler, SurfaceColour::Paper, true),
        variant(
            "image-spectral",
            Effects::Searchlight,
            SurfaceColour::Spectral,
            true,
        ),
    ];
    let mut measured = variant(
        "image-measured",
        Effects::Doppler,
        SurfaceColour::Paper,
        true,
    );
    measured.scene = View::Measured.apply(&measured.scene)?;
    cases.push(measured);
    Ok(cases)
}

/// A 256 × 128 equirectangular test sky: hues that turn with longitude, brighter towards the
/// zenith, a grey horizon band and a small bright sun (radiance 20) ahead of the flythrough's
/// observer (+y).
#[must_use]
pub fn test_sky_image() -> SkyImage {
    let (width, height) = (256u32, 128u32);
    let texels: Vec<[f32; 3]> = (0..height)
        .flat_map(|row| (0..width).map(move |column| (row, column)))
        .map(|(row, column)| {
            let longitude = (f64::from(column) + 0.5) / f64::from(width) * std::f64::consts::TAU;
            let latitude = 0.5 - (f64::from(row) + 0.5) / f64::from(height);
            let sun = (column as i64 - 192).abs() <= 2 && (row as i64 - 60).abs() <= 2;
            let colour = if sun {
                [20.0; 3]
            } else if latitude.abs() < 0.03 {
                [0.4; 3]
            } else {
                let level = 0.2 + latitude.max(0.0);
                [
                    level * (0.5 + 0.5 * longitude.sin()),
                    level * (0.5 + 0.5 * (2.0 * longitude).cos()),
                    level * 0.8,
                ]
            };
            colour.map(|c| c as f32)
        })
        .collect();
    SkyImage {
        width,
        height,
        texels: texels.into(),
        source: "test sky".to_owned(),
    }
}

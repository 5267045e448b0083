//! The scenes `validate` and `bench` run: the built-in scenes and models from Debian's
//! assimp-testmodels package, at chosen speeds.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use srt_physics::Frame;
use srt_scene::placement::approach_velocity;
use srt_scene::{Scene, SceneDescription, builtin_scenes};

/// Where Debian's assimp-testmodels package puts its models.
pub const ASSIMP_MODELS: &str = "/usr/share/assimp/models";

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
    let path = Path::new(ASSIMP_MODELS).join(relative);
    anyhow::ensure!(
        path.exists(),
        "{} is missing: install Debian's assimp-testmodels (apt-get install assimp-testmodels)",
        path.display()
    );
    Ok(path)
}

/// A bare model placed in front of the observer, approaching at `speed`.
///
/// # Errors
/// If the model cannot be loaded.
pub fn model_case(relative: &str, speed: f64) -> anyhow::Result<Case> {
    let path = assimp_model(relative)?;
    let (scene, _) = SceneDescription::for_model(&path, approach_velocity(speed))
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

//! Building the runtime scene from a description: procedural shapes, models and textures, and
//! their placement in each object's rest frame; and reading a scene file.

use std::path::Path;
use std::sync::Arc;

use glam::{DMat4, DVec3};
use srt_physics::Frame;

use super::error::{SceneError, SceneErrorKind, value_error};
use super::model::{
    ObjectDescription, ObserverDescription, SceneDescription, ShapeDescription, TextureDescription,
};
use super::{DEFAULT_LIGHT_TEMPERATURE_K, FIT_RADIUS};
use crate::assets;
use crate::mesh::{Material, MeshError, Part, Texture};
use crate::scene::{Light, Object, Observer, Scene, Shading};
use crate::{shapes, textures};

impl SceneDescription {
    /// Validates the description and builds the runtime scene: shapes are generated, models and
    /// textures loaded (paths relative to `base_dir`, or embedded for `builtin:` paths), objects
    /// placed in their rest frames. Returns the scene and the warnings met on the way (a missing
    /// texture image, problems the model importer could work around, a scene without objects…).
    ///
    /// The scene's name is `name`, or `"untitled"`.
    ///
    /// # Errors
    /// [`SceneError`] for every problem [`SceneDescription::validate`] finds, a model file that
    /// is missing or cannot be loaded (the message names it), or a placement that produces
    /// non-finite geometry.
    pub fn build(&self, base_dir: &Path) -> Result<(Scene, Vec<String>), SceneError> {
        let fail = |kind| SceneError::new(self.origin(), kind);
        self.check().map_err(fail)?;
        let mut warnings = Vec::new();
        let observer = self.observer.to_observer();
        let light = self.light.as_ref().map_or(
            Light {
                position: observer.position,
                temperature_k: DEFAULT_LIGHT_TEMPERATURE_K,
            },
            |l| Light {
                position: DVec3::from_array(l.position),
                temperature_k: l.temperature_k,
            },
        );
        let objects = self
            .objects
            .iter()
            .enumerate()
            .map(|(index, object)| object.build(index, base_dir, &mut warnings))
            .collect::<Result<Vec<_>, _>>()
            .map_err(fail)?;
        if objects.is_empty() {
            warnings.push("the scene has no objects".to_owned());
        }
        let render = &self.render;
        let scene = Scene {
            name: self.name.clone().unwrap_or_else(|| "untitled".to_owned()),
            objects,
            observer,
            light,
            shading: Shading {
                ambient: render.ambient,
                diffuse: render.diffuse,
                specular: render.specular,
                shininess: render.shininess,
            },
            effects: render.effects,
            tone_map: render
                .tone_map
                .unwrap_or_else(|| render.effects.default_tone_map()),
            background: DVec3::from_array(render.background),
        };
        Ok((scene, warnings))
    }
}

/// Reads, parses and builds the scene file at `path`; model and texture paths in it are relative
/// to its folder. Returns the scene (named after the file stem unless the file gives a name), the
/// description (for editing and saving) and the warnings.
///
/// # Errors
/// [`SceneError`] naming the file: it cannot be read, it is not a valid scene file (with line and
/// column), or [`SceneDescription::build`] fails.
pub fn load_scene_file(path: &Path) -> Result<(Scene, SceneDescription, Vec<String>), SceneError> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError::new(origin.clone(), SceneErrorKind::Io(e)))?;
    let description = SceneDescription::from_toml_str(&text, &origin)?;
    let base_dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let (mut scene, warnings) = description
        .build(base_dir)
        .map_err(|e| e.with_origin(origin.clone()))?;
    if description.name.is_none()
        && let Some(stem) = path.file_stem()
    {
        scene.name = stem.to_string_lossy().into_owned();
    }
    Ok((scene, description, warnings))
}

impl ObserverDescription {
    /// The runtime observer, with unit `direction` and `up`; only valid after `check`.
    fn to_observer(&self) -> Observer {
        let direction = self
            .view_direction()
            .unwrap_or(DVec3::NEG_Y)
            .normalize_or(DVec3::NEG_Y);
        Observer {
            position: DVec3::from_array(self.position),
            direction,
            up: DVec3::from_array(self.up).normalize_or(DVec3::Z),
            fov_y_deg: self.fov_y_deg,
            ct: self.ct,
        }
    }
}

impl ObjectDescription {
    /// Builds the runtime object; only valid after `check`.
    fn build(
        &self,
        index: usize,
        base_dir: &Path,
        warnings: &mut Vec<String>,
    ) -> Result<Object, SceneErrorKind> {
        let label = self.label(index);
        let frame = Frame::new(DVec3::from_array(self.beta), DVec3::from_array(self.offset))
            .map_err(|error| SceneErrorKind::Frame {
                object: label.clone(),
                error,
            })?;
        let mut parts = match &self.shape {
            ShapeDescription::Cube { size, subdivisions } => vec![Part {
                mesh: shapes::cube(*size, *subdivisions),
                material: Material {
                    name: "cube".to_owned(),
                    ..Material::default()
                },
            }],
            ShapeDescription::Sphere { radius, segments } => vec![Part {
                mesh: shapes::uv_sphere(*radius, *segments),
                material: Material {
                    name: "sphere".to_owned(),
                    ..Material::default()
                },
            }],
            ShapeDescription::Model { path } => {
                let resolved = assets::resolve(base_dir, path)
                    .map_err(|reason| value_error(format!("shape.path of {label}"), reason))?;
                let model =
                    assets::load_model(&resolved).map_err(|error| SceneErrorKind::Model {
                        object: label.clone(),
                        error,
                    })?;
                warnings.extend(model.warnings.into_iter().map(|w| format!("{label}: {w}")));
                model.parts
            }
        };
        if let Some(texture) = self.texture(base_dir, &label, warnings) {
            for part in &mut parts {
                part.material.texture = Some(Arc::clone(&texture));
            }
        }
        if let Some(color) = self.color {
            for part in &mut parts {
                for (channel, factor) in part.material.base_color.iter_mut().zip(color) {
                    #[expect(clippy::cast_possible_truncation, reason = "a colour in [0, 1]")]
                    let factor = factor as f32;
                    *channel *= factor;
                }
            }
        }
        let mut transform = self.placement();
        if self.fit {
            match fit_transform(&parts) {
                Some(fit) => transform *= fit,
                None => warnings.push(format!(
                    "{label}: fit = true ignored, the shape has no extent to scale"
                )),
            }
        }
        if transform != DMat4::IDENTITY {
            parts = parts
                .into_iter()
                .map(|Part { mesh, material }| {
                    let mesh = mesh.transformed(transform)?;
                    Ok(Part { mesh, material })
                })
                .collect::<Result<_, MeshError>>()
                .map_err(|error| SceneErrorKind::Mesh {
                    object: label.clone(),
                    error,
                })?;
        }
        Ok(Object {
            name: self.name.clone().unwrap_or(label),
            parts,
            frame,
            wireframe: self.wireframe,
        })
    }

    /// The texture this object asks for; `None` (with a warning) if its image cannot be loaded.
    fn texture(
        &self,
        base_dir: &Path,
        label: &str,
        warnings: &mut Vec<String>,
    ) -> Option<Arc<Texture>> {
        match self.texture.as_ref()? {
            TextureDescription::Checker { squares, colors } => Some(Arc::new(textures::checker(
                textures::checker_resolution(*squares),
                *squares,
                colors[0],
                colors[1],
            ))),
            TextureDescription::Image { path } => {
                let loaded = assets::resolve(base_dir, path).and_then(|r| assets::load_texture(&r));
                match loaded {
                    Ok(texture) => Some(Arc::new(texture)),
                    Err(error) => {
                        let fallback = if matches!(self.shape, ShapeDescription::Model { .. }) {
                            "the model's own materials are used"
                        } else {
                            "the base colour is used"
                        };
                        warnings.push(format!(
                            "{label}: texture \"{path}\" cannot be loaded ({error}); {fallback}"
                        ));
                        None
                    }
                }
            }
        }
    }
}

/// The transform that centres `parts` (their bounding box) at the origin and scales them to a
/// bounding-sphere radius of [`FIT_RADIUS`]; `None` if they have no extent.
#[must_use]
pub fn fit_transform(parts: &[Part]) -> Option<DMat4> {
    let (lo, hi) = parts
        .iter()
        .map(|p| p.mesh.bounds())
        .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))?;
    let centre = 0.5 * (lo + hi);
    let radius = parts
        .iter()
        .flat_map(|p| p.mesh.positions())
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max);
    (radius.is_finite() && radius > 0.0).then(|| {
        DMat4::from_scale(DVec3::splat(FIT_RADIUS / radius)) * DMat4::from_translation(-centre)
    })
}

//! Building the runtime scene from a description: procedural shapes, models and textures, and
//! their placement in each object's rest frame; and reading a scene file.
//!
//! Every scene, whatever its source (a scene file, a built-in scene, a bare model, the viewer's
//! edits), is built here, so the guards live here: one [`Budget`] per scene is charged with
//! every shape before it is generated and every model and texture while it loads, and every
//! object's placed geometry must lie within ±[`MAX_COORDINATE`] (checked on its bounding box
//! before the vertices are transformed). Identical textures are loaded once per scene.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DMat3, DMat4, DVec3};
use srt_physics::motion::{Motion, Thrust};
use srt_physics::{Event, FourVelocity, Frame, FrameError, MovingObserver, RelativeFrame};

use super::error::{SceneError, SceneErrorKind, value_error};
use super::model::{
    LightsDescription, ObjectDescription, ObserverDescription, SceneDescription, ShapeDescription,
    SkyDescription, TextureDescription,
};
use super::validate::{ValueName, invalid_velocity};
use super::{DEFAULT_LIGHT_TEMPERATURE_K, FIT_RADIUS};
use crate::assets;
use crate::input_file::{self, FileKind};
use crate::limits::{Budget, MAX_COORDINATE, OverBudget};
use crate::mesh::{Material, Mesh, MeshError, Part, Texture};
use crate::message::one_line;
use crate::scene::{
    Clock, Emission, Kinematics, Light, MovingLight, Object, Observer, Scene, Shading,
    SurfaceOptics,
};
use crate::sky::{self, Sky};
use crate::{shapes, textures};

/// What building one scene carries from object to object.
struct Builder<'a> {
    /// Where relative paths start.
    base_dir: &'a Path,
    /// What the scene has used so far.
    budget: Budget,
    /// Textures loaded so far, by what they were made from (failures keep their reason).
    textures: HashMap<TextureKey, Result<Arc<Texture>, String>>,
    /// Warnings so far.
    warnings: Vec<String>,
}

/// What a texture is made from: identical ones are made once per scene.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum TextureKey {
    /// A checkerboard: squares and the bits of its two colours.
    Checker(u32, [[u64; 3]; 2]),
    /// An image, by its resolved path (or `builtin:` name).
    Image(String),
    /// A flipbook: its frames' keys and the bits of its frame rate.
    Frames(Vec<String>, u64),
}

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
    /// is missing or cannot be loaded (the message names it), shapes and models that together
    /// exceed a scene's budget ([`crate::limits`]), or a placement that puts geometry beyond
    /// ±[`MAX_COORDINATE`].
    pub fn build(&self, base_dir: &Path) -> Result<(Scene, Vec<String>), SceneError> {
        self.build_within(base_dir, Budget::new())
    }

    /// [`SceneDescription::build`], charging the scene's shapes, models and textures to
    /// `budget`, which may already hold what the scene keeps from elsewhere (the viewer charges
    /// the parts an edit keeps with [`Budget::charge_held_parts`] and builds only new objects).
    ///
    /// # Errors
    /// As [`SceneDescription::build`].
    pub fn build_within(
        &self,
        base_dir: &Path,
        budget: Budget,
    ) -> Result<(Scene, Vec<String>), SceneError> {
        let fail = |kind| SceneError::new(self.origin(), kind);
        self.check().map_err(fail)?;
        let mut builder = Builder {
            base_dir,
            budget,
            textures: HashMap::new(),
            warnings: Vec::new(),
        };
        let Kinematics {
            observer,
            light,
            light_frames,
            frames,
            sky_beta,
            world,
        } = self.kinematics()?;
        let objects = self
            .objects
            .iter()
            .zip(&frames)
            .enumerate()
            .map(|(index, (object, relative))| object.build(index, relative, &mut builder))
            .collect::<Result<Vec<_>, _>>()
            .map_err(fail)?;
        let sky = match (&self.sky, sky_beta) {
            (Some(description), Some(beta)) => description
                .build(base_dir, beta, &mut builder.budget)
                .map_err(fail)?,
            _ => Sky::default(),
        };
        let mut warnings: Vec<String> = builder.warnings.iter().map(|w| one_line(w)).collect();
        if objects.is_empty() {
            warnings.push("the scene has no objects".to_owned());
        }
        let render = &self.render;
        let lights = (self.light.iter().flat_map(LightsDescription::moving))
            .zip(light_frames)
            .map(|(l, frame)| MovingLight {
                frame,
                temperature_k: l.temperature_k,
                strength: l.strength,
            })
            .collect();
        let scene = Scene {
            name: self.name.clone().unwrap_or_else(|| "untitled".to_owned()),
            objects,
            observer,
            light,
            lights,
            shadows: render.shadows,
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
            sky,
            colour: render.colour,
            exposure: render.exposure,
            cube_map_size: render.cube_map_size,
            world,
        };
        Ok((scene, warnings))
    }
}

impl SceneDescription {
    /// The observer's rest frame S relative to the world frame W: velocity `observer.beta`,
    /// origin event (`observer.ct`, `observer.position`), where S's clocks read `observer.ct`.
    /// A riding observer (`observer.thrust`) is drawn from its momentary rest frame when it
    /// looks: the inertial observer with the ship's velocity at the ship's event
    /// ([`SceneDescription::looking_observer`]).
    ///
    /// # Errors
    /// [`SceneErrorKind::Value`] naming `observer.beta` when it is not a velocity (|β| ≥ 1,
    /// not finite) or the observation event is not finite; `observer.thrust` as
    /// [`SceneDescription::looking_observer`] says.
    pub fn moving_observer(&self) -> Result<MovingObserver, SceneErrorKind> {
        let (looking, _) = self.looking_observer()?;
        inertial_observer(&looking)
    }

    /// The observation event in W: where the observer is when its own clock reads
    /// `observer.time` (`observer.ct` when absent), having moved along its worldline from
    /// (`observer.ct`, `observer.position`) — inertially, or riding its `thrust`.
    ///
    /// # Errors
    /// As [`SceneDescription::moving_observer`].
    pub fn observation_event(&self) -> Result<Event, SceneErrorKind> {
        let (observer, _) = self.looking_observer()?;
        let motion = inertial_observer(&observer)?;
        let time = observer.time.unwrap_or(observer.ct);
        let at_rest_in_s = Event::new(time, DVec3::from_array(observer.position));
        Ok(motion.observer_to_world().apply(at_rest_in_s))
    }

    /// The observer as the inertial observer it is when it looks, and for a riding observer
    /// the lamp's position in W then (`None`: the description's).
    ///
    /// Without a `thrust`, the description's observer. With one, the ship rests in its
    /// starting frame S₀ (velocity `observer.beta`, its clock reading S₀ time, at `position`)
    /// until its clock reads `start`, then follows the Born-rigid hyperbola along the thrust
    /// (srt_physics::motion::Thrust::origin_at_proper_time) and coasts: when its clock reads
    /// `observer.time` it is at the event E with velocity v in S₀. Aberration and the Doppler
    /// shift depend on nothing else, so the picture is the one an inertial observer with the
    /// composed velocity (collinear: rapidities add) sees at E; that observer is returned with
    /// E as its origin event. The lamp rides along Born-rigidly: its offset from the observer
    /// in the ship's rest frame stays the one it had in S₀.
    ///
    /// # Errors
    /// [`SceneErrorKind::Value`] naming `observer.thrust` for an unusable thrust (zero or not
    /// finite acceleration, negative duration), one across a moving observer's velocity (the
    /// camera would turn by a Thomas–Wigner rotation), or a lamp beyond the ship's Rindler
    /// horizon (1/α behind it, where no Born-rigid ship reaches); as
    /// [`SceneDescription::moving_observer`] for the velocity.
    pub fn looking_observer(&self) -> Result<(ObserverDescription, Option<DVec3>), SceneErrorKind> {
        let observer = &self.observer;
        let Some(ride) = observer.thrust else {
            return Ok((observer.clone(), None));
        };
        let thrust_error = |reason: String| value_error("observer.thrust", reason);
        let thrust = Thrust::new(
            DVec3::from_array(ride.proper_acceleration),
            ride.start,
            ride.duration,
        )
        .map_err(|e| thrust_error(e.to_string()))?;
        let start = inertial_observer(observer)?;
        let beta0 = DVec3::from_array(observer.beta);
        if beta0.cross(thrust.direction()).length() > 1e-9 * beta0.length() {
            return Err(thrust_error(format!(
                "must be along observer.beta {:?} when the observer moves (a thrust across it \
                 would turn the camera by a Thomas–Wigner rotation)",
                observer.beta
            )));
        }
        let position = DVec3::from_array(observer.position);
        let lamp_offset = self
            .light
            .as_ref()
            .and_then(LightsDescription::lamp)
            .map(|lamp| {
                let lamp = Event::new(observer.ct, DVec3::from_array(lamp.position));
                start.to_observer(lamp).position - position
            });
        if let Some(offset) = lamp_offset
            && offset.dot(thrust.direction()) <= thrust.horizon_height()
        {
            return Err(thrust_error(format!(
                "carries the lamp {:.6} behind the observer, beyond the ship's Rindler horizon at \
                 1/α = {:.6}: no Born-rigid ship reaches that far back",
                -offset.dot(thrust.direction()),
                -thrust.horizon_height()
            )));
        }
        let (ship, velocity) = thrust.origin_at_proper_time(observer.time.unwrap_or(observer.ct));
        let event = start
            .observer_to_world()
            .apply(Event::new(ship.ct, position + ship.position));
        // Eq. 3 on the four-velocities (velocity is along β₀): near c the composed β may round
        // to |β| = 1, which no frame can take; the ride says so rather than observer.beta.
        let beta = FourVelocity::from_beta(beta0)
            .compose(FourVelocity::from_beta(velocity))
            .beta();
        if !beta.is_finite() || beta.length() >= 1.0 {
            return Err(thrust_error(format!(
                "carries the observer so close to the speed of light by its clock's {} that its \
                 |β| rounds to 1 in f64 (give an earlier time, a smaller proper_acceleration or \
                 a duration)",
                observer.time.unwrap_or(observer.ct)
            )));
        }
        // The lamp's offset in the ship's frame is `lamp_offset`: in W, at E's time, its
        // component along β is longer by γ.
        let lamp = lamp_offset.map(|offset| {
            let along = beta.normalize_or_zero();
            let parallel = offset.dot(along);
            let gamma = 1.0 / (1.0 - beta.length_squared()).sqrt();
            event.position + offset + (parallel / gamma - parallel) * along
        });
        let looking = ObserverDescription {
            position: event.position.to_array(),
            beta: beta.to_array(),
            ct: event.ct,
            time: None,
            thrust: None,
            ..observer.clone()
        };
        Ok((looking, lamp))
    }

    /// Each object's frame relative to the observer and the Wigner rotation of its rest-frame
    /// geometry, in order ([`MovingObserver::relative_frame`]): what [`SceneDescription::build`]
    /// gives the objects, for editors that change velocities without rebuilding geometry.
    ///
    /// # Errors
    /// [`SceneError`] naming the observer or the object whose velocity or offset is not usable.
    pub fn relative_frames(&self) -> Result<Vec<RelativeFrame>, SceneError> {
        let fail = |kind| SceneError::new(self.origin(), kind);
        let observer = self.moving_observer().map_err(fail)?;
        self.objects
            .iter()
            .enumerate()
            .map(|(index, object)| {
                object.relative_frame(&observer).map_err(|error| {
                    fail(SceneErrorKind::Frame {
                        object: object.label(index),
                        error,
                    })
                })
            })
            .collect()
    }

    /// What of the built scene follows the observer's motion ([`Kinematics`]): the observer,
    /// the light resting beside it, every object's frame relative to it and the sky's velocity.
    /// [`SceneDescription::build`] places the scene with it; an editor that changes only the
    /// observer moves a built scene with [`Scene::follow`] instead of building it again.
    ///
    /// # Errors
    /// As [`SceneDescription::relative_frames`].
    pub fn kinematics(&self) -> Result<Kinematics, SceneError> {
        let fail = |kind| SceneError::new(self.origin(), kind);
        let (looking, riding_lamp) = self.looking_observer().map_err(fail)?;
        let motion = inertial_observer(&looking).map_err(fail)?;
        let observer = looking.to_observer();
        let light = match &self.light {
            None => Light {
                position: observer.position,
                temperature_k: DEFAULT_LIGHT_TEMPERATURE_K,
                strength: 1.0,
            },
            Some(lights) => lights.lamp().map_or(
                // A `[[light]]` list without a carried entry: no lamp.
                Light {
                    position: observer.position,
                    temperature_k: DEFAULT_LIGHT_TEMPERATURE_K,
                    strength: 0.0,
                },
                |l| Light {
                    // At rest relative to the observer, where W says it is at W's observation
                    // time.
                    position: motion
                        .to_observer(Event::new(
                            looking.ct,
                            riding_lamp.unwrap_or(DVec3::from_array(l.position)),
                        ))
                        .position,
                    temperature_k: l.temperature_k,
                    strength: l.strength,
                },
            ),
        };
        // A moving light rests at its frame's origin, at `position` in W at t = 0.
        let light_frames = self
            .light
            .iter()
            .flat_map(LightsDescription::moving)
            .enumerate()
            .map(|(index, l)| {
                Frame::new(DVec3::from_array(l.beta), DVec3::from_array(l.position))
                    .and_then(|world| motion.relative_frame(&world))
                    .map(|relative| relative.frame)
                    .map_err(|error| {
                        let key = format!("light[{index}].beta");
                        fail(invalid_velocity(
                            ValueName::Key(&key),
                            DVec3::from_array(l.beta),
                            &error,
                        ))
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        // The sky rests in W, which moves relative to the observer as an object at rest in W
        // does ([`MovingObserver::relative_frame`]: velocity −β_o, no rotation).
        let sky_beta = self
            .sky
            .as_ref()
            .map(|_| {
                Frame::new(DVec3::ZERO, DVec3::ZERO)
                    .and_then(|rest| motion.relative_frame(&rest))
                    .map(|world| world.frame.beta())
            })
            .transpose()
            .map_err(|error| {
                fail(invalid_velocity(
                    ValueName::Key("observer.beta"),
                    motion.beta(),
                    &error,
                ))
            })?;
        Ok(Kinematics {
            observer,
            light,
            light_frames,
            frames: self.relative_frames()?,
            sky_beta,
            world: motion.observer_to_world(),
        })
    }
}

impl SkyDescription {
    /// The stars, seen from the observer's frame: the built-in field's and the file's, resting
    /// in W, which moves with `beta` relative to the observer ([`Kinematics::sky_beta`]).
    fn build(
        &self,
        base_dir: &Path,
        beta: DVec3,
        budget: &mut Budget,
    ) -> Result<Sky, SceneErrorKind> {
        let on_disk = |key: &str, path: &str| match assets::resolve(base_dir, path) {
            Ok(assets::Resolved::File(file)) => Ok(file),
            Ok(assets::Resolved::Embedded { .. } | assets::Resolved::Memory { .. }) | Err(_) => {
                Err(value_error(
                    key,
                    format!("\"{path}\" is not a file on disk"),
                ))
            }
        };
        let image = self
            .image
            .as_ref()
            .map(|path| {
                sky::read_sky_image_cached(&on_disk("sky.image", path)?, budget)
                    .map_err(SceneErrorKind::Sky)
            })
            .transpose()?;
        let mut stars = sky::star_field(self.star_field);
        if let Some(path) = &self.stars {
            let file = on_disk("sky.stars", path)?;
            stars.extend(sky::read_star_file_cached(&file).map_err(SceneErrorKind::Sky)?);
            if stars.len() > sky::MAX_STARS {
                return Err(value_error(
                    "sky",
                    format!("has more than {} stars", sky::MAX_STARS),
                ));
            }
        }
        Ok(Sky {
            beta,
            stars,
            saturation_magnitude: self.saturation_magnitude,
            image,
            image_brightness: self.image_brightness,
            direction_map: glam::DMat3::IDENTITY,
        })
    }
}

impl ObjectDescription {
    /// The object's ultraviolet and infrared reflectances and emission.
    #[must_use]
    pub fn optics(&self) -> SurfaceOptics {
        SurfaceOptics {
            ultraviolet: self.ultraviolet,
            infrared: self.infrared,
            emission: self.emission.map(|e| Emission {
                temperature_k: e.temperature_k,
                brightness: e.brightness,
                blink: e.blink,
            }),
        }
    }

    /// The object's frame relative to `observer` (its `beta` and `offset` are given in W).
    fn relative_frame(&self, observer: &MovingObserver) -> Result<RelativeFrame, FrameError> {
        let world = Frame::new(DVec3::from_array(self.beta), DVec3::from_array(self.offset))?;
        observer.relative_frame(&world)
    }
}

/// Reads and parses the scene file at `path`, without building it (nothing else is read).
///
/// # Errors
/// [`SceneError`] naming the file: it cannot be read, or it is not a valid scene file (with line
/// and column).
pub fn read_scene_file(path: &Path) -> Result<SceneDescription, SceneError> {
    let origin = path.display().to_string();
    let text = input_file::read_text(path, FileKind::Scene)
        .map_err(|e| SceneError::new(origin.clone(), SceneErrorKind::Io(e)))?;
    SceneDescription::from_toml_str(&text, &origin)
}

/// The folder that relative paths in the scene file at `path` start from: its parent, or `.`
/// for a bare file name.
#[must_use]
pub fn scene_file_folder(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Reads, parses and builds the scene file at `path`; model and texture paths in it are relative
/// to its folder. Returns the scene (named after the file stem unless the file gives a name), the
/// description (for editing and saving) and the warnings.
///
/// # Errors
/// [`SceneError`] naming the file: as [`read_scene_file`], or [`SceneDescription::build`] fails.
pub fn load_scene_file(path: &Path) -> Result<(Scene, SceneDescription, Vec<String>), SceneError> {
    build_scene_file(read_scene_file(path)?, path)
}

/// Builds `description`, read from the scene file at `path` (and perhaps changed since), as
/// [`load_scene_file`] does: paths relative to the file's folder, errors naming the file, the
/// scene named after the file stem unless the description gives a name.
///
/// # Errors
/// [`SceneError`] naming the file when [`SceneDescription::build`] fails.
pub fn build_scene_file(
    description: SceneDescription,
    path: &Path,
) -> Result<(Scene, SceneDescription, Vec<String>), SceneError> {
    let (mut scene, warnings) = description
        .build(&scene_file_folder(path))
        .map_err(|e| e.with_origin(path.display().to_string()))?;
    if description.name.is_none()
        && let Some(stem) = path.file_stem()
    {
        scene.name = stem.to_string_lossy().into_owned();
    }
    Ok((scene, description, warnings))
}

/// The rest frame of the inertial `observer`: velocity `beta`, origin event (`ct`,
/// `position`), where its clocks read `ct`.
fn inertial_observer(observer: &ObserverDescription) -> Result<MovingObserver, SceneErrorKind> {
    let event = Event::new(observer.ct, DVec3::from_array(observer.position));
    let beta = DVec3::from_array(observer.beta);
    MovingObserver::new(beta, event)
        .map_err(|error| invalid_velocity(ValueName::Key("observer.beta"), beta, &error))
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
            time: self.time.unwrap_or(self.ct),
            projection: self.projection.unwrap_or_default(),
            stereo: self.stereo,
        }
    }
}

impl ObjectDescription {
    /// Builds the runtime object as `observer` describes it (its frame relative to the
    /// observer, its rest-frame geometry turned by the Wigner rotation), charging it to the
    /// scene's budget; only valid after `check`.
    fn build(
        &self,
        index: usize,
        relative: &RelativeFrame,
        builder: &mut Builder<'_>,
    ) -> Result<Object, SceneErrorKind> {
        let label = self.label(index);
        let too_large = |key: &str, error: OverBudget| {
            value_error(
                format!("{key} of {label}"),
                format!("makes the scene too large: {error}"),
            )
        };
        let mut parts = match &self.shape {
            ShapeDescription::Cube { size, subdivisions } => {
                builder
                    .budget
                    .charge_mesh(
                        shapes::cube_triangle_count(*subdivisions),
                        shapes::cube_vertex_count(*subdivisions),
                    )
                    .and_then(|()| builder.budget.charge_parts(1))
                    .map_err(|e| too_large("shape.subdivisions", e))?;
                vec![shape_part("cube", shapes::cube(*size, *subdivisions))]
            }
            ShapeDescription::Sphere { radius, segments } => {
                builder
                    .budget
                    .charge_mesh(
                        shapes::uv_sphere_triangle_count(*segments),
                        shapes::uv_sphere_vertex_count(*segments),
                    )
                    .and_then(|()| builder.budget.charge_parts(1))
                    .map_err(|e| too_large("shape.segments", e))?;
                vec![shape_part("sphere", shapes::uv_sphere(*radius, *segments))]
            }
            ShapeDescription::Model { path } => {
                let resolved = assets::resolve(builder.base_dir, path)
                    .map_err(|reason| value_error(format!("shape.path of {label}"), reason))?;
                let model =
                    assets::load_model(&resolved, &mut builder.budget).map_err(|error| {
                        SceneErrorKind::Model {
                            object: label.clone(),
                            error,
                        }
                    })?;
                let warnings = model.warnings.into_iter().map(|w| format!("{label}: {w}"));
                builder.warnings.extend(warnings);
                model.parts
            }
        };
        if let Some(texture) = self.texture(&label, builder) {
            for part in &mut parts {
                part.material.texture = Some(Arc::clone(&texture));
            }
        }
        if self.clock().is_some() {
            // The clock face replaces every texture, a model's own too.
            for part in &mut parts {
                part.material.texture = None;
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
                None => builder.warnings.push(format!(
                    "{label}: fit = true ignored, the shape has no usable extent to scale"
                )),
            }
        }
        if relative.rotation != DMat3::IDENTITY {
            transform = DMat4::from_mat3(relative.rotation) * transform;
        }
        let reach = placed_reach(&parts, transform);
        // `reach` is never NaN (`placed_reach` maps non-finite corners to infinity).
        if reach > MAX_COORDINATE {
            return Err(SceneErrorKind::OutOfBounds {
                object: label,
                reach,
            });
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
        let motion = self.placed_motion(&label, relative.rotation, &parts)?;
        Ok(Object {
            name: self.name.clone().unwrap_or(label),
            parts,
            frame: relative.frame,
            rest_time_shift: relative.rest_time_shift,
            wireframe: self.wireframe,
            optics: self.optics(),
            clock: self.clock(),
            motion,
        })
    }

    /// The object's motion (`spin` or `thrust`) in its rest coordinates turned by `rotation`
    /// (the Wigner rotation its `parts` are already turned by), checked against the parts: a
    /// spinning point must stay below the speed of light (ω·ρ < 1), a thrusting one above the
    /// Rindler horizon (1 + α·ξ > 0).
    ///
    /// # Errors
    /// [`SceneErrorKind::Value`] naming the object and the first point that breaks the rule.
    pub fn placed_motion(
        &self,
        label: &str,
        rotation: DMat3,
        parts: &[Part],
    ) -> Result<Motion, SceneErrorKind> {
        let field = |name: &str| format!("{name} of {label}");
        let motion = self
            .motion()
            .map_err(|(key, error)| value_error(field(key), error))?
            .rotated(rotation);
        let points = || parts.iter().flat_map(|part| part.mesh.positions().iter());
        match motion {
            Motion::Rest => {}
            Motion::Spin(spin) => {
                if let Some(point) = points().find(|&&p| spin.radius_of(p) >= spin.max_radius()) {
                    return Err(value_error(
                        field("spin.rate"),
                        format!(
                            "makes the point at {point} move at {:.4}c (ω · its distance {:.4} \
                             from the axis); every point must stay below the speed of light",
                            spin.rate().abs() * spin.radius_of(*point),
                            spin.radius_of(*point)
                        ),
                    ));
                }
            }
            Motion::Thrust(thrust) => {
                if let Some(point) =
                    points().find(|&&p| p.dot(thrust.direction()) <= thrust.horizon_height())
                {
                    return Err(value_error(
                        field("thrust.proper_acceleration"),
                        format!(
                            "puts the point at {point} beyond the Rindler horizon \
                             ({:.4} behind the origin along the acceleration); Born-rigid \
                             acceleration needs 1 + a·ξ > 0 for every point",
                            -thrust.horizon_height()
                        ),
                    ));
                }
            }
        }
        Ok(motion)
    }

    /// The clock face this object's `texture` asks for, if it asks for one.
    #[must_use]
    pub fn clock(&self) -> Option<Clock> {
        match self.texture {
            Some(TextureDescription::Clock {
                rate,
                offset,
                dial,
                colors: [face, ink],
            }) => Some(Clock {
                rate,
                offset,
                dial,
                face,
                ink,
            }),
            _ => None,
        }
    }

    /// The texture this object asks for, made once per scene; `None` (with a warning saying
    /// why) if it cannot be loaded or does not fit in the scene's texel budget: a texture
    /// problem never fails a scene, the colours it would have given are replaced.
    fn texture(&self, label: &str, builder: &mut Builder<'_>) -> Option<Arc<Texture>> {
        let description = self.texture.as_ref()?;
        let base_dir = builder.base_dir;
        let key = TextureKey::of(description, base_dir)?;
        let budget = &mut builder.budget;
        let loaded = builder
            .textures
            .entry(key)
            .or_insert_with(|| make_texture(description, base_dir, budget))
            .clone();
        match loaded {
            Ok(texture) => Some(texture),
            Err(error) => {
                let what = match description {
                    TextureDescription::Image { path } => format!("texture \"{path}\""),
                    TextureDescription::Checker { .. } => "the checker texture".to_owned(),
                    TextureDescription::Frames { files, .. } => {
                        format!("the flipbook of {} frames", files.len())
                    }
                    TextureDescription::Clock { .. } => "the clock".to_owned(),
                };
                let fallback = if matches!(self.shape, ShapeDescription::Model { .. }) {
                    "the model's own materials are used"
                } else {
                    "the base colour is used"
                };
                builder.warnings.push(format!(
                    "{label}: {what} cannot be loaded ({error}); {fallback}"
                ));
                None
            }
        }
    }
}

impl TextureKey {
    /// The key of `description`, with image paths resolved from `base_dir`; `None` for a clock,
    /// which is drawn per pixel and has no texels.
    fn of(description: &TextureDescription, base_dir: &Path) -> Option<Self> {
        match description {
            TextureDescription::Checker { squares, colors } => {
                Some(Self::Checker(*squares, colors.map(|c| c.map(f64::to_bits))))
            }
            TextureDescription::Image { path } => Some(Self::Image(image_key(path, base_dir))),
            TextureDescription::Frames { files, fps } => Some(Self::Frames(
                files.iter().map(|f| image_key(f, base_dir)).collect(),
                fps.to_bits(),
            )),
            TextureDescription::Clock { .. } => None,
        }
    }
}

/// Loads the image file (or `builtin:` image) at `path`, charging its texels to `budget`.
fn load_image(path: &str, base_dir: &Path, budget: &mut Budget) -> Result<Texture, String> {
    assets::resolve(base_dir, path).and_then(|resolved| assets::load_texture(&resolved, budget))
}

/// The key of the image at `path`: its resolved path (or `builtin:` name).
fn image_key(path: &str, base_dir: &Path) -> String {
    assets::resolve(base_dir, path).map_or_else(|_| path.to_owned(), |resolved| resolved.label())
}

/// Makes the texture `description` asks for, charging its texels to `budget`.
fn make_texture(
    description: &TextureDescription,
    base_dir: &Path,
    budget: &mut Budget,
) -> Result<Arc<Texture>, String> {
    match description {
        TextureDescription::Checker { squares, colors } => {
            let size = textures::checker_resolution(*squares);
            budget
                .charge_texels(size, size)
                .map_err(|e| format!("it is too large: {e}"))?;
            Ok(Arc::new(textures::checker(
                size, *squares, colors[0], colors[1],
            )))
        }
        TextureDescription::Image { path } => load_image(path, base_dir, budget).map(Arc::new),
        TextureDescription::Frames { files, fps } => {
            let frames = files
                .iter()
                .map(|path| load_image(path, base_dir, budget).map_err(|e| format!("{path}: {e}")))
                .collect::<Result<Vec<_>, _>>()?;
            let source = format!("flipbook of {} frames ({} …)", files.len(), files[0]);
            textures::flipbook(&frames, *fps, source).map(Arc::new)
        }
        TextureDescription::Clock { .. } => {
            Err("a clock is drawn per pixel, not loaded".to_owned())
        }
    }
}

/// A part of a procedural shape, its material named `name`.
fn shape_part(name: &str, mesh: Mesh) -> Part {
    Part {
        mesh,
        material: Material {
            name: name.to_owned(),
            ..Material::default()
        },
    }
}

/// The largest absolute coordinate of `parts` once `transform` is applied, computed on the
/// corners of each part's bounding box (an affine map takes the box to a parallelepiped whose
/// extreme coordinates are at its corners); infinite if any is not finite.
fn placed_reach(parts: &[Part], transform: DMat4) -> f64 {
    let mut reach = 0.0_f64;
    for part in parts {
        let (lo, hi) = part.mesh.bounds();
        for corner in 0..8 {
            let pick = |bit: usize, low: f64, high: f64| if corner & bit == 0 { low } else { high };
            let point = DVec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            );
            let placed = transform.transform_point3(point);
            if !placed.is_finite() {
                return f64::INFINITY;
            }
            reach = reach.max(placed.abs().max_element());
        }
    }
    reach
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

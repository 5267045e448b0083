//! The one rule of an edit: judge the edited description by the scene file's rules, then
//! follow it with the built scene (the observer alone) or build only the objects whose geometry
//! is new, keeping every other object's parts.

use srt_physics::RelativeFrame;
use srt_physics::motion::Motion;

use super::{EditError, Editor, Geometry, PartsPlan};
use crate::limits::Budget;
use crate::{
    Object, ObjectDescription, ObserverDescription, Part, Scene, SceneDescription, SceneError,
    SceneErrorKind,
};

impl Editor {
    /// Applies `change` to a copy of the description; if the scene file's rules accept the
    /// result, makes it the description and brings the runtime scene in step (building only
    /// objects whose geometry is new); otherwise nothing changes. Returns the warnings met
    /// building new objects.
    pub(super) fn apply(
        &mut self,
        change: impl FnOnce(&mut SceneDescription) -> Result<(), EditError>,
    ) -> Result<Vec<String>, EditError> {
        let mut description = self.description.clone();
        change(&mut description)?;
        self.set_description(description)
    }

    /// Makes `description` the scene's description if the scene file's rules accept it, and
    /// brings the runtime scene in step by the one rule: when only the observer changed and
    /// every object's geometry keeps its Wigner rotation (always for an observer at rest in W,
    /// and while the observer's velocity stays), the runtime scene follows the observer
    /// ([`Scene::follow`]) and nothing is built; otherwise the runtime scene's settings and the
    /// objects whose geometry is new are built, the others keep their parts. Otherwise nothing
    /// changes. Returns the warnings met building new objects.
    ///
    /// # Errors
    /// [`EditError::Scene`] with the scene file's message for a description its rules refuse,
    /// or one whose new objects do not load; the scene is then unchanged.
    pub fn set_description(
        &mut self,
        description: SceneDescription,
    ) -> Result<Vec<String>, EditError> {
        description.validate()?;
        if self.followed(&description)? {
            self.description = description;
            return Ok(Vec::new());
        }
        let frames = description.relative_frames()?;
        let geometry = geometries(&description, &frames);
        let plan = self.plan(&geometry);
        let (built, warnings) = self.build_new_objects(&description, &plan)?;
        self.builds += 1;
        self.commit(description, &plan, built, &frames, geometry);
        Ok(warnings)
    }

    /// Whether the runtime scene could follow `description`, validated, without building
    /// anything (only the observer changed, and no object's Wigner rotation), and if so has
    /// followed it.
    fn followed(&mut self, description: &SceneDescription) -> Result<bool, EditError> {
        let only_the_observer = SceneDescription {
            observer: self.description.observer.clone(),
            ..description.clone()
        } == self.description;
        if !only_the_observer {
            return Ok(false);
        }
        let kinematics = description.kinematics()?;
        let same_geometry = kinematics.frames.len() == self.built_from.len()
            && (kinematics.frames.iter())
                .zip(&self.built_from)
                .all(|(frame, built)| frame.rotation == built.rotation);
        if same_geometry {
            self.scene.follow(&kinematics);
        }
        Ok(same_geometry)
    }

    /// Applies `change` to the observer (camera, time, velocity): the edit made every frame
    /// while time runs or the observer flies, which builds nothing unless the observer's new
    /// velocity turns an object ([`Editor::set_description`]).
    pub(super) fn move_observer(
        &mut self,
        change: impl FnOnce(&mut ObserverDescription),
    ) -> Result<(), EditError> {
        self.edit(|description| {
            change(&mut description.observer);
            Ok(())
        })
    }

    /// Shows `other`'s scene in place of this one, as opening another scene does: the
    /// structure version moves on unless `other`'s scene has the same structure
    /// ([`Scene::same_structure`]), so a renderer keeps its upload across scenes that share it.
    pub fn replace_with(&mut self, mut other: Self) {
        let same = self.scene.same_structure(&other.scene);
        other.structure_version = self.structure_version + u64::from(!same);
        other.builds += self.builds + 1;
        *self = other;
    }

    /// [`Editor::apply`] for edits that add no object (and so meet no warning).
    pub(super) fn edit(
        &mut self,
        change: impl FnOnce(&mut SceneDescription) -> Result<(), EditError>,
    ) -> Result<(), EditError> {
        self.apply(change).map(|_no_warnings| ())
    }

    /// Which runtime object's parts each object of an edited description, of `geometry`,
    /// keeps: the first one not yet taken with the same geometry.
    pub(super) fn plan(&self, geometry: &[Geometry]) -> PartsPlan {
        let mut taken = vec![false; self.built_from.len()];
        geometry
            .iter()
            .map(|geometry| {
                let found =
                    (0..taken.len()).find(|&j| !taken[j] && self.built_from[j] == *geometry);
                if let Some(j) = found {
                    taken[j] = true;
                }
                found
            })
            .collect()
    }

    /// Builds the scene of `description` with only the objects `plan` does not find parts for:
    /// its observer, light and render settings, and those objects' parts, charged to one scene
    /// budget together with the parts the plan keeps. Warnings are those of the new objects.
    pub(super) fn build_new_objects(
        &self,
        description: &SceneDescription,
        plan: &PartsPlan,
    ) -> Result<(Scene, Vec<String>), SceneError> {
        let new_objects: Vec<ObjectDescription> = description
            .objects
            .iter()
            .zip(plan)
            .filter(|(_, reused)| reused.is_none())
            .map(|(object, _)| object.clone())
            .collect();
        let nothing_new = new_objects.is_empty();
        let probe = SceneDescription {
            objects: new_objects,
            ..description.clone()
        };
        let mut budget = Budget::new();
        let kept_parts = plan
            .iter()
            .flatten()
            .flat_map(|&index| &self.scene.objects[index].parts);
        budget.charge_held_parts(kept_parts).map_err(|error| {
            let kind = SceneErrorKind::Value {
                field: "the objects this edit keeps".to_owned(),
                reason: format!("make the scene too large: {error}"),
            };
            SceneError::new(description.origin(), kind)
        })?;
        let (built, warnings) = probe.build_within(&self.base_dir, budget)?;
        // Without objects the only warning is that the probe has none, which is not news.
        Ok((built, if nothing_new { Vec::new() } else { warnings }))
    }

    /// Makes `description` the scene: the settings come from `built`, each object's parts from
    /// the runtime object `plan` names or, in order, from `built`'s objects.
    pub(super) fn commit(
        &mut self,
        description: SceneDescription,
        plan: &PartsPlan,
        built: Scene,
        frames: &[RelativeFrame],
        geometry: Vec<Geometry>,
    ) {
        let old_count = self.scene.objects.len();
        let old_structure = self.scene.structure_beside_parts();
        // An object's parts and motion (both follow from its geometry, spin and thrust included).
        let mut kept: Vec<Option<(Vec<Part>, Motion)>> = std::mem::take(&mut self.scene.objects)
            .into_iter()
            .map(|object| Some((object.parts, object.motion)))
            .collect();
        let mut new_parts = built
            .objects
            .into_iter()
            .map(|object| (object.parts, object.motion));
        let objects = description
            .objects
            .iter()
            .zip(plan)
            .zip(frames)
            .enumerate()
            .map(|(index, ((object, reused), frame))| {
                let (parts, motion) = match reused {
                    Some(j) => kept[*j].take(),
                    None => new_parts.next(),
                }
                .expect("the plan takes each runtime object once and builds the rest");
                Object {
                    name: runtime_name(object, index),
                    parts,
                    frame: frame.frame,
                    rest_time_shift: frame.rest_time_shift,
                    wireframe: object.wireframe,
                    optics: object.optics(),
                    clock: object.clock(),
                    motion,
                }
            })
            .collect();
        let parts_in_place = plan.len() == old_count
            && plan
                .iter()
                .enumerate()
                .all(|(i, reused)| *reused == Some(i));
        let scene = Scene { objects, ..built };
        if !(parts_in_place && old_structure == scene.structure_beside_parts()) {
            self.structure_version += 1;
        }
        self.built_from = geometry;
        self.scene = scene;
        self.description = description;
    }
}

/// The [`Geometry`] of `object`, whose frame relative to the observer is `frame`.
pub(super) fn geometry_of(object: &ObjectDescription, frame: &RelativeFrame) -> Geometry {
    Geometry {
        object: ObjectDescription {
            name: None,
            wireframe: None,
            beta: [0.0; 3],
            offset: [0.0; 3],
            ..object.clone()
        },
        rotation: frame.rotation,
    }
}

/// The [`Geometry`] of every object of `description`, whose relative frames are `frames`.
pub(super) fn geometries(
    description: &SceneDescription,
    frames: &[RelativeFrame],
) -> Vec<Geometry> {
    description
        .objects
        .iter()
        .zip(frames)
        .map(|(object, frame)| geometry_of(object, frame))
        .collect()
}

/// The name the runtime object of `object`, number `index` (from 0), has: its own, or
/// `object N` as [`SceneDescription::build`] names it.
pub(super) fn runtime_name(object: &ObjectDescription, index: usize) -> String {
    object.name.clone().unwrap_or_else(|| object.label(index))
}

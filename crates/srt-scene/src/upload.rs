//! When a GPU renderer uploads a scene again: the one rule every front end keeps its upload by
//! (the viewer's panes, the web page's canvas, the `srt` library's kept engine behind Python's
//! `srt.Renderer`). What a renderer uploads — meshes, materials, textures, the sky — is decided
//! by the [`Editor`](crate::Editor)'s structure version
//! ([`Editor::structure_version`](crate::Editor::structure_version)), which moves on exactly when
//! [`Scene::same_structure`] would refuse; times, velocities, the camera and effects are written
//! with each frame and never upload. The measured view's meshes are contracted along each
//! object's velocity ([`View::Measured`]), so its key holds those velocities too. A new size
//! resizes a renderer's targets and uploads nothing.

use crate::{Scene, View};

/// What a renderer's upload holds: the editor's scene at a structure version and, for the
/// measured view, the velocities its meshes were contracted with (their bits).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UploadKey {
    /// The editor's structure version the meshes were taken at.
    structure_version: u64,
    /// Each object's velocity, for the measured view's contracted meshes.
    contracted_for: Option<Vec<[u64; 3]>>,
}

impl UploadKey {
    /// The key of `view` of `scene`, the editor's scene at structure version
    /// `structure_version`: the seen and Newtonian views draw the scene's own meshes, the
    /// measured view meshes contracted along each object's velocity (which the key therefore
    /// includes).
    #[must_use]
    pub fn new(view: View, scene: &Scene, structure_version: u64) -> Self {
        let contracted_for = (view == View::Measured).then(|| {
            scene
                .objects
                .iter()
                .map(|o| o.frame.beta().to_array().map(f64::to_bits))
                .collect()
        });
        Self {
            structure_version,
            contracted_for,
        }
    }

    /// Whether a renderer holding this key's upload must upload again to draw `next`'s.
    #[must_use]
    pub fn needs_upload(&self, next: &Self) -> bool {
        self != next
    }

    /// The editor's structure version the upload was taken at.
    #[must_use]
    pub const fn structure_version(&self) -> u64 {
        self.structure_version
    }

    /// Whether the upload holds meshes contracted for the measured view.
    #[must_use]
    pub const fn is_contracted(&self) -> bool {
        self.contracted_for.is_some()
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::Editor;

    /// The key of `view` of the editor's scene now.
    fn key(view: View, editor: &Editor) -> UploadKey {
        UploadKey::new(view, editor.scene(), editor.structure_version())
    }

    #[test]
    fn a_scene_is_uploaded_again_only_when_its_structure_or_contracted_meshes_change() {
        let (mut editor, _) = Editor::open("fig7").unwrap();
        let (seen, measured) = (key(View::Seen, &editor), key(View::Measured, &editor));
        assert!(!seen.needs_upload(&key(View::Newtonian, &editor)));
        assert!(seen.needs_upload(&measured) && !seen.is_contracted() && measured.is_contracted());
        // Time and the observer's camera are written with each frame.
        editor.set_time(editor.scene().observer.time + 1.0).unwrap();
        assert!(!seen.needs_upload(&key(View::Seen, &editor)));
        assert!(!measured.needs_upload(&key(View::Measured, &editor)));
        // A velocity keeps the seen view's upload; the measured view's meshes are contracted
        // along it.
        editor.set_velocity(0, 0.5, DVec3::Y, false).unwrap();
        assert_eq!(editor.structure_version(), seen.structure_version());
        assert!(!seen.needs_upload(&key(View::Seen, &editor)));
        assert!(measured.needs_upload(&key(View::Measured, &editor)));
        // One object fewer: every view uploads again.
        editor.remove_object(0).unwrap();
        assert!(seen.needs_upload(&key(View::Seen, &editor)));
        assert!(key(View::Newtonian, &editor).structure_version() > seen.structure_version());
    }
}

//! What `srt view` opens and the panel's limits; the scene state itself, and every edit the
//! panel makes to it, is srt-scene's [`Editor`] (the one scene state under every front end).

use srt_scene::{EditError, Editor};

/// The scene opened when `srt view` is given no argument.
pub const DEFAULT_SCENE: &str = "teaser";

/// The fastest speed the speed slider offers, as a fraction of c.
pub const MAX_SLIDER_SPEED: f64 = 0.999;

/// Opens what `srt view` was given: none opens [`DEFAULT_SCENE`]; the first argument is a
/// built-in scene name, a scene file (`.toml`) or a model (placed as `srt render` places it);
/// every further argument adds its objects (a model, or the objects of a scene) to the first
/// scene. Returns the editor and the warnings met loading.
///
/// # Errors
/// An unknown name, a missing or unsupported file, or a scene or model that does not load.
pub fn open_arguments(arguments: &[String]) -> Result<(Editor, Vec<String>), EditError> {
    let (first, rest) = match arguments.split_first() {
        Some((first, rest)) => (first.as_str(), rest),
        None => (DEFAULT_SCENE, &[][..]),
    };
    let (mut editor, mut warnings) = Editor::open(first)?;
    for argument in rest {
        warnings.extend(editor.add_argument(argument)?);
    }
    Ok((editor, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_argument_opens_the_teaser_and_further_ones_add_objects() {
        let (editor, _) = open_arguments(&[]).unwrap();
        assert_eq!(editor.scene().name, DEFAULT_SCENE);
        let arguments = ["fig7".to_owned(), "fig7".to_owned()];
        let (editor, _) = open_arguments(&arguments).unwrap();
        assert_eq!(editor.object_count(), 2);
        assert_ne!(editor.objects()[0].name, editor.objects()[1].name);
    }
}

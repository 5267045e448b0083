//! What the user documents list against what the program has: docs/python.md's list of the
//! built-in scenes is every one of them, in `srt scenes` order.

use std::path::Path;

/// The names in back-quotes of the paragraph that follows `marker` in `text` (up to its blank
/// line).
fn quoted_names_after(text: &str, marker: &str) -> Vec<String> {
    let start = text.find(marker).expect("the marker is in the document") + marker.len();
    let paragraph = text[start..].split("\n\n").next().unwrap_or_default();
    let paragraph = paragraph.split('(').next().unwrap_or_default();
    paragraph
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

#[test]
fn the_python_guide_lists_every_built_in_scene_in_order() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let guide = std::fs::read_to_string(root.join("docs/python.md")).expect("python.md reads");
    let listed = quoted_names_after(&guide, "The built-in scenes' names, in `srt scenes` order:");
    let real: Vec<String> = srt_scene::builtin_scenes()
        .iter()
        .map(|scene| scene.name.to_owned())
        .collect();
    assert_eq!(listed, real);
}

#[test]
fn the_list_reader_sees_a_missing_scene() {
    let text = "Names, in `srt scenes` order: `fig4`, `fig7` (see below).\n\nMore `x`.";
    let listed = quoted_names_after(text, "Names, in `srt scenes` order:");
    assert_eq!(listed, ["fig4", "fig7"]);
}

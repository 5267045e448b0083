//! The page's session: the scene it shows is the one `srt render` loads with the same options,
//! playing time builds nothing and gives the picture a fresh build gives, and bad input is
//! refused by name while the scene shown stays.

use glam::DVec3;
use srt_scene::{Effects, SceneSource};
use srt_trace::{RenderSettings, Tracer};
use srt_web::{Session, parse_query};

const WIDTH: u32 = 64;
const HEIGHT: u32 = 36;

/// The CPU picture of the scene named `argument` loaded through the command's route with the
/// values of the address `query`, as RGBA.
fn command_picture_of(argument: &str, query: &str) -> Vec<u8> {
    let page = parse_query(query).unwrap();
    let loaded = SceneSource::resolve(argument)
        .unwrap()
        .load_with(&page.overrides)
        .unwrap();
    let settings = RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        samples: 1,
    };
    Tracer::new(&loaded.scene)
        .render(settings, &|_| {})
        .to_rgb8()
        .into_iter()
        .flat_map(|[r, g, b]| [r, g, b, 255])
        .collect()
}

/// [`command_picture_of`] the address's own scene.
fn command_picture(query: &str) -> Vec<u8> {
    command_picture_of(&parse_query(query).unwrap().scene.unwrap(), query)
}

fn session_picture(session: &mut Session, query: &str) -> Vec<u8> {
    let page = parse_query(query).unwrap();
    if let Some(scene) = &page.scene {
        session.set_builtin(scene).unwrap();
    }
    session.set_overrides(page.overrides);
    session.render_cpu(WIDTH, HEIGHT).unwrap()
}

#[test]
fn the_page_shows_what_the_command_renders() {
    let mut session = Session::new("teaser").unwrap();
    for query in [
        "scene=teaser",
        "scene=fig7&effects=searchlight",
        "scene=fig4&time=4&beta=0.3,0,-0.8",
        "scene=clocks&time=12",
    ] {
        assert!(
            session_picture(&mut session, query) == command_picture(query),
            "{query}"
        );
    }
}

#[test]
fn playing_time_builds_nothing_and_matches_a_fresh_build() {
    let mut session = Session::new("fig7").unwrap();
    session_picture(&mut session, "scene=fig7&time=1");
    let builds = session.builds();
    let upload = session.upload_version();
    for ct in [2.0, 3.5, -1.0] {
        let query = format!("scene=fig7&time={ct}");
        let played = session_picture(&mut session, &query);
        assert_eq!(session.builds(), builds, "ct = {ct} built the scene again");
        assert!(played == command_picture(&query), "ct = {ct}");
    }
    // Another mode or velocity is built again, on the same upload.
    session_picture(
        &mut session,
        "scene=fig7&time=1&effects=geometry&beta=0,0,0.5",
    );
    assert_eq!(session.builds(), builds + 1);
    assert_eq!(session.upload_version(), upload);
    let info = session.info().unwrap();
    assert_eq!(
        info.effects,
        Effects::Doppler.name(),
        "the scene's own mode"
    );
    assert!(info.beta.length() > 0.9);
    // fig4's cube is fig7's (one upload draws both); the teaser's objects are others.
    session_picture(&mut session, "scene=fig4");
    assert_eq!(session.upload_version(), upload);
    session_picture(&mut session, "scene=teaser");
    assert_eq!(session.upload_version(), upload + 1);
}

#[test]
fn bad_input_is_named_and_the_scene_shown_stays() {
    let mut session = Session::new("fig7").unwrap();
    let before = session.render_cpu(WIDTH, HEIGHT).unwrap();

    let unknown = session.set_builtin("fig99").unwrap_err().to_string();
    assert!(
        unknown.contains("fig99") && unknown.contains("teaser"),
        "{unknown}"
    );

    let mut too_fast = parse_query("beta=0,0,1.2").unwrap().overrides;
    too_fast.beta = Some(DVec3::new(0.0, 0.0, 1.2));
    session.set_overrides(too_fast);
    let refused = session.scene().unwrap_err().to_string();
    assert!(refused.contains("beta"), "{refused}");
    session.set_overrides(parse_query("").unwrap().overrides);
    assert!(session.render_cpu(WIDTH, HEIGHT).unwrap() == before);

    let broken = session
        .load_model("ship.glb", b"not a model".to_vec())
        .unwrap_err()
        .to_string();
    assert!(
        broken.contains("ship.glb") && broken.contains("glTF"),
        "{broken}"
    );
    let empty = session
        .load_model("empty.stl", Vec::new())
        .unwrap_err()
        .to_string();
    assert!(
        empty.contains("empty.stl") && empty.contains("empty"),
        "{empty}"
    );
    let other = session
        .load_model("notes.txt", b"hello".to_vec())
        .unwrap_err()
        .to_string();
    assert!(other.contains("notes.txt"), "{other}");
    assert!(session.render_cpu(WIDTH, HEIGHT).unwrap() == before);
}

#[test]
fn a_dropped_model_is_shown_as_the_command_shows_a_model_file() {
    let spider = srt_scene::assets::embedded("models/spider.stl")
        .unwrap()
        .to_vec();
    let mut session = Session::new("teaser").unwrap();
    let version = session.upload_version();
    session.load_model("folder/spider.stl", spider).unwrap();
    assert_eq!(session.upload_version(), version + 1);
    let scene = session.scene().unwrap();
    assert_eq!(scene.objects.len(), 1);
    // The same picture as `srt render spider.stl` of the file.
    let dropped = session.render_cpu(WIDTH, HEIGHT).unwrap();
    let folder = tempfile::tempdir().unwrap();
    let file = folder.path().join("spider.stl");
    std::fs::write(
        &file,
        srt_scene::assets::embedded("models/spider.stl").unwrap(),
    )
    .unwrap();
    assert!(dropped == command_picture_of(file.to_str().unwrap(), ""));
}

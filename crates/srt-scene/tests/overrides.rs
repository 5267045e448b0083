//! Values a front end gives in place of a scene's own (`srt render --exposure` …) take one route:
//! they edit the description, the scene file's validation judges them, and its messages name
//! the option that gave a refused value.

use std::path::{Path, PathBuf};

use glam::DVec3;
use srt_scene::resolve::SceneSource;
use srt_scene::{
    Effects, OverrideNames, Overrides, SceneErrorKind, SurfaceColour, ValueName,
    description::observation_time,
};

/// A cube at rest in front of an observer at rest, plus `extra` lines.
fn scene_file(dir: &Path, extra: &str) -> PathBuf {
    let path = dir.join("box.toml");
    std::fs::write(
        &path,
        format!(
            "[observer]\nposition = [0, -5, 0]\nlook_at = [0, 0, 0]\n\
             [[object]]\nname = \"box\"\nshape = {{ type = \"cube\" }}\n{extra}"
        ),
    )
    .unwrap();
    path
}

/// The message of loading `argument` with `overrides`.
fn refusal(argument: &str, overrides: &Overrides) -> String {
    let source = SceneSource::resolve(argument).unwrap();
    source.load_with(overrides).unwrap_err().to_string()
}

#[test]
fn overrides_edit_the_description_that_is_built() {
    let overrides = Overrides {
        effects: Some(Effects::Searchlight),
        colour: Some(SurfaceColour::Spectral),
        exposure: Some(2.5),
        time: Some(-3.0),
        beta: Some(DVec3::new(0.0, -0.5, 0.25)),
        ..Overrides::default()
    };
    let loaded = SceneSource::resolve("fig4")
        .unwrap()
        .load_with(&overrides)
        .unwrap();
    let scene = &loaded.scene;
    assert_eq!(scene.effects, Effects::Searchlight);
    assert_eq!(scene.tone_map, Effects::Searchlight.default_tone_map());
    assert_eq!(scene.colour, SurfaceColour::Spectral);
    assert_eq!(scene.exposure, 2.5);
    assert_eq!(scene.observer.time, -3.0);
    for object in &scene.objects {
        assert_eq!(object.frame.beta(), DVec3::new(0.0, -0.5, 0.25));
    }
    // The description says what was built, velocities included.
    let description = &loaded.source.description;
    assert_eq!(description.render.exposure, 2.5);
    assert_eq!(description.objects[0].beta, [0.0, -0.5, 0.25]);
}

#[test]
fn no_overrides_change_nothing() {
    let source = SceneSource::resolve("flythrough").unwrap();
    let plain = source.load(None).unwrap();
    let routed = source.load_with(&Overrides::default()).unwrap();
    assert_eq!(plain.source, routed.source);
    assert_eq!(plain.scene.observer.time, routed.scene.observer.time);
    for (a, b) in plain.scene.objects.iter().zip(&routed.scene.objects) {
        assert_eq!(a.frame, b.frame);
    }
}

#[test]
fn a_bare_model_is_placed_for_the_velocity_given() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("tri.stl");
    std::fs::write(
        &model,
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n\
         endloop\nendfacet\nendsolid t\n",
    )
    .unwrap();
    let source = SceneSource::resolve(&model.display().to_string()).unwrap();
    let beta = DVec3::new(0.3, 0.0, 0.0);
    let routed = source
        .load_with(&Overrides {
            beta: Some(beta),
            ..Overrides::default()
        })
        .unwrap();
    assert_eq!(routed.source, source.load(Some(beta)).unwrap().source);
    assert_eq!(routed.scene.objects[0].frame.beta(), beta);
}

#[test]
fn refused_options_are_named_alone() {
    let cases = [
        (
            Overrides {
                exposure: Some(-1.0),
                ..Overrides::default()
            },
            "--exposure must be a positive number, got -1.0",
        ),
        (
            Overrides {
                exposure: Some(2.0),
                ..Overrides::default()
            },
            "--exposure 2.0 needs spectral colour (--colour spectral): the paper's colour tables \
             have no exposure",
        ),
        (
            Overrides {
                beta: Some(DVec3::new(0.0, 1.2, 0.0)),
                ..Overrides::default()
            },
            "--beta 0.0,1.2,0.0 is not a valid velocity: speed |β| = 1.2 is not below the speed \
             of light (it must be < 1)",
        ),
        (
            Overrides {
                observer_beta: Some(DVec3::new(f64::NAN, 0.0, 0.0)),
                ..Overrides::default()
            },
            "--observer-beta NaN,0.0,0.0 is not a valid velocity: the velocity has a component \
             that is not a finite number",
        ),
        (
            Overrides {
                time: Some(1e300),
                ..Overrides::default()
            },
            "--time must be a finite number within ±1e9, got 1e300",
        ),
        (
            Overrides {
                beta: Some(DVec3::new(0.0, 0.5, 0.0)),
                observer_beta: Some(DVec3::new(0.0, 0.2, 0.0)),
                ..Overrides::default()
            },
            "--beta sets every object's velocity relative to a resting observer and cannot be \
             combined with a moving observer (--observer-beta or observer.beta of built-in scene \
             \"fig7\"); give the objects' velocities in the scene file instead",
        ),
    ];
    for (overrides, expected) in cases {
        assert_eq!(refusal("fig7", &overrides), expected);
    }
    // The scene's own moving observer refuses --beta too.
    let message = refusal(
        "flythrough",
        &Overrides {
            beta: Some(DVec3::new(0.0, 0.5, 0.0)),
            ..Overrides::default()
        },
    );
    assert!(
        message.starts_with("--beta sets every object's velocity")
            && message.contains("flythrough"),
        "{message}"
    );
}

#[test]
fn a_scene_value_refused_because_of_an_option_names_both() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(
        dir.path(),
        "[render]\ncolour = \"spectral\"\nexposure = 2.0\n",
    );
    let message = refusal(
        &path.display().to_string(),
        &Overrides {
            colour: Some(SurfaceColour::Paper),
            ..Overrides::default()
        },
    );
    assert_eq!(
        message,
        format!(
            "{}: render.exposure = 2.0 needs spectral colour (--colour spectral): the paper's \
             colour tables have no exposure",
            path.display()
        )
    );
}

#[test]
fn options_are_judged_before_any_model_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ship.toml");
    std::fs::write(
        &path,
        "[observer]\nposition = [0, -5, 0]\nlook_at = [0, 0, 0]\n\
         [[object]]\nshape = { type = \"model\", path = \"missing.glb\" }\n",
    )
    .unwrap();
    let message = refusal(
        &path.display().to_string(),
        &Overrides {
            exposure: Some(f64::INFINITY),
            ..Overrides::default()
        },
    );
    assert_eq!(message, "--exposure must be a positive number, got inf");
}

#[test]
fn a_front_end_names_its_own_controls() {
    let overrides = Overrides {
        exposure: Some(0.0),
        names: OverrideNames {
            exposure: "the exposure slider",
            ..OverrideNames::COMMAND_LINE
        },
        ..Overrides::default()
    };
    assert_eq!(
        refusal("fig7", &overrides),
        "the exposure slider must be a positive number, got 0.0"
    );
}

#[test]
fn the_time_rule_is_the_scene_files() {
    assert_eq!(
        observation_time(ValueName::Option("--t0"), 4.5).unwrap(),
        4.5
    );
    let refused = observation_time(ValueName::Option("--t1"), -1e20).unwrap_err();
    assert!(matches!(refused, SceneErrorKind::Override { .. }));
    assert_eq!(
        refused.to_string(),
        "--t1 must be a finite number within ±1e9, got -1e20"
    );
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(dir.path(), "");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("[observer]\n", "[observer]\nct = 1e300\n");
    std::fs::write(&path, text).unwrap();
    let message = SceneSource::resolve(&path.display().to_string())
        .unwrap()
        .load(None)
        .unwrap_err()
        .to_string();
    assert_eq!(
        message,
        format!(
            "{}: observer.ct must be a finite number within ±1e9, got 1e300",
            path.display()
        )
    );
}

/// A description a front end edited (or read from text) loads as the source's own would with
/// the same values given as overrides.
#[test]
fn an_edited_description_loads_as_the_overridden_source() {
    let source = SceneSource::resolve("fig4").unwrap();
    let mut edited = source.description(None).unwrap();
    edited.description.observer.ct = 4.4;
    let from_edit = source
        .load_edited(edited.clone(), &Overrides::default())
        .unwrap();
    let overridden = source
        .load_with(&Overrides {
            time: Some(4.4),
            ..Overrides::default()
        })
        .unwrap();
    assert_eq!(
        from_edit.scene.observer.time,
        overridden.scene.observer.time
    );
    assert_eq!(from_edit.source.description, edited.description);
    // Text without a file: built from its base folder, named as a scene without a file.
    let text = edited.clone().load_with(&Overrides::default()).unwrap();
    assert_eq!(text.scene.observer.time, 4.4);
    let mut broken = edited;
    broken.description.observer.fov_y_deg = 200.0;
    let message = broken
        .load_with(&Overrides::default())
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("scene \"fig4\": observer.fov_y_deg"),
        "{message}"
    );
}

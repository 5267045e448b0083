//! The editor's rules, each edit checked against a fresh build of the edited description.

use std::path::{Path, PathBuf};

use glam::DVec3;
use srt_physics::Event;

use super::*;
use crate::description::{SpinDescription, ThrustDescription};
use crate::load_scene_file;
use crate::resolve::DEFAULT_MODEL_SPEED;
use crate::{
    Effects, LightDescription, LightsDescription, Observer, ShapeDescription, SurfaceColour,
};
use srt_color::ToneMap;

fn teaser() -> Editor {
    Editor::open("teaser").expect("the teaser builds").0
}

/// The editor of the first argument with each further one added, as `srt view` opens them.
fn from_arguments(arguments: &[String]) -> Result<(Editor, Vec<String>), EditError> {
    let (mut editor, mut warnings) = Editor::open(&arguments[0])?;
    for argument in &arguments[1..] {
        warnings.extend(editor.add_argument(argument)?);
    }
    Ok((editor, warnings))
}

/// A folder holding the tetrahedron fixture as `tetra.stl`, and that file's path.
fn tetrahedron_file() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("tetra.stl");
    std::fs::write(&model, tetrahedron_stl()).unwrap();
    (dir, model)
}

#[test]
fn spin_and_thrust_are_edits_checked_like_the_scene_file() {
    let (mut editor, _) = Editor::open("fig7").unwrap();
    let spin = SpinDescription {
        axis: [0.0, 0.0, 1.0],
        rate: 0.5,
        centre: [0.0; 3],
    };
    editor.set_spin(0, Some(spin)).unwrap();
    assert_eq!(editor.spin(0), Some(spin));
    assert!(matches!(
        editor.scene().objects[0].motion,
        srt_physics::motion::Motion::Spin(_)
    ));
    // A rim at the speed of light, or a thrust as well, is refused; nothing changes.
    let too_fast = SpinDescription { rate: 5.0, ..spin };
    assert!(editor.set_spin(0, Some(too_fast)).is_err());
    assert_eq!(editor.spin(0), Some(spin));
    let thrust = ThrustDescription {
        proper_acceleration: [0.0, 0.1, 0.0],
        start: 0.0,
        duration: f64::INFINITY,
    };
    assert!(editor.set_thrust(0, Some(thrust)).is_err());
    editor.set_spin(0, None).unwrap();
    editor.set_thrust(0, Some(thrust)).unwrap();
    assert!(matches!(
        editor.scene().objects[0].motion,
        srt_physics::motion::Motion::Thrust(_)
    ));
    editor.set_thrust(0, None).unwrap();
    assert!(editor.scene().objects[0].motion.is_rest());
}

#[test]
fn moving_lights_are_added_edited_and_removed_like_objects() {
    let (mut editor, _) = Editor::open("fig7").unwrap();
    let lamp = editor.scene().light;
    assert!(editor.moving_lights().is_empty());
    let index = editor.add_moving_light().unwrap();
    assert_eq!(index, 0);
    // The `[light]` table became the list's carried lamp: it lights as before.
    assert_eq!(editor.scene().light, lamp);
    assert_eq!(editor.scene().lights.len(), 1);
    let mut light = editor.moving_lights()[0].clone();
    light.beta = [0.0, 0.8, 0.0];
    light.temperature_k = 4000.0;
    editor.set_moving_light(0, light.clone()).unwrap();
    assert_eq!(
        editor.scene().lights[0].frame.beta(),
        DVec3::new(0.0, 0.8, 0.0)
    );
    assert_eq!(editor.scene().lights[0].temperature_k, 4000.0);
    // Refused like a scene file's value; nothing changes.
    light.beta = [0.0, 1.0, 0.0];
    assert!(editor.set_moving_light(0, light).is_err());
    assert_eq!(
        editor.scene().lights[0].frame.beta(),
        DVec3::new(0.0, 0.8, 0.0)
    );
    assert!(matches!(
        editor.set_moving_light(3, LightDescription::lamp([0.0; 3], 5000.0)),
        Err(EditError::NoSuchLight(3))
    ));
    editor.set_lamp_strength(0.0).unwrap();
    assert_eq!(editor.scene().light.strength, 0.0);
    assert!(editor.set_lamp_strength(-1.0).is_err());
    assert!(editor.shadows());
    editor.set_shadows(false).unwrap();
    assert!(!editor.scene().shadows);
    // Saved and read back, the lights are the same.
    let text = editor.description_for_saving().to_toml_string();
    let saved = SceneDescription::from_toml_str(&text, "saved").unwrap();
    assert_eq!(saved.light, editor.description().light);
    editor.remove_moving_light(0).unwrap();
    assert!(editor.scene().lights.is_empty());
    assert_eq!(editor.scene().light.strength, 0.0);
    assert!(matches!(
        editor.remove_moving_light(0),
        Err(EditError::NoSuchLight(0))
    ));
}

#[test]
fn spectral_colour_and_exposure_are_edits_checked_like_the_scene_file() {
    let (mut editor, _) = Editor::open("teaser").unwrap();
    assert_eq!(editor.scene().colour, SurfaceColour::Paper);
    // The paper's colour tables have no exposure.
    assert!(editor.set_exposure(2.0).is_err());
    assert_eq!(editor.scene().exposure, 1.0);
    editor.set_colour(SurfaceColour::Spectral).unwrap();
    editor.set_exposure(2.0).unwrap();
    assert_eq!(editor.scene().exposure, 2.0);
    assert!(editor.set_exposure(-1.0).is_err());
    assert!(editor.set_exposure(f64::NAN).is_err());
    assert_eq!(editor.scene().exposure, 2.0);
    // Back to the paper's colour: the exposure goes back to 1.
    editor.set_colour(SurfaceColour::Paper).unwrap();
    assert_eq!(editor.scene().exposure, 1.0);
}

#[test]
fn typed_speeds_are_numbers_of_at_least_zero() {
    assert_eq!(parse_speed("0.9").unwrap(), 0.9);
    assert_eq!(parse_speed(" 0.5c ").unwrap(), 0.5);
    assert_eq!(parse_speed("0").unwrap(), 0.0);
    assert_eq!(parse_speed("0.9999").unwrap(), 0.9999);
    // Whether it is below c is the scene's rule, checked when the speed is set.
    assert_eq!(parse_speed("1.5c").unwrap(), 1.5);
    let message = |text| parse_speed(text).unwrap_err().to_string();
    assert!(message("fast").contains("not a speed"));
    assert!(message("NaN").contains("not a speed"));
    assert!(message("inf").contains("not a speed"));
    assert!(message("-0.5").contains("negative"));
}

/// Refused edits say what the scene file says about the same values, and change nothing.
#[test]
fn refused_edits_give_the_scene_files_message_and_change_nothing() {
    type Edit = fn(&mut Editor) -> Result<(), EditError>;
    type Same = fn(&mut SceneDescription);
    let cases: [(&str, Edit, Same); 6] = [
        (
            "speed",
            |e| e.set_velocity(1, 1.5, DVec3::X, false),
            |d| d.objects[1].beta = [1.5, 0.0, 0.0],
        ),
        (
            "offset",
            |e| e.set_offset(2, DVec3::new(0.0, f64::NAN, 0.0)),
            |d| d.objects[2].offset[1] = f64::NAN,
        ),
        (
            "wireframe",
            |e| e.set_wireframe(0, Some(-1.0)),
            |d| d.objects[0].wireframe = Some(-1.0),
        ),
        (
            "light",
            |e| e.set_light(0.0, DVec3::ONE),
            |d| {
                d.light = Some(LightsDescription::Lamp(LightDescription::lamp(
                    [1.0; 3], 0.0,
                )));
            },
        ),
        (
            "time",
            |e| e.set_time(f64::INFINITY),
            |d| {
                d.observer.time = Some(f64::INFINITY);
            },
        ),
        (
            "field of view",
            |e| {
                let observer = e.scene().observer;
                e.set_observer(Observer {
                    fov_y_deg: 180.0,
                    ..observer
                })
            },
            |d| d.observer.fov_y_deg = 180.0,
        ),
    ];
    for (what, edit, same) in cases {
        let mut editor = teaser();
        let (description, scene) = (editor.description().clone(), editor.scene().clone());
        let version = editor.structure_version();
        let error = edit(&mut editor).unwrap_err();
        assert!(matches!(error, EditError::Scene(_)), "{what}: {error}");
        let mut expected = description.clone();
        same(&mut expected);
        assert_eq!(
            error.to_string(),
            expected.validate().unwrap_err().to_string(),
            "{what}"
        );
        assert_eq!(editor.description(), &description, "{what}");
        assert_eq!(editor.scene(), &scene, "{what}");
        assert_eq!(editor.structure_version(), version, "{what}");
    }
}

#[test]
fn a_speed_of_c_or_more_is_refused_naming_the_speed_of_light() {
    let mut editor = teaser();
    for text in ["1", "1.0", "1c", "300000"] {
        let speed = parse_speed(text).unwrap();
        let error = editor.set_velocity(1, speed, DVec3::X, true).unwrap_err();
        assert!(
            error.to_string().contains("speed of light"),
            "{text}: {error}"
        );
    }
    assert!(matches!(
        editor.set_velocity(1, 0.5, DVec3::ZERO, true),
        Err(EditError::Direction(_))
    ));
    assert!(matches!(
        editor.set_velocity(7, 0.5, DVec3::X, true),
        Err(EditError::NoSuchObject(7))
    ));
    assert_eq!(editor.description(), teaser().description());
}

#[test]
fn the_teaser_opens() {
    let editor = teaser();
    assert_eq!(editor.scene().name, "teaser");
    assert_eq!(editor.object_count(), 3);
    assert!((editor.speed(0) - 0.95).abs() < 1e-3);
}

#[test]
fn further_arguments_add_objects_under_names_of_their_own() {
    let arguments = ["fig7", "teaser", "teaser"].map(str::to_owned);
    let (editor, _) = from_arguments(&arguments).unwrap();
    assert_eq!(editor.object_count(), 7);
    let names: Vec<_> = editor.objects().iter().map(|o| o.name.as_str()).collect();
    assert!(
        names
            .iter()
            .all(|n| names.iter().filter(|m| *m == n).count() == 1),
        "{names:?}"
    );
    let described: Vec<_> = editor
        .description()
        .objects
        .iter()
        .map(|o| o.name.as_deref().unwrap_or_default())
        .collect();
    assert_eq!(described, names);
}

#[test]
fn a_bare_model_approaches_the_observer() {
    let (_dir, model) = tetrahedron_file();
    let (editor, _) = from_arguments(&[model.display().to_string()]).unwrap();
    let object = &editor.scene().objects[0];
    let observer = editor.scene().observer.event();
    let seen = object.frame.apparent_position(DVec3::ZERO, observer);
    let towards_observer = (observer.position - seen).normalize();
    assert!((editor.speed(0) - DEFAULT_MODEL_SPEED).abs() < 1e-12);
    assert!(object.frame.beta().normalize().dot(towards_observer) > 0.999);
}

#[test]
fn unknown_arguments_and_unsupported_files_are_refused_by_the_resolver() {
    assert!(matches!(
        from_arguments(&["no-such-scene".to_owned()]),
        Err(EditError::Source(ResolveError::NotFound(_)))
    ));
    let dir = tempfile::tempdir().unwrap();
    let notes = dir.path().join("notes.txt");
    std::fs::write(&notes, "hello").unwrap();
    let mut editor = teaser();
    for result in [
        editor.open_file(&notes),
        editor.add_model(&notes),
        editor.add_model(Path::new("teaser")),
    ] {
        assert!(
            matches!(result, Err(EditError::Source(ResolveError::Unsupported(_)))),
            "{result:?}"
        );
    }
}

#[test]
fn changing_the_speed_keeps_the_apparent_position() {
    let mut editor = teaser();
    let observer = editor.scene().observer.event();
    let before = editor.scene().objects[0]
        .frame
        .apparent_position(DVec3::ZERO, observer);
    for speed in [0.0, 0.3, 0.99] {
        let direction = editor.direction(0);
        editor.set_velocity(0, speed, direction, true).unwrap();
        let frame = editor.scene().objects[0].frame;
        assert!((frame.beta().length() - speed).abs() < 1e-12);
        let after = frame.apparent_position(DVec3::ZERO, observer);
        assert!(
            (after - before).length() < 1e-9,
            "{speed}: {before} → {after}"
        );
        assert_eq!(
            editor.description().objects[0].beta,
            frame.beta().to_array()
        );
        assert_eq!(
            editor.description().objects[0].offset,
            frame.offset().to_array()
        );
    }
    // The remembered direction survives a speed of zero.
    assert!(
        editor
            .direction(0)
            .dot(DVec3::new(0.4883, -0.8139, 0.0407).normalize())
            > 0.999
    );
}

#[test]
fn a_model_that_fails_to_load_leaves_the_scene_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("broken.stl");
    std::fs::write(&broken, b"solid nothing\nthis is not an STL file\n").unwrap();
    let mut editor = teaser();
    let version = editor.structure_version();
    let error = editor.add_model(&broken).unwrap_err().to_string();
    assert!(error.contains("broken.stl"), "{error}");
    let missing = editor
        .add_model(&dir.path().join("missing.obj"))
        .unwrap_err()
        .to_string();
    assert!(missing.contains("missing.obj"), "{missing}");
    assert_eq!(editor.object_count(), 3);
    assert_eq!(editor.description().objects.len(), 3);
    assert_eq!(editor.structure_version(), version);
}

#[test]
fn models_are_added_in_view_and_removed() {
    let (_dir, model) = tetrahedron_file();
    let mut editor = teaser();
    editor.add_model(&model).unwrap();
    editor.add_model(&model).unwrap();
    assert_eq!(editor.object_count(), 5);
    assert_eq!(editor.objects()[3].name, "tetra");
    assert_eq!(editor.objects()[4].name, "tetra 2");
    assert_eq!(editor.speed(3), 0.0);
    // In front of the camera.
    let observer = editor.scene().observer;
    let to_object = editor.offset(3) - observer.position;
    assert!(to_object.normalize().dot(observer.basis().0) > 0.999);
    editor
        .set_velocity(3, 0.9, editor.direction(3), true)
        .unwrap();
    assert!(
        editor.direction(3).dot(observer.basis().0) < -0.999,
        "approaches the observer"
    );
    let version = editor.structure_version();
    editor.remove_object(0).unwrap();
    assert_eq!(editor.object_count(), 4);
    assert_eq!(editor.description().objects.len(), 4);
    assert_eq!(editor.objects()[2].name, "tetra");
    assert!(editor.structure_version() > version);
    assert!(editor.remove_object(9).is_err());
}

/// Edits of motion, time, light and style reuse the loaded parts: they succeed with the
/// model file gone, and the meshes need no new upload.
#[test]
fn cheap_edits_never_read_a_model_file_again() {
    let (dir, model) = tetrahedron_file();
    let mut editor = teaser();
    editor.add_model(&model).unwrap();
    drop(dir);
    assert!(!model.exists());
    let version = editor.structure_version();
    editor.set_velocity(3, 0.8, DVec3::Y, true).unwrap();
    editor.set_offset(3, DVec3::new(1.0, 2.0, 3.0)).unwrap();
    editor.set_wireframe(3, Some(0.05)).unwrap();
    editor.set_time(1.5).unwrap();
    editor.set_light(5000.0, DVec3::ONE).unwrap();
    editor.set_effects(Effects::Geometry).unwrap();
    assert_eq!(editor.structure_version(), version);
    editor.remove_object(0).unwrap();
    let tetra = &editor.objects()[2];
    assert_eq!((tetra.name.as_str(), tetra.triangle_count()), ("tetra", 4));
    assert_eq!(tetra.frame.offset(), DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(tetra.wireframe, Some(0.05));
}

/// The parts an edit keeps count against the scene's budget with the ones it builds: two
/// cubes of 1.08 million triangles each do not fit in one scene (2 million), even when
/// they are made one edit at a time.
#[test]
fn kept_parts_count_against_the_scene_budget() {
    let mut editor = teaser();
    let big_cube = |object: &mut ObjectDescription| {
        object.shape = ShapeDescription::Cube {
            size: 1.0,
            subdivisions: 300,
        };
    };
    editor.edit_object(0, big_cube).unwrap();
    let refused = editor.edit_object(1, big_cube).unwrap_err().to_string();
    assert!(
        refused.contains("too large") && refused.contains("already loaded"),
        "{refused}"
    );
    assert_ne!(editor.objects()[1].triangle_count(), 12 * 300 * 300);
}

/// An edit of an object's geometry rebuilds that object (and only needs its own files).
#[test]
fn an_edit_of_the_geometry_rebuilds_the_object() {
    let mut editor = teaser();
    let version = editor.structure_version();
    let triangles = editor.objects()[0].triangle_count();
    editor
        .edit_object(1, |object| {
            object.shape = ShapeDescription::Cube {
                size: 2.0,
                subdivisions: 3,
            };
        })
        .unwrap();
    assert_eq!(editor.objects()[1].triangle_count(), 12 * 3 * 3);
    assert_eq!(editor.objects()[0].triangle_count(), triangles);
    assert!(editor.structure_version() > version);
}

#[test]
fn saved_scenes_load_back_with_the_edits() {
    let (dir, model) = tetrahedron_file();
    let mut editor = teaser();
    editor.add_model(&model).unwrap();
    editor
        .set_velocity(3, 0.9, DVec3::new(0.0, -1.0, 0.0), true)
        .unwrap();
    editor.set_effects(Effects::Searchlight).unwrap();
    editor.set_wireframe(1, Some(0.02)).unwrap();
    editor.set_light(8000.0, DVec3::new(1.0, 2.0, 3.0)).unwrap();
    editor.set_time(2.5).unwrap();
    let saved = dir.path().join("sub").join("saved.toml");
    std::fs::create_dir_all(saved.parent().unwrap()).unwrap();
    editor.save_toml(&saved).unwrap();
    let (scene, description, _) = load_scene_file(&saved).unwrap();
    assert_eq!(scene.objects.len(), 4);
    assert_eq!(description.objects[3].beta, [0.0, -0.9, 0.0]);
    assert_eq!(scene.effects, Effects::Searchlight);
    assert_eq!(scene.objects[1].wireframe, Some(0.02));
    assert_eq!(scene.light.temperature_k, 8000.0);
    assert_eq!(scene.observer.time, 2.5);
    assert_eq!(scene.objects[3].triangle_count(), 4);
}

#[test]
fn the_observer_is_validated_and_reset() {
    let mut editor = teaser();
    let home = editor.home();
    let mut moved = home;
    moved.position += DVec3::new(1.0, 2.0, 0.5);
    moved.fov_y_deg = 60.0;
    editor.set_observer(moved).unwrap();
    for refused in [
        Observer {
            direction: DVec3::ZERO,
            ..moved
        },
        Observer {
            direction: moved.up,
            ..moved
        },
    ] {
        assert!(matches!(
            editor.set_observer(refused),
            Err(EditError::Scene(_))
        ));
    }
    assert_eq!(editor.scene().observer.fov_y_deg, 60.0);
    editor.set_time(4.0).unwrap();
    editor.reset_view().unwrap();
    assert_eq!(editor.scene().observer.position, home.position);
    assert_eq!(editor.scene().observer.time, 4.0);
}

#[test]
fn effects_and_tone_maps() {
    let mut editor = teaser();
    editor.set_effects(Effects::Searchlight).unwrap();
    assert_eq!(editor.scene().tone_map, ToneMap::Searchlight);
    editor.set_tone_map(Some(ToneMap::Luminance)).unwrap();
    assert_eq!(editor.scene().tone_map, ToneMap::Luminance);
    editor.set_effects(Effects::Geometry).unwrap();
    assert_eq!(editor.scene().tone_map, ToneMap::Luminance);
    editor.set_tone_map(None).unwrap();
    editor.set_effects(Effects::Searchlight).unwrap();
    assert_eq!(editor.scene().tone_map, ToneMap::Searchlight);
}

/// The editor's runtime scene is what building its description from scratch gives.
fn assert_matches_a_fresh_build(editor: &Editor) {
    let (fresh, _) = editor.description().build(&editor.base_dir).unwrap();
    assert_eq!(editor.scene(), &fresh);
}

/// What runs every frame while time plays or the observer flies (time, camera, a flight's
/// step) moves the runtime scene without building it, and gives what a fresh build of the
/// edited description gives; a change of the observer's velocity that turns moving
/// objects' geometry (the Wigner rotation) builds, as it must.
#[test]
fn time_and_flight_move_the_scene_without_building_it() {
    for name in ["teaser", "flythrough"] {
        let (mut editor, _) = Editor::open(name).unwrap();
        let builds = editor.builds;
        for step in 1..=3 {
            editor.set_time(0.5 * f64::from(step)).unwrap();
            assert_matches_a_fresh_build(&editor);
        }
        let turned = editor.scene().observer.direction + DVec3::new(0.1, 0.0, -0.05);
        let observer = Observer {
            direction: turned,
            ..editor.scene().observer
        };
        editor.set_observer(observer).unwrap();
        assert_matches_a_fresh_build(&editor);
        // A coasting flight: the observer moves on along its worldline, velocity unchanged.
        let beta = editor.observer_beta();
        let event = editor.observer_event();
        let next = Event::new(event.ct + 0.25, event.position + beta * 0.25);
        editor.set_observer_motion(next, beta).unwrap();
        assert_matches_a_fresh_build(&editor);
        assert_eq!(
            editor.builds, builds,
            "{name}: an observer edit built the scene"
        );
    }
    // Thrust changes the observer's velocity: the teaser's moving objects turn, so it builds.
    let (mut editor, _) = Editor::open("teaser").unwrap();
    let builds = editor.builds;
    editor
        .set_observer_motion(editor.observer_event(), DVec3::new(0.0, 0.1, 0.0))
        .unwrap();
    assert_eq!(editor.builds, builds + 1);
    assert_matches_a_fresh_build(&editor);
    // A time the rules refuse is refused on the fast path too, changing nothing.
    let before = editor.scene().clone();
    assert!(matches!(
        editor.set_time(f64::NAN),
        Err(EditError::Scene(_))
    ));
    assert_eq!(editor.scene(), &before);
}

/// With a moving observer, edits are made in the world frame, and parts turned by the
/// Wigner rotation are rebuilt when a velocity changes the rotation.
#[test]
fn a_moving_observer_is_edited_in_the_world_frame() {
    let (mut editor, _) = Editor::open("flythrough").unwrap();
    let beta_o = DVec3::new(0.0, 0.9, 0.0);
    assert_eq!(editor.observer_beta(), beta_o);
    assert_matches_a_fresh_build(&editor);
    // The sphere moves at 0.6c in W (the panel's speed), faster relative to the observer.
    assert!((editor.speed(0) - 0.6).abs() < 1e-15);
    assert!(editor.objects()[0].frame.beta().length() > 0.9);
    editor
        .set_velocity(0, 0.3, DVec3::new(-1.0, 0.0, 0.2), true)
        .unwrap();
    assert!((editor.speed(0) - 0.3).abs() < 1e-15);
    assert_matches_a_fresh_build(&editor);
    // Keeping where it is seen: the emission event seen now, in W, is unchanged.
    editor.set_observer_beta(DVec3::new(0.2, 0.7, 0.0)).unwrap();
    assert_matches_a_fresh_build(&editor);
    // Time, on the observer's clock, moves the observer along its worldline through W: 2 of its
    // own time are γ·2 of W's time, and the place it was at W's time ct stays.
    let (before, clock) = (editor.observer_event(), editor.time());
    let anchor = editor.description().observer.position;
    editor.set_time(clock + 2.0).unwrap();
    assert_eq!(editor.time(), clock + 2.0);
    assert_eq!(editor.description().observer.position, anchor);
    let beta = editor.observer_beta();
    let gamma = 1.0 / (1.0 - beta.length_squared()).sqrt();
    let after = editor.observer_event();
    assert!((after.ct - before.ct - 2.0 * gamma).abs() < 1e-9);
    assert!((after.position - before.position - 2.0 * gamma * beta).length() < 1e-9);
    assert_matches_a_fresh_build(&editor);
    assert!(matches!(
        editor.set_observer_beta(DVec3::new(0.0, 1.0, 0.0)),
        Err(EditError::Scene(_))
    ));
    // The light is read and written in the world frame.
    let (temperature, position) = editor.light();
    editor.set_light(temperature, position).unwrap();
    assert_eq!(editor.light(), (temperature, position));
}

/// Changing the velocity keeps the object's origin where it is seen, in the world frame
/// when the observer moves.
#[test]
fn keeping_the_apparent_position_works_for_a_moving_observer() {
    let (mut editor, _) = Editor::open("flythrough").unwrap();
    let seen = |editor: &Editor| {
        let object = &editor.objects()[1];
        object
            .frame
            .apparent_position(DVec3::ZERO, editor.scene().observer.event())
    };
    let before = seen(&editor);
    editor
        .set_velocity(1, 0.8, DVec3::new(0.0, 1.0, 0.0), true)
        .unwrap();
    let after = seen(&editor);
    assert!((after - before).length() < 1e-9, "{before} → {after}");
}

/// A binary STL file with one tetrahedron (4 triangles), the fixture the UI tests use too.
fn tetrahedron_stl() -> Vec<u8> {
    include_bytes!("../../tests/fixtures/tetrahedron.stl").to_vec()
}

/// The structure version changes exactly when what a renderer uploads changes
/// ([`Scene::same_structure`]): speeds, time and effects keep it; a first moving light, a
/// removed object and a geometry edit change it.
#[test]
fn the_structure_version_follows_what_a_renderer_uploads() {
    type Edit = fn(&mut Editor) -> Result<(), EditError>;
    let edits: [(&str, Edit, bool); 7] = [
        ("speed", |e| e.set_velocity(0, 0.5, DVec3::X, false), false),
        ("time", |e| e.set_time(3.0), false),
        ("effects", |e| e.set_effects(Effects::Geometry), false),
        ("shadows off", |e| e.set_shadows(false), false),
        ("a moving light", |e| e.add_moving_light().map(|_| ()), true),
        (
            "a second moving light",
            |e| e.add_moving_light().map(|_| ()),
            false,
        ),
        ("an object removed", |e| e.remove_object(1), true),
    ];
    let mut editor = teaser();
    for (what, edit, changes) in edits {
        let (before, version) = (editor.scene().clone(), editor.structure_version());
        edit(&mut editor).unwrap();
        let changed = editor.structure_version() != version;
        assert_eq!(changed, changes, "{what}");
        assert_eq!(changed, !before.same_structure(editor.scene()), "{what}");
    }
}

//! Lists the built-in scenes, or loads one scene and says what is in it.
//!
//! `cargo run -p srt-scene --example inspect` lists the built-in scenes;
//! `cargo run -p srt-scene --example inspect -- SCENE` loads SCENE, a built-in scene's name
//! (`teaser`), a scene file (`my_scene.toml`) or a model (`.gltf`, `.glb`, `.obj`, `.ply`,
//! `.stl`, placed in front of the observer and approaching at 0.9c), and prints its objects with
//! their velocities, the observer and the light.

use srt_scene::{SceneSource, builtin_scenes};

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let Some(argument) = std::env::args().nth(1) else {
        for builtin in builtin_scenes() {
            println!("{:24} {}", builtin.name, builtin.summary);
        }
        return Ok(());
    };
    // The one resolver srt uses: a built-in name, else a scene file or model by its extension.
    let loaded = SceneSource::resolve(&argument)?.load(None)?;
    let scene = &loaded.scene;
    println!(
        "{}: {} objects, {} triangles",
        scene.name,
        scene.objects.len(),
        scene.triangle_count()
    );
    for object in &scene.objects {
        let beta = object.frame.beta();
        println!(
            "  {:16} {:3} parts {:7} triangles  beta ({:+.3}, {:+.3}, {:+.3}) = {:.3}c, gamma {:.3}",
            object.name,
            object.parts.len(),
            object.triangle_count(),
            beta.x,
            beta.y,
            beta.z,
            beta.length(),
            object.frame.gamma(),
        );
    }
    let observer = &scene.observer;
    println!(
        "  observer at {:.2?} looking along {:.2?}, fov {}°, ct = {}",
        observer.position.to_array(),
        observer.direction.to_array(),
        observer.fov_y_deg,
        observer.time
    );
    println!(
        "  light {} K at {:.2?}; effects: {}",
        scene.light.temperature_k,
        scene.light.position.to_array(),
        scene.effects.name()
    );
    for warning in &loaded.warnings {
        println!("  warning: {warning}");
    }
    Ok(())
}

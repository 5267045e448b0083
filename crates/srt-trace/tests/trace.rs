//! srt-trace's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test trace MODULE::` runs one.

mod bands;
mod bare_model;
mod blink;
mod clock;
mod moving_bodies;
mod moving_lights;
mod near_light_speed;
mod physics_checks;
mod principle_of_relativity;
mod projections;
mod seen;
mod sky;
mod spectral;
mod stop;

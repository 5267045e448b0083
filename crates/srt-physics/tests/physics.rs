//! srt-physics's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test physics MODULE::` runs one.

#[allow(dead_code)] // each module uses its own share
mod common;
mod flight;
mod moving_observer;
mod properties;
mod sky;

//! srt-gpu's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test gpu MODULE::` runs one.

#[allow(dead_code)] // each module uses its own share
mod common;
mod context;
mod image_based;
mod images;
mod layout;
mod limits;
mod moving;
mod probe;
mod projections;
mod readback;
mod reflect;
mod shaders;
mod slices;
mod upload;
mod watertight;
mod windows;

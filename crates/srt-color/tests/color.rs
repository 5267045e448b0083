//! srt-color's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test color MODULE::` runs one.

mod lut;
mod planck;
mod spectral;
mod srgb;
#[allow(dead_code)] // each module uses its own share
mod support;
mod tonemap;
mod xyz;

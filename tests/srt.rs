//! The `srt` command's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test srt MODULE::` runs one.

mod architecture;
mod cli;
#[allow(dead_code)] // each module uses its own share
mod common;
mod documents;
mod material_numbers;
mod memory;
mod near_light_speed;
mod overrides;
mod records;
mod slurm;
mod supersampling;
mod video_and_shards;
mod view;

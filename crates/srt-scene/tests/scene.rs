//! srt-scene's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test scene MODULE::` runs one.

mod fuzz;
mod hostile;
mod import;
mod import_corpus;
mod moving_observer;
mod overrides;
mod resolve;
mod scene_builtin;
mod scene_file;
mod view;

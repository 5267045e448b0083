//! srt-physics's integration tests in one binary (one link, not one per file): each module
//! below was a test binary of its own; `cargo test --test physics MODULE::` runs one.

use proptest::test_runner::FileFailurePersistence;

/// Where this binary's property tests keep a failing case, which proptest runs again before
/// any new one: beside the test's file, as `NAME.proptest-regressions`, committed with it
/// (docs/ARCHITECTURE.md, "Failing cases are kept"; tests/architecture.rs checks every test).
const KEEP_FAILURES: FileFailurePersistence =
    FileFailurePersistence::WithSource("proptest-regressions");

#[allow(dead_code)] // each module uses its own share
mod common;
mod flight;
mod moving_observer;
mod properties;
mod sky;

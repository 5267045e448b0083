//! The assimp model corpus: real models no one here made (Debian's `assimp-testmodels`, in
//! /usr/share/assimp/models, or the copy `SRT_ASSIMP_MODELS` names), which srt's tests,
//! benchmarks and `cargo xtask validate` read; and the one rule for a test that needs it on a
//! machine without it: print a line starting with `SKIPPED ` and pass, unless
//! `SRT_REQUIRE_CORPUS=1` (set by CI) requires it, then fail.

use std::io::Write as _;
use std::path::PathBuf;

/// Where Debian installs the corpus.
pub const DEFAULT_FOLDER: &str = "/usr/share/assimp/models";

/// How to get the corpus, for messages about a missing one.
pub const HOW_TO_GET_IT: &str =
    "install it with `apt-get install assimp-testmodels` or point SRT_ASSIMP_MODELS at a copy";

/// The corpus folder: `SRT_ASSIMP_MODELS`, or [`DEFAULT_FOLDER`].
#[must_use]
pub fn folder() -> PathBuf {
    std::env::var_os("SRT_ASSIMP_MODELS")
        .map_or_else(|| PathBuf::from(DEFAULT_FOLDER), PathBuf::from)
}

/// `relative` (a model file or a folder; "" for the corpus itself) in the corpus, for the test
/// named `test`: `None`, after a `SKIPPED ` line on standard error, where it is missing.
///
/// # Panics
/// Where it is missing and `SRT_REQUIRE_CORPUS=1`.
#[must_use]
pub fn for_test(test: &str, relative: &str) -> Option<PathBuf> {
    let path = folder().join(relative);
    if path.exists() {
        return Some(path);
    }
    assert!(
        std::env::var_os("SRT_REQUIRE_CORPUS").is_none_or(|v| v != "1"),
        "{test}: {} is missing and SRT_REQUIRE_CORPUS=1: {HOW_TO_GET_IT}",
        path.display()
    );
    // To the process's standard error directly: the test harness captures `eprintln!` of a
    // passing test, and a skip must be seen.
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED {test}: {} not found; {HOW_TO_GET_IT}",
        path.display()
    );
    None
}

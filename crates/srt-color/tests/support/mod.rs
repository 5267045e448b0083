//! Shared helpers of the spectral tests: CIEDE2000 and the CSV fixtures.

pub mod ciede2000;

use std::path::PathBuf;

/// The rows of a CSV fixture in `tests/data`, without `#` comments and the header, split at commas.
pub fn fixture_rows(name: &str) -> Vec<Vec<String>> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("reading {}: {e}", path.display()));
    text.lines()
        .filter(|line| !line.trim().is_empty() && !line.starts_with('#'))
        .skip(1)
        .map(|line| line.split(',').map(str::to_owned).collect())
        .collect()
}

/// Field `index` of a fixture row as a number.
pub fn number(row: &[String], index: usize) -> f64 {
    row[index]
        .parse()
        .unwrap_or_else(|e| panic!("field {index} of {row:?}: {e}"))
}

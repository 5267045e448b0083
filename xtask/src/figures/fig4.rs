//! Fig. 4 of the paper (not yet drawn).

use std::path::{Path, PathBuf};

/// Writes the figure into `out_dir`.
pub fn write(_out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    Ok(Vec::new())
}

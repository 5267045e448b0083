//! The documentation figures, each reproducing one of the paper's figures from the library crates.

mod colorchecker;
mod fig4;
mod fig5;
mod fig6;
mod fig8;
mod sky;

use std::path::{Path, PathBuf};

/// Writes every figure into `out_dir` and returns the paths written.
pub fn write_all(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    written.extend(fig4::write(out_dir)?);
    written.extend(fig5::write(out_dir)?);
    written.extend(fig6::write(out_dir)?);
    written.extend(fig8::write(out_dir)?);
    written.extend(colorchecker::write(out_dir)?);
    written.extend(sky::write(out_dir)?);
    Ok(written)
}

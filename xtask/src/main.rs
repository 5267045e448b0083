//! Project automation for srt: `cargo xtask figures | validate | bench`.

mod bench;
mod cases;
mod figures;
mod plot;
mod provenance;
mod validate;

use std::path::PathBuf;

use clap::{Parser, Subcommand};

/// Command line of `cargo xtask`.
#[derive(Parser)]
#[command(about = "srt project automation")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// What `cargo xtask` can do.
#[derive(Subcommand)]
enum Command {
    /// Write the documentation figures (the paper's Fig. 4, 5, 6 and 8; ColorChecker; the sky;
    /// the clocks, the beacon, the late shadows and the rolling wheel) as PNGs.
    Figures {
        /// Folder to write into (default: docs/figures in the workspace).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Check every GPU pass against its CPU mirror on the current adapter (kernels, footprints,
    /// images); exits non-zero on any disagreement.
    Validate {
        /// Only the image cases whose scene name contains this text (kernels always run).
        #[arg(long)]
        only: Option<String>,
        /// Instead of the image cases: every frame `cargo xtask bench` times, at its sizes, with
        /// every exact method, recorded for the bench's table.
        #[arg(long)]
        bench_frames: bool,
    },
    /// Measure the paper's Table 1 and scenes in motion on the current adapter; a full run
    /// rewrites the generated blocks of docs/performance.md (table and summary) and saves every
    /// measurement as docs/performance-results.json.
    Bench {
        /// Frames measured per scene and method (after warm-up).
        #[arg(long, default_value_t = 5)]
        frames: u32,
        /// Only the cases whose name contains this text, printed without updating the document
        /// or docs/performance-results.json.
        #[arg(long)]
        only: Option<String>,
        /// Also save the run's results as JSON at PATH, on any run (`--only` included), e.g. to
        /// compare a subset before and after a change.
        #[arg(long, value_name = "PATH")]
        results: Option<PathBuf>,
        /// Measure nothing: print a Markdown table comparing two saved results files (each
        /// method's old ms, new ms and new / old per case, matched by name and size; cases in
        /// only one file listed apart). Needs no GPU.
        #[arg(
            long,
            num_args = 2,
            value_names = ["OLD", "NEW"],
            conflicts_with_all = ["frames", "only", "results"]
        )]
        compare: Option<Vec<PathBuf>>,
    },
}

/// The workspace root (xtask lives one level below it).
fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask sits inside the workspace")
        .to_path_buf()
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Figures { out } => {
            let out = out.unwrap_or_else(|| workspace_root().join("docs/figures"));
            for path in figures::write_all(&out)? {
                println!("wrote {}", path.display());
            }
        }
        Command::Validate { only, bench_frames } => {
            if bench_frames {
                validate::run_bench_frames(&workspace_root(), only.as_deref())?;
            } else {
                validate::run(&workspace_root(), only.as_deref())?;
            }
        }
        Command::Bench {
            compare: Some(files),
            ..
        } => bench::run_compare(&files[0], &files[1])?,
        Command::Bench {
            frames,
            only,
            results,
            compare: None,
        } => bench::run(
            &workspace_root(),
            frames,
            only.as_deref(),
            results.as_deref(),
        )?,
    }
    Ok(())
}

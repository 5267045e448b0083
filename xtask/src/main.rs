//! Project automation for srt: `cargo xtask figures | validate | bench | embree`.

mod bench;
mod cases;
mod embree;
mod figures;
mod plot;
mod provenance;
mod renderers;
mod validate;
mod web;

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
    /// Fit the sRGB coefficient table of spectral colour afresh and write it where srt-color
    /// embeds it (crates/srt-color/data/coefficients_32.bin); run after any change to the fit.
    CoefficientTable,
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
        /// With --bench-frames: the bench's `--size`s (static cases at each, sweeps at the
        /// first); 1280x720 and 1920x1080 when none is given.
        #[arg(
            long = "size",
            value_name = "WxH",
            value_parser = bench::parse_size,
            requires = "bench_frames"
        )]
        sizes: Vec<(u32, u32)>,
    },
    /// Measure the paper's Table 1 and scenes in motion on the current adapter; a full run
    /// rewrites the generated blocks of docs/performance.md (table and summary) and saves every
    /// measurement as docs/performance-results.json.
    Bench {
        /// Least frames timed per scene and method (after warm-up); short frames are timed
        /// until each method's add up to 0.25 s, at most 60.
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
        /// Measure the static cases at this size, e.g. 3840x2160 (repeatable; the sweeps run at
        /// the first): 1280x720 and 1920x1080 when none is given, 1280x720 with --throughput.
        #[arg(long = "size", value_name = "WxH", value_parser = bench::parse_size)]
        sizes: Vec<(u32, u32)>,
        /// Measure nothing: print a Markdown table comparing two saved results files (each
        /// method's old ms, new ms and new / old per case, matched by name and size; cases in
        /// only one file listed apart). Needs no GPU.
        #[arg(
            long,
            num_args = 2,
            value_names = ["OLD", "NEW"],
            conflicts_with_all = ["frames", "only", "results", "sizes"]
        )]
        compare: Option<Vec<PathBuf>>,
        /// Measure instead each method's sustained frames per second: FRAMES frames (default
        /// 30) back to back at each --size, the scene moving on, frames in flight, no readback;
        /// a full run rewrites the throughput block of docs/performance.md.
        #[arg(
            long,
            value_name = "FRAMES",
            num_args = 0..=1,
            default_missing_value = "30",
            conflicts_with_all = ["frames", "results", "compare"]
        )]
        throughput: Option<u32>,
        /// Measure nothing: copy the results file IN to OUT with what `auto` weighs of each
        /// object in each of its frames (triangles, layers, seen pixels) filled in, the frames'
        /// scenes rebuilt by name and size on this machine's adapter (geometry only: the same
        /// on every adapter). For files recorded before the bench kept them, e.g. a hardware
        /// GPU's.
        #[arg(
            long,
            num_args = 2,
            value_names = ["IN", "OUT"],
            conflicts_with_all = ["frames", "only", "results", "sizes", "compare", "throughput"]
        )]
        object_loads: Option<Vec<PathBuf>>,
    },
    /// Build the web page into target/web (wasm with Debian's wasm toolchain, its JavaScript
    /// glue with wasm-bindgen), then serve it on localhost or test it in headless Chromium.
    /// Time the exact CPU tracer against Intel's Embree on identical rays (Embree's Python
    /// binding `embreex`, one thread; `pip install embreex`): the picture's marginal cost over
    /// an 8×8 render, whole process, against Embree's intersection per thread; checks that the
    /// hit masks agree.
    Embree {
        /// Only the cases whose name contains this text.
        #[arg(long)]
        only: Option<String>,
        /// Picture sizes (repeatable): 1280x720 and 1920x1080 when none is given.
        #[arg(long = "size", value_name = "WxH", value_parser = bench::parse_size)]
        sizes: Vec<(u32, u32)>,
    },
    Web {
        /// Serve target/web on 127.0.0.1 until stopped.
        #[arg(long)]
        serve: bool,
        /// The port to serve on.
        #[arg(long, default_value_t = 8080, requires = "serve")]
        port: u16,
        /// Load the embed page of several scenes on WebGPU and on the CPU path in headless
        /// Chromium and compare each screenshot with the exact CPU picture.
        #[arg(long, conflicts_with = "serve")]
        test: bool,
        /// Save a screenshot of the whole page (its controls included) at PATH, 1280×800, once
        /// its first frame is drawn (with --query for the address).
        #[arg(long, value_name = "PATH", conflicts_with_all = ["serve", "test"])]
        screenshot: Option<PathBuf>,
        /// The address's query for --screenshot, e.g. "scene=fig7&split=1".
        #[arg(long, default_value = "", requires = "screenshot")]
        query: String,
        /// Time the CPU worker's frames in headless Chromium on the flythrough and the teaser at
        /// 1280×720: the first frame (the scene and tracer built) and the median of five more
        /// as the time control moves.
        #[arg(long, conflicts_with_all = ["serve", "test", "screenshot"])]
        time: bool,
        /// With --time: time the page built in DIR too (another commit's), beside this one
        /// (repeatable).
        #[arg(long, value_name = "DIR", requires = "time")]
        page: Vec<PathBuf>,
        /// Use the page already in target/web.
        #[arg(long)]
        no_build: bool,
    },
}

/// The workspace root (xtask lives one level below it).
fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask sits inside the workspace")
        .to_path_buf()
}

/// `sizes`, or `default` where none was given.
fn sizes_or(sizes: Vec<(u32, u32)>, default: &[(u32, u32)]) -> Vec<(u32, u32)> {
    if sizes.is_empty() {
        default.to_vec()
    } else {
        sizes
    }
}

/// Builds srt-color's coefficient table at its default resolution and writes its texels where
/// the crate embeds them, through a temporary file renamed into place.
fn write_coefficient_table(root: &std::path::Path) -> anyhow::Result<PathBuf> {
    use anyhow::Context as _;
    use srt_color::spectral::CoefficientTable;
    let table = CoefficientTable::build(CoefficientTable::DEFAULT_RESOLUTION)?;
    let path = root.join("crates/srt-color/data/coefficients_32.bin");
    let partial = path.with_extension("bin.partial");
    std::fs::write(&partial, table.texel_bytes())
        .with_context(|| format!("writing {}", partial.display()))?;
    std::fs::rename(&partial, &path).with_context(|| format!("writing {}", path.display()))?;
    Ok(path)
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Figures { out } => {
            let out = out.unwrap_or_else(|| workspace_root().join("docs/figures"));
            for path in figures::write_all(&out)? {
                println!("wrote {}", path.display());
            }
        }
        Command::CoefficientTable => {
            let path = write_coefficient_table(&workspace_root())?;
            println!("wrote {}", path.display());
        }
        Command::Validate {
            only,
            bench_frames,
            sizes,
        } => {
            if bench_frames {
                let sizes = sizes_or(sizes, &bench::DEFAULT_SIZES);
                validate::run_bench_frames(&workspace_root(), &sizes, only.as_deref())?;
            } else {
                validate::run(&workspace_root(), only.as_deref())?;
            }
        }
        Command::Embree { only, sizes } => {
            let sizes = sizes_or(sizes, &bench::DEFAULT_SIZES);
            embree::run(&workspace_root(), &sizes, only.as_deref())?;
        }
        Command::Bench {
            compare: Some(files),
            ..
        } => bench::run_compare(&files[0], &files[1])?,
        Command::Bench {
            object_loads: Some(files),
            ..
        } => bench::run_object_loads(&files[0], &files[1])?,
        Command::Bench {
            throughput: Some(frames),
            only,
            sizes,
            ..
        } => {
            let sizes = sizes_or(sizes, &bench::DEFAULT_SIZES[..1]);
            bench::run_throughput(&workspace_root(), frames, &sizes, only.as_deref())?;
        }
        Command::Bench {
            frames,
            only,
            results,
            sizes,
            compare: None,
            throughput: None,
            object_loads: None,
        } => bench::run(
            &workspace_root(),
            frames,
            &sizes_or(sizes, &bench::DEFAULT_SIZES),
            only.as_deref(),
            results.as_deref(),
        )?,
        Command::Web {
            serve,
            port,
            test,
            screenshot,
            query,
            time,
            page: other_pages,
            no_build,
        } => {
            let root = workspace_root();
            let page = if no_build {
                root.join(web::OUT_DIR)
            } else {
                web::build(&root)?
            };
            if serve {
                web::serve_forever(&page, port)?;
            } else if test {
                web::test(&root, &page)?;
            } else if let Some(path) = screenshot {
                web::screenshot(&root, &page, &query, &path)?;
            } else if time {
                // This build's page last; with --no-build, only if one was built before.
                let this = Some(page).filter(|page| page.join("index.html").is_file());
                let pages: Vec<PathBuf> = other_pages.into_iter().chain(this).collect();
                web::time_cpu_frames(&root, &pages)?;
            }
        }
    }
    Ok(())
}

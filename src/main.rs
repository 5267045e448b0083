//! The `srt` command-line program: render relativistic scenes and models to images, list the
//! built-in scenes, and open the interactive viewer.
//!
//! Every failure the user can cause (bad files, bad numbers, unwritable paths) ends in one clear
//! message on standard error and exit code 2; nothing is written half-way.

mod cli;
mod output;
mod render;
mod source;

use std::process::ExitCode;

use clap::Parser;

use crate::cli::{Cli, Command};

/// Runs `srt view`.
#[cfg(feature = "viewer")]
fn view(scenes: &[String]) -> anyhow::Result<()> {
    srt_viewer::run(scenes)
}

/// Without the `viewer` feature there is no window.
#[cfg(not(feature = "viewer"))]
fn view(_scenes: &[String]) -> anyhow::Result<()> {
    anyhow::bail!("this srt was built without the `viewer` feature; rebuild with default features")
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or_default() {
        Command::Render(args) => render::run(&args),
        Command::Scenes => {
            source::print_scenes();
            Ok(())
        }
        Command::View { scenes } => view(&scenes),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::from(2)
        }
    }
}

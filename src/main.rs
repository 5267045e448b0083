//! The `srt` command-line program: render relativistic scenes and models to images, and list the
//! built-in scenes.
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or_default() {
        Command::Render(args) => render::run(&args),
        Command::Scenes => {
            source::print_scenes();
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::from(2)
        }
    }
}

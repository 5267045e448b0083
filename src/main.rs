//! The `srt` command-line program.

fn main() {}

//! `cargo run -p srt-viewer --example view -- [SCENE_OR_MODEL ...]`: the viewer without the `srt`
//! program around it (what `srt view` runs).

fn main() -> Result<(), srt_viewer::ViewerError> {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    srt_viewer::run(&arguments)
}

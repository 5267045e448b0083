//! End-to-end tests of issue 12: videos (`-o NAME.mp4 | NAME.gif`, `srt encode`), frames shared
//! among machines (`--shard K/N`), and the record of how each image was made (`srt info`).
//! Small pictures on the CPU backend, so each test runs in seconds.

use crate::common;

use std::fs::File;
use std::io::Write as _;
use std::path::Path;

use common::{assert_clean_failure, folder, srt, srt_ok, stderr};
use openh264::formats::YUVSource as _;

/// Options every render here shares: the exact CPU renderer at 64×36.
const SMALL: [&str; 6] = ["--backend", "cpu", "--width", "64", "--height", "36"];

/// `srt render teaser` with the small options, `extra` and `-o output`.
fn render_teaser(dir: &Path, extra: &[&str], output: &str) -> String {
    let args = [&["render", "teaser"][..], &SMALL, extra, &["-o", output]].concat();
    srt_ok(&args, dir)
}

/// The names of the files in `dir`, sorted.
fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("readable folder")
        .map(|entry| {
            entry
                .expect("entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}

/// Mean absolute difference of two equally sized 8-bit RGB buffers, in 8-bit steps.
fn mean_difference(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    let sum: u64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| u64::from(x.abs_diff(*y)))
        .sum();
    sum as f64 / a.len() as f64
}

/// A decoded video: its size and its frames as 8-bit RGB.
struct Decoded {
    size: (u16, u16),
    frames: Vec<Vec<u8>>,
}

/// Decodes every sample of the MP4's one video track with OpenH264.
fn decode_mp4(path: &Path) -> Decoded {
    let mut reader = mp4::read_mp4(File::open(path).expect("the MP4 exists")).expect("an MP4");
    assert_eq!(reader.tracks().len(), 1, "one track");
    let track = reader.tracks().values().next().expect("a track");
    let (id, size, samples) = (
        track.track_id(),
        (track.width(), track.height()),
        track.sample_count(),
    );
    // The samples hold length-prefixed NAL units; the decoder takes start codes, with the
    // parameter sets (kept in the avcC box) first.
    let mut annex_b = Vec::new();
    for set in [
        track.sequence_parameter_set().expect("an SPS"),
        track.picture_parameter_set().expect("a PPS"),
    ] {
        annex_b.extend_from_slice(&[0, 0, 0, 1]);
        annex_b.extend_from_slice(set);
    }
    let mut decoder = openh264::decoder::Decoder::new().expect("an H.264 decoder");
    let mut frames = Vec::new();
    let mut keep = |yuv: &openh264::decoder::DecodedYUV<'_>| {
        let (width, height) = yuv.dimensions();
        let mut rgb = vec![0; width * height * 3];
        yuv.write_rgb8(&mut rgb);
        assert_eq!((width, height), (usize::from(size.0), usize::from(size.1)));
        frames.push(rgb);
    };
    for sample_id in 1..=samples {
        let sample = reader
            .read_sample(id, sample_id)
            .expect("a readable sample")
            .expect("the sample exists");
        let mut data: &[u8] = &sample.bytes;
        while data.len() >= 4 {
            let length = u32::from_be_bytes(data[..4].try_into().unwrap()) as usize;
            annex_b.extend_from_slice(&[0, 0, 0, 1]);
            annex_b.extend_from_slice(&data[4..4 + length]);
            data = &data[4 + length..];
        }
        if let Some(yuv) = decoder.decode(&annex_b).expect("a decodable sample") {
            keep(&yuv);
        }
        annex_b.clear();
    }
    for yuv in decoder.flush_remaining().expect("flushes") {
        keep(&yuv);
    }
    Decoded { size, frames }
}

/// Decodes a GIF; returns it and each frame's delay in 1/100 s.
fn decode_gif(path: &Path) -> (Decoded, Vec<u16>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(File::open(path).expect("the GIF exists"))
        .expect("a GIF");
    let size = (decoder.width(), decoder.height());
    let (mut frames, mut delays) = (Vec::new(), Vec::new());
    while let Some(frame) = decoder.read_next_frame().expect("a decodable frame") {
        assert_eq!((frame.width, frame.height), size, "every frame is whole");
        let rgb = frame
            .buffer
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        frames.push(rgb);
        delays.push(frame.delay);
    }
    (Decoded { size, frames }, delays)
}

/// An MP4 and a GIF of the teaser decode to the frame count and size asked for, and each of
/// their frames is the picture of the numbered image of that frame (up to the codecs' losses:
/// about 1 step of 255 on average for H.264 here, none for the GIF's palette; a black frame
/// would be 7 steps off, the last frame 3).
#[test]
fn mp4_and_gif_of_the_teaser_decode_to_the_frames_asked_for() {
    let dir = folder();
    let frames = ["--frames", "5", "--t0", "0", "--t1", "8"];
    let said = render_teaser(
        dir.path(),
        &[&frames[..], &["--fps", "10"]].concat(),
        "t.mp4",
    );
    assert!(said.contains("wrote t.mp4 (5 frames at 10 fps"), "{said}");
    render_teaser(
        dir.path(),
        &[&frames[..], &["--fps", "10"]].concat(),
        "t.gif",
    );
    render_teaser(dir.path(), &frames, "t.png");
    let pictures: Vec<Vec<u8>> = (0..5)
        .map(|k| {
            let path = dir.path().join(format!("t_{k:04}.png"));
            image::open(path).expect("a frame").to_rgb8().into_raw()
        })
        .collect();
    assert!(
        mean_difference(&pictures[0], &pictures[4]) > 2.0,
        "the objects move"
    );

    let mp4 = decode_mp4(&dir.path().join("t.mp4"));
    let (gif, delays) = decode_gif(&dir.path().join("t.gif"));
    assert_eq!(delays, [10; 5], "10 fps");
    for (video, tolerance) in [(mp4, 2.0), (gif, 0.5)] {
        assert_eq!(video.size, (64, 36));
        assert_eq!(video.frames.len(), 5);
        for (k, (frame, picture)) in video.frames.iter().zip(&pictures).enumerate() {
            let error = mean_difference(frame, picture);
            assert!(error < tolerance, "frame {k} differs by {error} on average");
            // In order: each frame is nearer its own picture than any other frame's.
            for (j, other) in pictures.iter().enumerate().filter(|&(j, _)| j != k) {
                let other_error = mean_difference(frame, other);
                assert!(
                    error < other_error,
                    "frame {k} is {error} from its picture but {other_error} from frame {j}'s"
                );
            }
        }
    }
    assert_eq!(
        file_names(dir.path()).len(),
        7,
        "two videos and five frames, nothing else"
    );
}

/// Three shares of an animation write exactly the files of one unsharded run, byte for byte,
/// and `srt encode` joins them into a video.
#[test]
fn three_shards_give_the_frames_of_one_unsharded_run_byte_for_byte() {
    let dir = folder();
    for name in ["whole", "shares"] {
        std::fs::create_dir(dir.path().join(name)).unwrap();
    }
    let frames = ["--frames", "7", "--t0", "-2", "--t1", "9"];
    render_teaser(dir.path(), &frames, "whole/f.png");
    for share in ["1/3", "2/3", "3/3"] {
        let said = render_teaser(
            dir.path(),
            &[&frames[..], &["--shard", share]].concat(),
            "shares/f.png",
        );
        if share == "2/3" {
            let lines: Vec<&str> = said.lines().collect();
            assert_eq!(lines.len(), 2, "share 2/3 renders frames 1 and 4:\n{said}");
            assert!(lines[0].starts_with("wrote shares/f_0001.png"), "{said}");
            assert!(lines[1].starts_with("wrote shares/f_0004.png"), "{said}");
        }
    }
    let whole = file_names(&dir.path().join("whole"));
    assert_eq!(whole.len(), 7, "{whole:?}");
    assert_eq!(file_names(&dir.path().join("shares")), whole);
    for name in &whole {
        let read = |folder: &str| std::fs::read(dir.path().join(folder).join(name)).unwrap();
        assert!(read("whole") == read("shares"), "{name} differs");
    }

    let frame_paths: Vec<String> = whole.iter().map(|n| format!("shares/{n}")).collect();
    let frame_args: Vec<&str> = frame_paths.iter().map(String::as_str).collect();
    for video in ["film.gif", "film.mp4"] {
        let said = srt_ok(
            &[&["encode"][..], &frame_args, &["-o", video, "--fps", "12"]].concat(),
            dir.path(),
        );
        assert!(
            said.contains(&format!("wrote {video} (7 frames, 64x36, 12 fps")),
            "{said}"
        );
    }
    assert_eq!(decode_gif(&dir.path().join("film.gif")).0.frames.len(), 7);
    assert_eq!(decode_mp4(&dir.path().join("film.mp4")).frames.len(), 7);
}

/// `srt encode` takes srt's linear-light EXR frames through the sRGB encoding: the video shows
/// what the PNG frames show.
#[test]
fn encode_takes_exr_frames_as_the_png_frames_look() {
    let dir = folder();
    for name in ["f.png", "f.exr"] {
        render_teaser(dir.path(), &["--frames", "2", "--t0", "3"], name);
    }
    srt_ok(
        &["encode", "f_0000.exr", "f_0001.exr", "-o", "f.gif"],
        dir.path(),
    );
    let (gif, _) = decode_gif(&dir.path().join("f.gif"));
    assert_eq!(gif.frames.len(), 2);
    for (k, frame) in gif.frames.iter().enumerate() {
        let png = image::open(dir.path().join(format!("f_{k:04}.png"))).expect("a frame");
        let error = mean_difference(frame, png.to_rgb8().as_raw());
        assert!(error < 0.5, "frame {k} differs by {error} on average");
    }
}

/// Every image records how it was made, and `srt info` prints it; the same render writes the
/// same record into PNG and EXR.
#[test]
fn info_prints_how_an_image_was_made() {
    let dir = folder();
    let options = [
        "--time",
        "4.5",
        "--beta",
        "0,0.5,-0.25",
        "--effects",
        "searchlight",
    ];
    for name in ["a.png", "a.exr"] {
        let args = [&["render", "fig4"][..], &SMALL, &options, &["-o", name]].concat();
        srt_ok(&args, dir.path());
    }
    let png = srt_ok(&["info", "a.png"], dir.path());
    let entries = info_entries(&png);
    for (key, value) in [
        ("srt version", env!("CARGO_PKG_VERSION")),
        ("scene", "fig4 (built-in)"),
        ("observer velocity", "(0.0, 0.0, 0.0)"),
        ("effects", "searchlight"),
        ("backend", "cpu"),
        ("adapter", "none"),
        ("size", "64x36"),
        ("samples", "1"),
        ("time", "4.5"),
    ] {
        assert_eq!(
            entries.get(key).map(String::as_str),
            Some(value),
            "{key} in:\n{png}"
        );
    }
    assert!(
        entries["velocities"].ends_with("(0.0, 0.5, -0.25)"),
        "{png}"
    );
    assert!(!entries.contains_key("scene sha256"), "{png}");
    // An EXR's record is the PNG's; below it, the range of its pixels.
    let exr = srt_ok(&["info", "a.exr"], dir.path());
    let (record, range) = exr.split_at(png.len());
    assert_eq!(record, png);
    assert!(
        range.contains("pixel range") && range.contains("pixels above 1.0"),
        "{exr}"
    );

    // A scene file is named by its file name and the SHA-256 of its content; a moving observer
    // is recorded.
    let scene = "[observer]\nposition = [0, -8, 0]\nlook_at = [0, 0, 0]\n\n[[object]]\n\
                 shape = { type = \"cube\" }\nbeta = [0.3, 0, 0]\n";
    std::fs::write(dir.path().join("s.toml"), scene).unwrap();
    let args = [
        &["render", "s.toml"][..],
        &SMALL,
        &["--observer-beta", "0,0.2,0", "-o", "s.png"],
    ]
    .concat();
    srt_ok(&args, dir.path());
    let info = srt_ok(&["info", "s.png"], dir.path());
    let entries = info_entries(&info);
    use sha2::Digest as _;
    let digest = sha2::Sha256::digest(scene.as_bytes());
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    assert_eq!(entries["scene"], "s.toml (scene file)", "{info}");
    assert_eq!(entries["scene sha256"], hex, "{info}");
    assert_eq!(entries["observer velocity"], "(0.0, 0.2, 0.0)", "{info}");
}

/// The `key  value` lines `srt info` prints (keys may hold single spaces; two or more end them).
fn info_entries(text: &str) -> std::collections::HashMap<String, String> {
    text.lines()
        .map(|line| {
            let (key, value) = line.split_once("  ").expect("a key and a value");
            (key.to_owned(), value.trim_start().to_owned())
        })
        .collect()
}

/// `srt info` on a file that is no image, an image srt did not write, or no file at all: one
/// clear line, exit code 2.
#[test]
fn info_refuses_files_without_a_record() {
    let dir = folder();
    std::fs::write(dir.path().join("notes.png"), "not an image").unwrap();
    assert_clean_failure(
        &srt(&["info", "notes.png"], dir.path()),
        &["notes.png", "not a PNG or EXR image"],
    );
    image::RgbImage::new(4, 4)
        .save(dir.path().join("plain.png"))
        .unwrap();
    assert_clean_failure(
        &srt(&["info", "plain.png"], dir.path()),
        &["plain.png", "no srt record"],
    );
    assert_clean_failure(
        &srt(&["info", "gone.exr"], dir.path()),
        &["gone.exr", "no such file"],
    );
}

/// Bad shares, video options and outputs stop before rendering with one clear line and exit
/// code 2, and leave nothing behind.
#[test]
fn bad_shards_and_video_outputs_are_refused_and_leave_nothing() {
    let dir = folder();
    let cases: [(&[&str], &[&str]); 10] = [
        (
            &["--frames", "4", "--shard", "3/2", "-o", "f.png"],
            &["--shard 3/2", "between 1 and 2"],
        ),
        (
            &["--frames", "4", "--shard", "0/0", "-o", "f.png"],
            &["--shard 0/0", "at least 1"],
        ),
        (&["--shard", "1/2", "-o", "f.png"], &["--shard", "--frames"]),
        (
            &["--frames", "4", "-o", "f.avi"],
            &["f.avi", ".mp4", ".gif"],
        ),
        (
            &["--frames", "4", "-o", "missing/f.mp4"],
            &["missing/f.mp4", "does not exist"],
        ),
        // No one, root included, may create files in /proc.
        (
            &["--frames", "2", "-o", "/proc/f.mp4"],
            &["/proc/f.mp4", "cannot"],
        ),
        (&["-o", "f.mp4"], &["f.mp4", "--frames"]),
        (
            &["--frames", "4", "--shard", "1/2", "-o", "f.gif"],
            &["--shard", "srt encode"],
        ),
        (
            &[
                "--frames", "4", "--width", "65", "--height", "36", "-o", "f.mp4",
            ],
            &["f.mp4", "even", "65x36"],
        ),
        (
            &["--frames", "4", "--width", "4000", "-o", "f.mp4"],
            &["f.mp4", "3840x2160", "4000x720"],
        ),
    ];
    for (extra, mentions) in cases {
        // Every case is refused before the scene is loaded, so the default size costs nothing.
        let args = [&["render", "teaser", "--backend", "cpu"][..], extra].concat();
        assert_clean_failure(&srt(&args, dir.path()), mentions);
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        let locked = dir.path().join("locked");
        std::fs::create_dir(&locked).unwrap();
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o555)).unwrap();
        // Root may write anywhere, so as root the case runs srt as an unprivileged user
        // (through util-linux's setpriv) where the system has setpriv.
        let args = [
            &["render", "teaser"][..],
            &SMALL,
            &["--frames", "2", "-o", "locked/f.gif"],
        ]
        .concat();
        let refused = if File::create(locked.join("probe")).is_err() {
            Some(srt(&args, dir.path()))
        } else {
            std::fs::remove_file(locked.join("probe")).unwrap();
            as_nobody(&args, dir.path())
        };
        match refused {
            Some(output) => assert_clean_failure(&output, &["locked/f.gif", "cannot"]),
            None => {
                // Written to stderr directly: the harness captures `eprintln!` of passing tests.
                let _ = writeln!(
                    std::io::stderr(),
                    "SKIPPED the read-only-folder case: running as root without `setpriv` to \
                     run srt as an unprivileged user (the /proc case above still runs)"
                );
            }
        }
        assert!(file_names(&locked).is_empty());
        std::fs::remove_dir(&locked).unwrap();
    }
    assert!(
        file_names(dir.path()).is_empty(),
        "{:?}",
        file_names(dir.path())
    );
}

/// Runs `srt` with `args` in `dir` as an unprivileged user (uid and gid 65534, `nobody` on
/// Debian), or `None` where the system has no `setpriv`. `dir` is opened to every user for the
/// run.
#[cfg(unix)]
fn as_nobody(args: &[&str], dir: &Path) -> Option<std::process::Output> {
    use std::os::unix::fs::PermissionsExt as _;
    std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o755)).unwrap();
    let output = std::process::Command::new("setpriv")
        .args(["--reuid=65534", "--regid=65534", "--clear-groups", "--"])
        .arg(env!("CARGO_BIN_EXE_srt"))
        .args(args)
        .current_dir(dir)
        .output()
        .ok();
    std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o700)).unwrap();
    output
}

/// A video that fails midway (its third frame is no image; then frames of two sizes) leaves no
/// file, not even a temporary one, and an existing video of that name untouched.
#[test]
fn a_video_failing_midway_leaves_no_file() {
    let dir = folder();
    render_teaser(dir.path(), &["--frames", "2"], "f.png");
    std::fs::write(dir.path().join("f_0002.png"), "not an image").unwrap();
    let before = file_names(dir.path());
    assert_clean_failure(
        &srt(
            &[
                "encode",
                "f_0000.png",
                "f_0001.png",
                "f_0002.png",
                "-o",
                "film.mp4",
            ],
            dir.path(),
        ),
        &["f_0002.png"],
    );
    assert_eq!(file_names(dir.path()), before);

    image::RgbImage::new(32, 18)
        .save(dir.path().join("small.png"))
        .unwrap();
    std::fs::write(dir.path().join("film.gif"), b"precious").unwrap();
    assert_clean_failure(
        &srt(
            &[
                "encode",
                "f_0000.png",
                "f_0001.png",
                "small.png",
                "-o",
                "film.gif",
            ],
            dir.path(),
        ),
        &["small.png", "32x18", "64x36"],
    );
    assert_eq!(
        std::fs::read(dir.path().join("film.gif")).unwrap(),
        b"precious"
    );
    assert_eq!(file_names(dir.path()).len(), before.len() + 2);
    assert_clean_failure(
        &srt(&["encode", "f_0000.png", "-o", "film.png"], dir.path()),
        &["film.png", ".mp4"],
    );
}

/// The files in `dir` whose names end with `.partial` (the temporary files of unfinished
/// outputs).
fn partial_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".partial"))
        .collect()
}

/// Starts `srt` with `args` in `dir`, waits until `ready` holds for the folder (up to ten
/// minutes: a bound for a stuck run, not a speed), sends it `signal` (`kill -s`) and returns
/// how it ended.
#[cfg(unix)]
fn interrupted(
    args: &[&str],
    dir: &Path,
    signal: &str,
    ready: impl Fn(&Path) -> bool,
) -> std::process::ExitStatus {
    // Without a runtime folder srt makes a private one in the temporary folder: a folder of
    // the test's own, empty again once srt has ended.
    let temporary = folder();
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_srt"))
        .args(args)
        .current_dir(dir)
        .env_remove("XDG_RUNTIME_DIR")
        .env("TMPDIR", temporary.path())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("srt runs");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(600);
    while !ready(dir) && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    assert!(ready(dir), "srt never got to the point to interrupt");
    let sent = std::process::Command::new("kill")
        .args(["-s", signal, &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
    let ended = child.wait().expect("srt ends");
    let left: Vec<_> = std::fs::read_dir(temporary.path()).unwrap().collect();
    assert!(
        left.is_empty(),
        "SIG{signal} left {left:?} in the temporary folder"
    );
    ended
}

/// A render ended by SIGINT, SIGTERM or SIGHUP removes its unfinished files and exits with
/// 128 + the signal: a video leaves the folder as it was; a sharded run of numbered images keeps
/// only the frames it finished, every one finished before the signal among them, each the
/// frame an uninterrupted run writes, byte for byte.
#[cfg(unix)]
#[test]
fn interrupted_renders_leave_no_unfinished_file() {
    // Far more frames than are rendered before the signal, on any machine.
    let frames = ["--frames", "4000", "--t0", "0", "--t1", "8"];
    for (signal, status) in [("INT", 130), ("TERM", 143), ("HUP", 129)] {
        let dir = folder();
        let args = [&["render", "teaser"][..], &SMALL, &frames, &["-o", "t.gif"]].concat();
        let ended = interrupted(&args, dir.path(), signal, |dir| {
            !partial_files(dir).is_empty()
        });
        assert_eq!(ended.code(), Some(status), "SIG{signal}");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert!(left.is_empty(), "SIG{signal} left {left:?}");
    }
    let dir = folder();
    let sharded = [&frames[..], &["--shard", "1/2"]].concat();
    let args = [
        &["render", "teaser"][..],
        &SMALL,
        &sharded,
        &["-o", "t.png"],
    ]
    .concat();
    // The frames finished when the signal is sent, as they are then (each renamed into place
    // whole, so a name there is a complete file).
    let finished = std::cell::RefCell::new(Vec::new());
    let ended = interrupted(&args, dir.path(), "TERM", |dir| {
        if !dir.join("t_0002.png").exists() {
            return false;
        }
        *finished.borrow_mut() = finished_frames(dir);
        true
    });
    assert_eq!(ended.code(), Some(143));
    assert!(partial_files(dir.path()).is_empty());
    let finished = finished.into_inner();
    let kept = finished_frames(dir.path());
    assert!(
        finished.iter().any(|(name, _)| name == "t_0002.png"),
        "{finished:?}"
    );
    for (name, bytes) in &finished {
        let now = kept.iter().find(|(kept, _)| kept == name);
        assert!(
            now.is_some_and(|(_, now)| now == bytes),
            "{name}, finished before SIGTERM, is gone or changed"
        );
    }
    // Every frame left (those finished before the signal and any finished before it took
    // effect) is the frame an uninterrupted run writes, byte for byte: each rendered alone
    // here as the one frame of its own share (frame i is share i + 1 of 4000).
    let whole = folder();
    for (name, bytes) in &kept {
        let frame: u32 = name
            .strip_prefix("t_")
            .and_then(|n| n.strip_suffix(".png"))
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{name} is not a frame of t.png"));
        assert_eq!(frame % 2, 0, "{name} is not in share 1/2");
        let alone = format!("{}/4000", frame + 1);
        render_teaser(
            whole.path(),
            &[&frames[..], &["--shard", &alone]].concat(),
            "t.png",
        );
        let expected = std::fs::read(whole.path().join(name)).unwrap();
        assert!(
            *bytes == expected,
            "{name} differs from the frame of an uninterrupted run"
        );
    }
}

/// The files of `dir` but the temporary ones, each with its bytes, sorted by name.
#[cfg(unix)]
fn finished_frames(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut names = file_names(dir);
    names.retain(|name| !name.ends_with(".partial"));
    names
        .into_iter()
        .map(|name| {
            let bytes = std::fs::read(dir.join(&name)).unwrap();
            (name, bytes)
        })
        .collect()
}

/// The boxes of an MP4 below `start..end` of `data`, each as its path of box types
/// ("moov/trak/…/st3d") with its start and size, descending into the containers on the way to
/// the video sample entry and into the spherical metadata.
fn mp4_boxes(data: &[u8], start: usize, end: usize, parent: &str) -> Vec<(String, usize, usize)> {
    let mut found = Vec::new();
    let mut at = start;
    while at + 8 <= end {
        let size = u32::from_be_bytes(data[at..at + 4].try_into().unwrap()) as usize;
        let kind = String::from_utf8_lossy(&data[at + 4..at + 8]).into_owned();
        let path = if parent.is_empty() {
            kind.clone()
        } else {
            format!("{parent}/{kind}")
        };
        let fields = match kind.as_str() {
            "moov" | "trak" | "mdia" | "minf" | "stbl" | "sv3d" | "proj" => Some(0),
            "stsd" => Some(8),
            "avc1" => Some(78),
            _ => None,
        };
        if let Some(fields) = fields {
            found.extend(mp4_boxes(data, at + 8 + fields, at + size, &path));
        }
        found.push((path, at, size));
        at += size;
    }
    found
}

/// An equirectangular video carries the Spherical Video V2 boxes in its sample entry — `st3d`
/// (mono) and `sv3d` with `svhd` and `proj` (`prhd`, `equi`) — so that 360° players show it
/// around the viewer, and still decodes to its frames; a perspective video has none; a stereo
/// pair's says top-bottom.
#[test]
fn a_360_video_carries_the_spherical_boxes_and_still_plays() {
    let dir = folder();
    let common = [
        "--frames",
        "3",
        "--width",
        "64",
        "--height",
        "32",
        "--backend",
        "cpu",
    ];
    for (name, projection) in [("sky.mp4", "equirectangular"), ("flat.mp4", "perspective")] {
        let output = srt(
            &[
                &["render", "fig7", "--projection", projection, "-o", name][..],
                &common,
            ]
            .concat(),
            dir.path(),
        );
        assert!(output.status.success(), "{}", stderr(&output));
        assert_eq!(
            decode_mp4(&dir.path().join(name)).frames.len(),
            3,
            "{name} plays"
        );
    }
    let sky = std::fs::read(dir.path().join("sky.mp4")).unwrap();
    let boxes = mp4_boxes(&sky, 0, sky.len(), "");
    let entry = "moov/trak/mdia/minf/stbl/stsd/avc1";
    let find = |path: &str| {
        boxes
            .iter()
            .find(|(p, ..)| p == path)
            .map(|&(_, at, size)| (at, size))
    };
    for child in [
        "avcC",
        "st3d",
        "sv3d",
        "sv3d/svhd",
        "sv3d/proj",
        "sv3d/proj/prhd",
        "sv3d/proj/equi",
    ] {
        assert!(
            find(&format!("{entry}/{child}")).is_some(),
            "{child} missing: {boxes:?}"
        );
    }
    let (st3d, size) = find(&format!("{entry}/st3d")).unwrap();
    assert_eq!((size, sky[st3d + 12]), (13, 0), "st3d: mono");
    let (equi, size) = find(&format!("{entry}/sv3d/proj/equi")).unwrap();
    assert_eq!(size, 28);
    assert!(
        sky[equi + 8..equi + 28].iter().all(|&b| b == 0),
        "the whole sphere"
    );
    let flat = std::fs::read(dir.path().join("flat.mp4")).unwrap();
    assert!(
        !mp4_boxes(&flat, 0, flat.len(), "")
            .iter()
            .any(|(p, ..)| p.ends_with("sv3d")),
        "a perspective video is not 360°"
    );
    // A stereo pair, the left eye above the right: st3d's mode 1 (top-bottom).
    let output = srt(
        &[
            &[
                "render",
                "fig7",
                "--projection",
                "equirectangular",
                "--set",
                "observer.stereo={eye_separation=0.1}",
                "-o",
                "pair.mp4",
            ][..],
            &common,
        ]
        .concat(),
        dir.path(),
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let pair = std::fs::read(dir.path().join("pair.mp4")).unwrap();
    let boxes = mp4_boxes(&pair, 0, pair.len(), "");
    let &(_, st3d, size) = boxes
        .iter()
        .find(|(p, ..)| *p == format!("{entry}/st3d"))
        .expect("st3d");
    assert_eq!((size, pair[st3d + 12]), (13, 1), "st3d: top-bottom");
}

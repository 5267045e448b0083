//! End-to-end tests of the record of how a video was made (issue 68, section 2): `srt render`
//! and `srt encode` store it in every MP4 (the user-data comment `moov/udta/©cmt`) and GIF (a
//! comment extension) they write, `srt info` prints it as it does an image's, and a video cut
//! short, a foreign one or one without a record is refused in one clear line. Tiny pictures on
//! the CPU backend, so each test runs in seconds.

use crate::common;

use std::collections::HashMap;
use std::path::Path;

use common::{assert_clean_failure, folder, srt, srt_ok};

/// Options every render here shares: the exact CPU renderer at 32×18.
const TINY: [&str; 6] = ["--backend", "cpu", "--width", "32", "--height", "18"];

/// An animation of three frames from ct = 1 to ct = 2.
const FRAMES: [&str; 6] = ["--frames", "3", "--t0", "1", "--t1", "2"];

/// `srt render teaser` with the tiny options, the three frames, `extra` and `-o output`.
fn render(dir: &Path, extra: &[&str], output: &str) {
    let args = [
        &["render", "teaser"][..],
        &TINY,
        &FRAMES,
        extra,
        &["-o", output],
    ]
    .concat();
    srt_ok(&args, dir);
}

/// The entries `srt info FILE` prints (`key  value` lines; keys may hold single spaces).
fn info(dir: &Path, file: &str) -> HashMap<String, String> {
    srt_ok(&["info", file], dir)
        .lines()
        .map(|line| {
            let (key, value) = line.split_once("  ").expect("a key and a value");
            (key.to_owned(), value.trim_start().to_owned())
        })
        .collect()
}

/// A frame's record less its own entries (time, frame number, EXR channels): what a video of
/// its animation states for all its frames.
fn shared_entries(mut record: HashMap<String, String>) -> HashMap<String, String> {
    for key in ["time", "frame", "exr channels"] {
        record.remove(key);
    }
    record
}

/// Asserts that `video`'s record is the frames' shared entries (`frame`'s) and then `time`,
/// `frames` and `said` for the video.
fn assert_video_record(
    video: &HashMap<String, String>,
    frame: &HashMap<String, String>,
    [time, frames, said]: [&str; 3],
) {
    let mut expected = shared_entries(frame.clone());
    for (key, value) in [("time", time), ("frames", frames), ("video", said)] {
        expected.insert(key.to_owned(), value.to_owned());
    }
    assert_eq!(video, &expected);
}

/// `srt render` writes the record into an MP4 and a GIF: `srt info` prints the numbered
/// frames' record (scene, size, renderer, srt version…) with the animation's time and frame
/// range and the video's frame count and rate; the MP4 keeps it in `moov/udta/©cmt` and still
/// reads as an MP4 of three samples, the GIF still decodes to three frames.
#[test]
fn rendered_videos_hold_the_record_that_srt_info_prints() {
    let dir = folder();
    render(dir.path(), &[], "v.png");
    let frame = info(dir.path(), "v_0001.png");
    for (key, value) in [
        ("srt version", env!("CARGO_PKG_VERSION")),
        ("scene", "teaser (built-in)"),
        ("backend", "cpu"),
        ("size", "32x18"),
        ("samples", "1"),
        ("time", "1.5"),
        ("frame", "1 of 0 to 2"),
    ] {
        assert_eq!(frame.get(key).map(String::as_str), Some(value), "{key}");
    }
    for video in ["v.mp4", "v.gif"] {
        render(dir.path(), &["--fps", "10"], video);
        let record = info(dir.path(), video);
        assert_video_record(
            &record,
            &frame,
            [
                "1.0 to 2.0",
                "0 to 2 of 0 to 2",
                "3 frames at 10 fps, rendered by srt render",
            ],
        );
        assert_eq!(record["scene"], "teaser (built-in)", "{video}");
        assert_eq!(record["size"], "32x18", "{video}");
    }

    let mp4 = std::fs::read(dir.path().join("v.mp4")).unwrap();
    let udta = mp4
        .windows(4)
        .position(|w| w == b"udta")
        .expect("a udta box");
    assert_eq!(
        &mp4[udta + 8..udta + 12],
        b"\xa9cmt",
        "the comment opens udta"
    );
    let reader = mp4::read_mp4(std::fs::File::open(dir.path().join("v.mp4")).unwrap())
        .expect("still an MP4");
    let track = reader.tracks().values().next().expect("a track");
    assert_eq!(track.sample_count(), 3);
    let mut decoder = gif::DecodeOptions::new()
        .read_info(std::fs::File::open(dir.path().join("v.gif")).unwrap())
        .expect("still a GIF");
    let mut frames = 0;
    while decoder.read_next_frame().expect("a frame").is_some() {
        frames += 1;
    }
    assert_eq!(frames, 3);
}

/// `srt encode` writes the joined frames' record: the first frame's shared entries, the time
/// and frame range from the first frame to the last, and the count and rate; EXR frames give
/// the same record (their channels' note is not the video's), and frames srt did not write give
/// a record that says so.
#[test]
fn encoded_videos_hold_the_joined_frames_record() {
    let dir = folder();
    render(dir.path(), &[], "f.png");
    render(dir.path(), &[], "f.exr");
    let frame = info(dir.path(), "f_0001.png");
    for (frames, video) in [
        (["f_0001.png", "f_0002.png"], "j.mp4"),
        (["f_0001.exr", "f_0002.exr"], "j.gif"),
    ] {
        srt_ok(
            &[&["encode"][..], &frames, &["-o", video, "--fps", "12"]].concat(),
            dir.path(),
        );
        assert_video_record(
            &info(dir.path(), video),
            &frame,
            [
                "1.5 to 2.0",
                "1 to 2 of 0 to 2",
                "2 frames at 12 fps, joined by srt encode",
            ],
        );
    }
    image::RgbImage::new(32, 18)
        .save(dir.path().join("plain.png"))
        .unwrap();
    srt_ok(&["encode", "plain.png", "-o", "p.gif"], dir.path());
    let record = info(dir.path(), "p.gif");
    assert_eq!(record["srt version"], env!("CARGO_PKG_VERSION"));
    assert!(
        record["video"].ends_with("joined by srt encode from frames without an srt record"),
        "{record:?}"
    );
    assert!(!record.contains_key("scene"), "{record:?}");
}

/// A video cut short, a file that only looks like one, and a video srt did not write: one clear
/// line naming the file and the reason, exit code 2, no panic.
#[test]
fn cut_foreign_and_unrecorded_videos_are_refused_clearly() {
    let dir = folder();
    for video in ["v.mp4", "v.gif"] {
        render(dir.path(), &[], video);
        let whole = std::fs::read(dir.path().join(video)).unwrap();
        let cut = format!("cut-{video}");
        std::fs::write(dir.path().join(&cut), &whole[..whole.len() / 2]).unwrap();
        assert_clean_failure(&srt(&["info", &cut], dir.path()), &[&cut, "cut short"]);
    }
    std::fs::write(dir.path().join("fake.mp4"), "no video at all").unwrap();
    assert_clean_failure(
        &srt(&["info", "fake.mp4"], dir.path()),
        &["fake.mp4", "nor an MP4 or GIF video"],
    );
    // An MP4 of nothing but a file type, an empty movie box and empty media data.
    let boxed = |kind: &[u8; 4], body: &[u8]| {
        [&(8 + body.len() as u32).to_be_bytes()[..], kind, body].concat()
    };
    let bare = [
        boxed(b"ftyp", b"isom"),
        boxed(b"moov", &[]),
        boxed(b"mdat", &[]),
    ]
    .concat();
    std::fs::write(dir.path().join("bare.mp4"), bare).unwrap();
    let mut gif = Vec::new();
    {
        // A whole GIF (its trailer written by into_inner) of one frame, without a comment.
        let mut encoder = gif::Encoder::new(&mut gif, 2, 2, &[]).unwrap();
        encoder
            .write_frame(&gif::Frame::from_rgb(2, 2, &[7; 12]))
            .unwrap();
        encoder.into_inner().unwrap();
    }
    std::fs::write(dir.path().join("bare.gif"), gif).unwrap();
    for bare in ["bare.mp4", "bare.gif"] {
        assert_clean_failure(&srt(&["info", bare], dir.path()), &[bare, "no srt record"]);
    }
}

//! Seeded mutation fuzzing of every loader: glTF, GLB, OBJ + MTL, PLY, STL and TOML scene files.
//!
//! Each target starts from small valid seed files (the fixtures, and a scene file) and loads
//! mutated copies: bit flips, byte insertions and deletions, truncation, duplicated tokens or
//! chunks, numbers swapped for huge, tiny, negative, NaN or infinite values, and (for binary
//! files) 32-bit words overwritten with extreme counts and floats. Every case must load, or fail
//! with one line of at most `MAX_MESSAGE_CHARS` characters, free of control characters, that
//! names the file; no loader may panic (a panic caught by the importer's guard counts as one).
//! A loaded model never exceeds the scene budget, and its warnings are bounded lines too.
//!
//! Environment variables:
//!
//! - `SRT_FUZZ_CASES=N`: cases per target (default 40, so that `cargo test` stays quick; a
//!   campaign of 20 000 per target takes about 10 s per target, see `docs/fuzzing.md`).
//! - `SRT_FUZZ_SEED=S`: the campaign's seed (default 8). A case is reproducible from the seed,
//!   the target and its number, all of which a failure prints, and the failing input is kept in
//!   the system's temporary folder under `srt-fuzz-failures/`.
//! - `SRT_FUZZ_VERBOSE=1`: print every refusal's message (to read what users would see).
//!
//! Each target prints a summary (cases loaded and refused, the slowest case) to the process's
//! stderr; no timing is asserted.

use std::io::Write as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use srt_scene::import::{ImportFailure, load_model};
use srt_scene::limits::MAX_SCENE_TRIANGLES;
use srt_scene::load_scene_file;
use srt_scene::message::MAX_MESSAGE_CHARS;

/// Cases per target when `SRT_FUZZ_CASES` is not set.
const DEFAULT_CASES: u64 = 40;
/// The campaign seed when `SRT_FUZZ_SEED` is not set.
const DEFAULT_SEED: u64 = 8;

/// Values that numbers in text files are swapped for.
const NUMBERS: [&str; 22] = [
    "0.9999999999999999",
    "0.5773502691896256",
    "1.0000000000000002",
    "-0.9999999999999999",
    "1e300",
    "-1e300",
    "3e38",
    "-3.5e38",
    "1e-300",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "-0",
    "65535",
    "4294967295",
    "4294967296",
    "2147483648",
    "99999999999999999999",
    "1e9",
];

/// 32-bit words that binary files get overwritten with: huge counts, extreme floats.
const WORDS: [u32; 10] = [
    0xffff_ffff,
    0x7fff_ffff,
    0x8000_0000,
    0x0001_0000,
    0x0000_0000,
    0x7f80_0000, // +inf
    0xff80_0000, // -inf
    0x7fc0_0000, // NaN
    0x7f7f_ffff, // f32::MAX
    0x0100_0000,
];

/// One loader under test: seed files copied into one folder, of which a case mutates one and
/// then loads a file.
struct Target {
    name: &'static str,
    /// Files copied into the working folder: (name there, contents).
    files: Vec<(String, Vec<u8>)>,
    /// Indices into `files` of those a case may mutate.
    mutated: Vec<usize>,
    /// What a case loads.
    loads: Loads,
}

/// What a case of a [`Target`] loads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Loads {
    /// The model file that was mutated (targets with several alternative seeds).
    MutatedModel,
    /// The model file with this index (its companions may have been mutated).
    Model(usize),
    /// The scene file with this index.
    Scene(usize),
}

impl Target {
    /// The file a case that mutated file `mutated` loads, and whether it is a scene file.
    fn loaded_file(&self, mutated: usize) -> (&str, bool) {
        match self.loads {
            Loads::MutatedModel => (&self.files[mutated].0, false),
            Loads::Model(index) => (&self.files[index].0, false),
            Loads::Scene(index) => (&self.files[index].0, true),
        }
    }
}

fn fixture(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A target over the fixtures `files`, mutating those with the indices in `mutated`.
fn target(name: &'static str, files: &[&str], mutated: &[usize], loads: Loads) -> Target {
    Target {
        name,
        files: files
            .iter()
            .map(|file| ((*file).to_owned(), fixture(file)))
            .collect(),
        mutated: mutated.to_vec(),
        loads,
    }
}

/// The scene file seed: every shape, a model with its material library and texture, a checker
/// and an image texture, and every table.
const SCENE: &str = r#"name = "fuzz"
[observer]
position = [0.0, -6.0, 1.0]
look_at = [0.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
fov_y_deg = 50.0
ct = 0.5
thrust = { proper_acceleration = [0.0, 0.1, 0.0], start = 0.25, duration = 2.0 }

[[light]]
position = [0.0, -6.0, 1.0]
temperature_k = 5800.0
strength = 0.5
carried = true

[[light]]
position = [2.0, -3.0, 4.0]
beta = [0.5773502691896256, 0.5773502691896256, 0.5773502691896256]
temperature_k = 5000.0
strength = 10.0

[render]
effects = "searchlight"
background = [0.1, 0.1, 0.2]
ambient = 0.2

[[object]]
name = "box"
shape = { type = "cube", size = 1.5, subdivisions = 3 }
texture = { type = "clock", rate = 1.0, offset = 0.0, dial = 12.0 }
beta = [0.9999999999999999, 0.0, 0.0]
offset = [-1.0, 0.0, 0.0]
rotate_deg = [0.0, 30.0, 0.0]
spin = { axis = [0.0, 0.0, 1.0], rate = 0.5, centre = [0.0, 0.0, 0.0] }

[[object]]
name = "ball"
shape = { type = "sphere", radius = 0.5, segments = 12 }
texture = { type = "frames", files = ["checker.png", "checker.png"], fps = 6.0 }
beta = [0.5773502691896256, 0.5773502691896256, 0.5773502691896256]
scale = [1.0, 2.0, 1.0]
translate = [0.0, 0.0, 1.0]
thrust = { proper_acceleration = [0.0, 0.0, 0.25], start = 0.0, duration = 4.0 }

[[object]]
name = "model"
shape = { type = "model", path = "cube.obj" }
fit = true
color = [0.8, 0.8, 0.8]
wireframe = 0.02
beta = [0.0, 0.0, -0.9999999999999999]
emission = { temperature_k = 3000.0, brightness = 1.0, blink = { period = 0.5, duty = 0.25 } }
"#;

fn gltf() -> Target {
    target("gltf", &["cube.gltf"], &[0], Loads::Model(0))
}

fn gltf_external() -> Target {
    let files = ["cube_external.gltf", "cube_external.bin"];
    target("gltf-external", &files, &[0, 0, 0, 1], Loads::Model(0))
}

fn glb() -> Target {
    target("glb", &["cube.glb"], &[0], Loads::Model(0))
}

fn obj_mtl() -> Target {
    let files = ["cube.obj", "cube.mtl", "checker.png"];
    target("obj", &files, &[0, 0, 0, 1, 2], Loads::Model(0))
}

fn ply() -> Target {
    let files = ["cube_ascii.ply", "cube_binary_le.ply", "cube_binary_be.ply"];
    target("ply", &files, &[0, 1, 2], Loads::MutatedModel)
}

fn stl() -> Target {
    let files = ["cube_ascii.stl", "cube_binary.stl"];
    target("stl", &files, &[0, 1], Loads::MutatedModel)
}

fn scene() -> Target {
    let mut scene = target(
        "scene",
        &["cube.obj", "cube.mtl", "checker.png"],
        &[],
        Loads::Scene(3),
    );
    scene
        .files
        .push(("scene.toml".to_owned(), SCENE.as_bytes().to_vec()));
    scene.mutated = vec![3];
    scene
}

/// Applies one to four random mutations to `bytes` (usually one, so that most cases get past
/// the syntax and into the loaders' checks); returns their names. Number swaps, which keep the
/// file's structure, are the most frequent.
fn mutate(bytes: &mut Vec<u8>, rng: &mut ChaCha8Rng) -> Vec<&'static str> {
    let mut applied = Vec::new();
    let count = *[1, 1, 1, 1, 1, 2, 2, 3, 4]
        .get(rng.random_range(0..9))
        .unwrap_or(&1);
    for _ in 0..count {
        let len = bytes.len();
        let at = |rng: &mut ChaCha8Rng| rng.random_range(0..=len);
        let kind = match rng.random_range(0..20) {
            0..=5 => 5,
            6..=8 => 6,
            9 | 10 => 0,
            11 => 1,
            12 => 2,
            13 => 3,
            14 | 15 => 4,
            _ => 7,
        };
        let name = match kind {
            0 if len > 0 => {
                let i = rng.random_range(0..len);
                bytes[i] ^= 1 << rng.random_range(0..8);
                "bit flip"
            }
            1 => {
                let byte = *[
                    b'\n', b'{', b'}', b'[', b'-', b'0', b'9', b' ', 0, 0xff, b'"',
                ]
                .get(rng.random_range(0..11))
                .unwrap_or(&b'x');
                bytes.insert(at(rng), byte);
                "byte insert"
            }
            2 if len > 0 => {
                bytes.remove(rng.random_range(0..len));
                "byte delete"
            }
            3 if len > 0 => {
                bytes.truncate(rng.random_range(0..len));
                "truncation"
            }
            4 if len > 0 => {
                let start = rng.random_range(0..len);
                let end = (start + rng.random_range(1..=64)).min(len);
                let chunk = bytes[start..end].to_vec();
                let copies = rng.random_range(1..=8);
                let insert = at(rng);
                for _ in 0..copies {
                    bytes.splice(insert..insert, chunk.iter().copied());
                }
                "chunk duplication"
            }
            5 => {
                if swap_number(bytes, rng) {
                    "number swap"
                } else {
                    continue;
                }
            }
            6 => {
                if duplicate_token(bytes, rng) {
                    "token duplication"
                } else {
                    continue;
                }
            }
            7 if len >= 4 => {
                let i = rng.random_range(0..=len - 4) & !3;
                let word = WORDS[rng.random_range(0..WORDS.len())];
                bytes[i..i + 4].copy_from_slice(&word.to_le_bytes());
                "word overwrite"
            }
            _ => continue,
        };
        applied.push(name);
    }
    applied
}

/// The byte ranges of the numbers (digits with signs, points and exponents) in `bytes`.
fn number_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let mut start = i;
            if start > 0 && bytes[start - 1] == b'-' {
                start -= 1;
            }
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'.') {
                i += 1;
            }
            spans.push((start, i));
        }
        i += 1;
    }
    spans
}

/// Replaces a random number in `bytes` by one of [`NUMBERS`]; `false` if there is none.
fn swap_number(bytes: &mut Vec<u8>, rng: &mut ChaCha8Rng) -> bool {
    let spans = number_spans(bytes);
    if spans.is_empty() {
        return false;
    }
    let (start, end) = spans[rng.random_range(0..spans.len())];
    let value = NUMBERS[rng.random_range(0..NUMBERS.len())];
    bytes.splice(start..end, value.bytes());
    true
}

/// Repeats a random whitespace-separated token (1 to 1000 times); `false` if there is none.
fn duplicate_token(bytes: &mut Vec<u8>, rng: &mut ChaCha8Rng) -> bool {
    let mut tokens = Vec::new();
    let mut start = None;
    for (i, b) in bytes.iter().enumerate() {
        match (b.is_ascii_whitespace(), start) {
            (false, None) => start = Some(i),
            (true, Some(s)) => {
                tokens.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    if tokens.is_empty() {
        return false;
    }
    let (s, e) = tokens[rng.random_range(0..tokens.len())];
    let token: Vec<u8> = bytes[s..e].iter().copied().chain([b' ']).collect();
    let copies = *[1, 2, 10, 1000].get(rng.random_range(0..4)).unwrap_or(&1);
    let repeated: Vec<u8> = token.repeat(copies);
    bytes.splice(e..e, repeated);
    true
}

/// What one case did.
enum Outcome {
    Loaded,
    /// Refused, with this message.
    Refused(String),
}

/// Loads `path` as `target` says; `Err` with what is wrong with the behaviour.
fn check(path: &Path, scene: bool) -> Result<Outcome, String> {
    let name = path
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let result = catch_unwind(AssertUnwindSafe(|| {
        if scene {
            load_scene_file(path)
                .map(|(_, _, warnings)| (warnings, 0))
                .map_err(|e| (e.to_string(), false))
        } else {
            load_model(path)
                .map(|model| {
                    let triangles = model.triangle_count();
                    (model.warnings, triangles)
                })
                .map_err(|e| {
                    let crashed = matches!(e.reason(), ImportFailure::Crashed(_));
                    (e.to_string(), crashed)
                })
        }
    }));
    let readable = |message: &str, what: &str| -> Result<(), String> {
        if message.chars().count() > MAX_MESSAGE_CHARS {
            return Err(format!(
                "{what} longer than {MAX_MESSAGE_CHARS} characters: {message}"
            ));
        }
        if message.chars().any(char::is_control) {
            return Err(format!("{what} has control characters: {message:?}"));
        }
        Ok(())
    };
    match result {
        Err(_) => Err("the loader panicked".to_owned()),
        Ok(Err((message, true))) => Err(format!("a parser panicked (caught): {message}")),
        Ok(Err((message, false))) => {
            readable(&message, "the error")?;
            if !message.contains(&name) {
                return Err(format!("the error does not name {name}: {message}"));
            }
            Ok(Outcome::Refused(message))
        }
        Ok(Ok((warnings, triangles))) => {
            if triangles > MAX_SCENE_TRIANGLES {
                return Err(format!("{triangles} triangles loaded"));
            }
            for warning in &warnings {
                readable(warning, "a warning")?;
            }
            Ok(Outcome::Loaded)
        }
    }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Runs the campaign for `target`; panics with the first failure.
fn campaign(target: &Target) {
    let cases = env_number("SRT_FUZZ_CASES", DEFAULT_CASES);
    let seed = env_number("SRT_FUZZ_SEED", DEFAULT_SEED);
    let verbose = std::env::var_os("SRT_FUZZ_VERBOSE").is_some_and(|v| v == "1");
    let dir = tempfile::tempdir().expect("a temporary folder");
    let write_all = || {
        for (name, bytes) in &target.files {
            std::fs::write(dir.path().join(name), bytes).expect("writing a seed file");
        }
    };
    write_all();
    let (loaded_name, is_scene) = target.loaded_file(0);
    if let Err(problem) = check(&dir.path().join(loaded_name), is_scene).and_then(|outcome| {
        matches!(outcome, Outcome::Loaded)
            .then_some(())
            .ok_or_else(|| "refused".to_owned())
    }) {
        panic!(
            "the unmutated seed of fuzz target {} does not load: {problem}",
            target.name
        );
    }
    let started = Instant::now();
    let (mut loaded, mut refused) = (0u64, 0u64);
    let mut slowest = (Duration::ZERO, 0);
    for case in 0..cases {
        let case_seed = seed ^ (case.wrapping_mul(0x9e37_79b9_7f4a_7c15)) ^ hash(target.name);
        let mut rng = ChaCha8Rng::seed_from_u64(case_seed);
        let which = target.mutated[rng.random_range(0..target.mutated.len())];
        let (mutated_name, seed_bytes) = &target.files[which];
        let mut bytes = seed_bytes.clone();
        let mutations = mutate(&mut bytes, &mut rng);
        let mutated_path = dir.path().join(mutated_name);
        std::fs::write(&mutated_path, &bytes).expect("writing a mutated file");
        let (loaded_name, is_scene) = target.loaded_file(which);
        let start = Instant::now();
        let outcome = check(&dir.path().join(loaded_name), is_scene);
        let took = start.elapsed();
        if took > slowest.0 {
            slowest = (took, case);
        }
        match outcome {
            Ok(Outcome::Loaded) => loaded += 1,
            Ok(Outcome::Refused(message)) => {
                refused += 1;
                if verbose {
                    let _ = writeln!(
                        std::io::stderr(),
                        "{} case {case} {mutations:?}: {message}",
                        target.name
                    );
                }
            }
            Err(problem) => {
                let kept = keep_failure(target.name, case, mutated_name, &bytes);
                panic!(
                    "fuzz target {} case {case} (SRT_FUZZ_SEED={seed}): {problem}\n\
                     mutations of {mutated_name}: {mutations:?}; input kept as {}",
                    target.name,
                    kept.display()
                );
            }
        }
        // Restore the seed for the next case.
        std::fs::write(&mutated_path, seed_bytes).expect("restoring a seed file");
    }
    let _ = writeln!(
        std::io::stderr(),
        "fuzz {}: {cases} cases (seed {seed}) in {:.2?}: {loaded} loaded, {refused} refused \
         cleanly; slowest case {} took {:.2?}",
        target.name,
        started.elapsed(),
        slowest.1,
        slowest.0
    );
}

/// A stable hash of a target's name, so that targets see different cases.
fn hash(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    })
}

/// Saves a failing input where it survives the test; returns its path.
fn keep_failure(target: &str, case: u64, name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join("srt-fuzz-failures");
    let path = dir.join(format!("{target}-{case}-{name}"));
    let _ = std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&path, bytes));
    path
}

#[test]
fn fuzz_gltf() {
    campaign(&gltf());
}

#[test]
fn fuzz_gltf_with_external_buffer() {
    campaign(&gltf_external());
}

#[test]
fn fuzz_glb() {
    campaign(&glb());
}

#[test]
fn fuzz_obj_and_mtl() {
    campaign(&obj_mtl());
}

#[test]
fn fuzz_ply() {
    campaign(&ply());
}

#[test]
fn fuzz_stl() {
    campaign(&stl());
}

#[test]
fn fuzz_scene_files() {
    campaign(&scene());
}

#[test]
fn mutations_change_the_seed_and_are_reproducible() {
    let seed = fixture("cube_ascii.stl");
    let mutated = |case: u64| {
        let mut rng = ChaCha8Rng::seed_from_u64(case);
        let mut bytes = seed.clone();
        let names = mutate(&mut bytes, &mut rng);
        (bytes, names)
    };
    let changed = (0..50).filter(|&case| mutated(case).0 != seed).count();
    assert!(changed >= 45, "only {changed} of 50 cases changed the seed");
    assert_eq!(mutated(7), mutated(7));
    let mut numbers = b"v 1.5 -2 3e4".to_vec();
    assert_eq!(number_spans(&numbers), [(2, 5), (6, 8), (9, 12)]);
    assert!(swap_number(&mut numbers, &mut ChaCha8Rng::seed_from_u64(1)));
    assert_ne!(numbers, b"v 1.5 -2 3e4");
}

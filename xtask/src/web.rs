//! `cargo xtask web`: builds the web page into `target/web/` (the page's files from
//! `crates/srt-web/web/`, the wasm module and its JavaScript glue, nothing from elsewhere),
//! serves it on localhost (`--serve`), and tests it in headless Chromium (`--test`): the embed
//! page of several scenes, on WebGPU and on the CPU path, screenshot and compared with the exact
//! CPU reference at the same size, with `cargo xtask validate`'s tolerance; `--time` times the
//! page's CPU worker (this build's, and others' given with `--page`).
//!
//! The wasm is built with Debian's wasm toolchain (`rustc-web`, `cargo-web`, `rust-web-src`,
//! `lld-16`: its standard library is built from source with `-Zbuild-std`), so the project's own
//! rustup toolchain needs no wasm target; `SRT_WEB_CARGO`, `SRT_WEB_RUSTC` and
//! `SRT_WEB_LINKER` name another. The JavaScript glue comes from `wasm-bindgen-cli` of the
//! version in Cargo.lock.

mod devtools;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};
use srt_scene::SceneSource;
use srt_trace::compare::compare;
use srt_trace::{RenderSettings, Tracer};
use srt_web::parse_query;

use crate::validate::{EDGE_MARGIN, MAX_MISMATCH, TOLERANCE};
use devtools::Browser;

/// Where the page is built, below the workspace.
pub const OUT_DIR: &str = "target/web";

/// The page's own files (HTML, JavaScript, CSS), below the workspace.
const PAGE_DIR: &str = "crates/srt-web/web";

/// The browser test's cases: a scene and more of the address, at [`TEST_SIZE`].
const TEST_CASES: [&str; 5] = [
    "scene=fig7",
    // One mesh of 1 920 000 triangles: uploaded in slices where WebGPU's storage bindings are
    // the default 128 MiB.
    "scene=fig10-cube200&set=object.cube.shape.subdivisions%3D400",
    "scene=teaser&effects=searchlight",
    "scene=rolling-wheel",
    // A full-sky embed: the ray tracer on WebGPU, every pixel in the equirectangular projection.
    "scene=rolling-wheel&projection=equirectangular",
];

/// The cases on which `backend=auto` weighs WebGPU against the CPU tracer: one mesh of
/// 1.92 M triangles (a CPU frame builds its tracer, WebGPU keeps its upload) and the teaser.
/// On SwiftShader WebGPU is the faster on both (docs/web.md lists eleven scenes), so the rule's
/// CPU side is checked by srt-gpu's unit tests and the viewer's UI test, and the CPU path's
/// pictures by the `backend=cpu` cases.
const AUTO_CASES: [&str; 2] = [TEST_CASES[1], TEST_CASES[2]];

/// The canvas size of the browser test, in pixels.
const TEST_SIZE: (u32, u32) = (320, 180);

/// How long a page may take to draw its first frame.
const FIRST_FRAME_TIMEOUT: Duration = Duration::from_secs(300);

/// A program the build needs, and how to get it.
struct Tool {
    path: PathBuf,
    install: &'static str,
}

fn tool(variable: &str, default: &str, install: &'static str) -> Tool {
    Tool {
        path: std::env::var_os(variable).map_or_else(|| PathBuf::from(default), PathBuf::from),
        install,
    }
}

const DEBIAN_WASM: &str =
    "apt-get install rustc-web cargo-web rust-web-src lld-16 (Debian's wasm toolchain)";

/// Builds the page into `workspace/target/web` and returns that folder.
///
/// # Errors
/// A missing tool (the message says how to install it), or a failed build.
pub fn build(workspace: &Path) -> anyhow::Result<PathBuf> {
    let cargo = tool("SRT_WEB_CARGO", "/usr/bin/cargo", DEBIAN_WASM);
    let rustc = tool("SRT_WEB_RUSTC", "/usr/bin/rustc", DEBIAN_WASM);
    let linker = tool(
        "SRT_WEB_LINKER",
        "/usr/lib/llvm-16/bin/wasm-ld",
        DEBIAN_WASM,
    );
    for needed in [&cargo, &rustc, &linker] {
        if !needed.path.is_file() {
            bail!("{} is missing: {}", needed.path.display(), needed.install);
        }
    }
    let bindgen_version = locked_version(workspace, "wasm-bindgen")?;
    check_bindgen(&bindgen_version)?;

    let build_dir = workspace.join("target/web-build");
    let started = Instant::now();
    let status = Command::new(&cargo.path)
        .current_dir(workspace)
        .args([
            "build",
            "--release",
            "--locked",
            "-Zbuild-std=std,panic_abort",
        ])
        .args([
            "--target",
            "wasm32-unknown-unknown",
            "-p",
            "srt-web",
            "--target-dir",
        ])
        .arg(&build_dir)
        .env("RUSTC", &rustc.path)
        .env("RUSTC_BOOTSTRAP", "1")
        .env("CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER", &linker.path)
        // getrandom (through rand) reaches the browser's crypto; the page's own crates build
        // without warnings, as clippy holds the native build to.
        .env(
            "RUSTFLAGS",
            "--cfg getrandom_backend=\"wasm_js\" -D warnings",
        )
        .env("CARGO_PROFILE_RELEASE_DEBUG", "false")
        .env_remove("CARGO")
        .env_remove("RUSTC_WRAPPER")
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .status()
        .with_context(|| format!("cannot run {}", cargo.path.display()))?;
    if !status.success() {
        bail!("the wasm build of srt-web failed ({status})");
    }
    let out = workspace.join(OUT_DIR);
    if out.exists() {
        std::fs::remove_dir_all(&out).with_context(|| format!("cannot empty {}", out.display()))?;
    }
    let wasm = build_dir.join("wasm32-unknown-unknown/release/srt_web.wasm");
    let status = Command::new("wasm-bindgen")
        .args(["--target", "web", "--no-typescript", "--out-dir"])
        .arg(&out)
        .arg(&wasm)
        .status()
        .context("cannot run wasm-bindgen")?;
    if !status.success() {
        bail!("wasm-bindgen failed on {} ({status})", wasm.display());
    }
    for entry in std::fs::read_dir(workspace.join(PAGE_DIR))? {
        let path = entry?.path();
        let name = path.file_name().context("a page file")?;
        std::fs::copy(&path, out.join(name))
            .with_context(|| format!("cannot copy {}", path.display()))?;
    }
    let size = std::fs::metadata(out.join("srt_web_bg.wasm"))?.len();
    println!(
        "built the page into {} in {:.0} s (wasm {:.1} MB)",
        out.display(),
        started.elapsed().as_secs_f64(),
        size as f64 / 1e6
    );
    Ok(out)
}

/// The version of `package` in the workspace's Cargo.lock.
fn locked_version(workspace: &Path, package: &str) -> anyhow::Result<String> {
    let lock = std::fs::read_to_string(workspace.join("Cargo.lock"))?;
    let name_line = format!("name = \"{package}\"");
    let mut lines = lock.lines();
    while let Some(line) = lines.next() {
        if line == name_line
            && let Some(version) = lines.next().and_then(|l| l.strip_prefix("version = \""))
        {
            return Ok(version.trim_end_matches('"').to_owned());
        }
    }
    bail!("Cargo.lock has no {package}")
}

/// Refuses a missing `wasm-bindgen` or one of another version than the crate's.
fn check_bindgen(version: &str) -> anyhow::Result<()> {
    let install = format!("cargo install wasm-bindgen-cli --version ={version}");
    let output = Command::new("wasm-bindgen")
        .arg("--version")
        .output()
        .with_context(|| format!("wasm-bindgen is missing: {install}"))?;
    let found = String::from_utf8_lossy(&output.stdout);
    if found.split_whitespace().nth(1) != Some(version) {
        bail!(
            "wasm-bindgen {} is installed, the crate is {version}: {install}",
            found.trim()
        );
    }
    Ok(())
}

/// Serves `root` on 127.0.0.1:`port` (0: any free port) from a background thread; returns the
/// address.
///
/// # Errors
/// When the port cannot be opened.
pub fn serve(root: &Path, port: u16) -> anyhow::Result<String> {
    let server = tiny_http::Server::http(("127.0.0.1", port))
        .map_err(|e| anyhow::anyhow!("cannot serve on port {port}: {e}"))?;
    let address = format!("http://{}/", server.server_addr());
    let root = root.to_path_buf();
    std::thread::spawn(move || {
        for request in server.incoming_requests() {
            let _ = respond(&root, request);
        }
    });
    Ok(address)
}

/// Answers one request with a file of `root` (no folders above it), or 404.
fn respond(root: &Path, request: tiny_http::Request) -> std::io::Result<()> {
    let path = request.url().split(['?', '#']).next().unwrap_or("/");
    let relative = path.trim_start_matches('/');
    let relative = if relative.is_empty() {
        "index.html"
    } else {
        relative
    };
    let file = root.join(relative);
    let inside = !relative
        .split('/')
        .any(|part| part == ".." || part.is_empty());
    match std::fs::read(&file) {
        Ok(bytes) if inside => {
            let kind = match file.extension().and_then(|e| e.to_str()) {
                Some("html") => "text/html; charset=utf-8",
                Some("js") => "text/javascript; charset=utf-8",
                Some("css") => "text/css; charset=utf-8",
                Some("wasm") => "application/wasm",
                _ => "application/octet-stream",
            };
            let header =
                tiny_http::Header::from_bytes("Content-Type", kind).expect("a valid header");
            request.respond(tiny_http::Response::from_data(bytes).with_header(header))
        }
        _ => request.respond(tiny_http::Response::from_string("not found").with_status_code(404)),
    }
}

/// Serves the built page until the process is stopped.
///
/// # Errors
/// When the port cannot be opened.
pub fn serve_forever(root: &Path, port: u16) -> anyhow::Result<()> {
    let address = serve(root, port)?;
    println!("serving {} at {address} (Ctrl-C stops)", root.display());
    println!("embed example: {address}index.html?scene=fig7&width=320&height=180&embed=1");
    loop {
        std::thread::park();
    }
}

/// The browser test: every case of [`TEST_CASES`] on WebGPU and on the CPU path, compared with
/// the exact CPU reference.
///
/// # Errors
/// A case whose picture differs beyond the tolerance, a page that reports an error or never
/// draws, or no browser.
pub fn test(workspace: &Path, root: &Path) -> anyhow::Result<()> {
    let address = serve(root, 0)?;
    let out = workspace.join("target/web-test");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out)?;
    let profile = out.join("profile");
    let _ = std::fs::remove_dir_all(&profile);
    let executable = devtools::find_browser()?;
    let mut browser = Browser::start(&executable, &profile, &out.join("chromium.log"))?;
    let (width, height) = TEST_SIZE;
    let mut failures = Vec::new();
    for case in TEST_CASES {
        let reference = reference_image(case, width, height)?;
        for backend in ["webgpu", "cpu"] {
            let query = format!("{case}&width={width}&height={height}&embed=1&backend={backend}");
            let started = Instant::now();
            browser.open(&format!("{address}index.html?{query}"))?;
            let title = browser.wait_for_title(
                |title| title.starts_with("srt ready") || title.starts_with("srt error"),
                FIRST_FRAME_TIMEOUT,
            )?;
            println!(
                "web {query}: drawn in {:.1} s",
                started.elapsed().as_secs_f64()
            );
            let expected = format!("srt ready ({backend})");
            if title != expected {
                let console = browser.console().join("\n  ");
                failures.push(format!(
                    "{query}: the page says {title:?}, not {expected:?}; its console:\n  {console}"
                ));
                println!("web {query} FAIL ({title})");
                continue;
            }
            let png = browser.screenshot((0.0, 0.0), width, height)?;
            if let Some(failure) = check_picture(&out, &query, &png, &reference)? {
                failures.push(failure);
            }
        }
    }
    failures.extend(check_the_faster_draws(&mut browser, &address, &out)?);
    failures.extend(check_controls(&mut browser, &address, &out)?);
    failures.extend(check_model_drop(&mut browser, &address, &out)?);
    if !failures.is_empty() {
        bail!(
            "the web page differs from the CPU reference:\n{}",
            failures.join("\n")
        );
    }
    println!(
        "web: all {} pages, auto's {} weighed pages, the controls' picture and a dropped model's \
         equal the CPU reference",
        TEST_CASES.len() * 2,
        AUTO_CASES.len()
    );
    Ok(())
}

/// Compares the screenshot `png` of the page `query` with `reference`, saves it in `out`, and
/// prints the verdict; returns the failure, if it fails.
fn check_picture(
    out: &Path,
    query: &str,
    png: &[u8],
    reference: &srt_trace::RenderedImage,
) -> anyhow::Result<Option<String>> {
    let file = out.join(format!("{}.png", query.replace(['&', '=', ',', ' '], "_")));
    std::fs::write(&file, png)?;
    let shot = image::load_from_memory(png)?.to_rgb8();
    if shot.dimensions() != (reference.width, reference.height) {
        return Ok(Some(format!(
            "{query}: a {:?} screenshot",
            shot.dimensions()
        )));
    }
    let pixels: Vec<[u8; 3]> = shot.pixels().map(|p| p.0).collect();
    let mismatch = compare(reference, &pixels, TOLERANCE, EDGE_MARGIN);
    let ok = mismatch.fraction() <= MAX_MISMATCH;
    println!(
        "web {query} mismatch={:.6} max={} {}",
        mismatch.fraction(),
        mismatch.max_difference,
        if ok { "ok" } else { "FAIL" }
    );
    Ok((!ok).then(|| {
        format!(
            "{query}: mismatch {:.6} > {MAX_MISMATCH} (screenshot {})",
            mismatch.fraction(),
            file.display()
        )
    }))
}

/// `backend=auto` on a software adapter draws by the faster of WebGPU and the CPU tracer
/// (srt-gpu's `exact_path`), both at the canvas's full size: on [`AUTO_CASES`], the first
/// frame (which uploads the scene) is WebGPU's and is not weighed, the second is WebGPU's and
/// timed, before the third the worker measures the CPU; the third must be drawn by the path the
/// rule picks from the times it was chosen on, and equal the reference.
fn check_the_faster_draws(
    browser: &mut Browser,
    address: &str,
    out: &Path,
) -> anyhow::Result<Vec<String>> {
    let (width, height) = TEST_SIZE;
    let mut failures = Vec::new();
    for case in AUTO_CASES {
        let query = format!("{case}&width={width}&height={height}&embed=1");
        browser.open(&format!("{address}index.html?{query}"))?;
        browser.wait_for_title(|title| title == "srt ready (webgpu)", FIRST_FRAME_TIMEOUT)?;
        let mut shown = serde_json::Value::Null;
        for frame in 2..=3 {
            browser.evaluate("window.dispatchEvent(new Event('resize')), true")?;
            shown = browser.wait_for(
                "[Number(document.body.dataset.frames), document.body.dataset.drawnBy, \
                 document.body.dataset.choice || null, document.body.dataset.paths || null, \
                 Number(document.body.dataset.frameMs)]",
                |value| value[0].as_u64().unwrap_or(0) >= frame,
                FIRST_FRAME_TIMEOUT,
            )?;
            if frame == 2 {
                // The first WebGPU time on record is the second frame's own: the first
                // frame's upload was not counted (nor averaged in).
                let paths: serde_json::Value =
                    serde_json::from_str(shown[3].as_str().unwrap_or("null")).unwrap_or_default();
                let (on_record, second) = (paths["webgpu_ms"].as_f64(), shown[4].as_f64());
                if on_record
                    .zip(second)
                    .is_none_or(|(a, b)| (a - b).abs() > 0.01)
                {
                    failures.push(format!(
                        "auto {query}: after the second frame ({second:?} ms) WebGPU's time on \
                         record is {on_record:?} ms; the upload frame was counted"
                    ));
                }
            }
        }
        println!("web auto {query}: {shown}");
        let choice: serde_json::Value =
            serde_json::from_str(shown[2].as_str().unwrap_or("null")).unwrap_or_default();
        let expected = match (choice["webgpu_ms"].as_f64(), choice["cpu_ms"].as_f64()) {
            (Some(gpu), Some(cpu)) if cpu * srt_gpu::exact_path::MARGIN < gpu => "cpu",
            (Some(_), Some(_)) => "webgpu",
            _ => {
                failures.push(format!(
                    "auto {query}: the third frame was chosen without both paths' times \
                     ({choice}); the page did not weigh, or counted the upload"
                ));
                continue;
            }
        };
        if choice["path"] != expected || shown[1] != expected {
            failures.push(format!(
                "auto {query}: the rule picks {expected} from {choice}, but the page drew by {}",
                shown[1]
            ));
        }
        let png = browser.screenshot((0.0, 0.0), width, height)?;
        let reference = reference_image(case, width, height)?;
        failures.extend(check_picture(
            out,
            &format!("auto {query}"),
            &png,
            &reference,
        )?);
    }
    Ok(failures)
}

/// The page with its controls reacts to them: on the teaser, the velocity, effect and time
/// controls are moved as a person moves them, and the next frame (by whichever path draws) must equal
/// the CPU reference of the address the page reports drawing.
fn check_controls(browser: &mut Browser, address: &str, out: &Path) -> anyhow::Result<Vec<String>> {
    let (width, height) = TEST_SIZE;
    browser.open(&format!(
        "{address}index.html?scene=teaser&width={width}&height={height}"
    ))?;
    browser.wait_for_title(|title| title == "srt ready (webgpu)", FIRST_FRAME_TIMEOUT)?;
    let frames = browser.evaluate("Number(document.body.dataset.frames)")?;
    browser.evaluate(
        "(() => {
            const set = (id, value, kind) => {
                const control = document.getElementById(id);
                if (control.type === 'checkbox') control.checked = value; else control.value = value;
                control.dispatchEvent(new Event(kind));
            };
            set('set-velocity', true, 'change');
            set('speed', '0.8', 'input');
            set('effects', 'searchlight', 'change');
            set('time', '0.5', 'input');
            return true;
        })()",
    )?;
    let frames = frames.as_u64().unwrap_or(0);
    // The first frame after the last change shows all of them.
    let shown = browser.wait_for(
        "[Number(document.body.dataset.frames), document.body.dataset.query]",
        |value| {
            value[0].as_u64().unwrap_or(0) > frames
                && value[1]
                    .as_str()
                    .is_some_and(|q| q.contains("effects=searchlight") && q.contains("time=0.5"))
        },
        FIRST_FRAME_TIMEOUT,
    )?;
    let query = shown[1].as_str().unwrap_or_default().to_owned();
    let at = canvas_corner(browser)?;
    let png = browser.screenshot(at, width, height)?;
    let reference = reference_image(&query, width, height)?;
    let mut failures: Vec<String> =
        check_picture(out, &format!("controls {query}"), &png, &reference)?
            .into_iter()
            .collect();
    // Play runs the observer's clock: frames keep coming, each at a later time.
    let clock = "(() => { const q = new URLSearchParams(document.body.dataset.query); \
                 return [Number(document.body.dataset.frames), Number(q.get('time'))]; })()";
    let before = browser.evaluate(clock)?;
    browser.evaluate("document.getElementById('play').click(), true")?;
    let later = browser.wait_for(
        clock,
        |now| {
            now[0].as_u64().unwrap_or(0) >= before[0].as_u64().unwrap_or(0) + 2
                && now[1].as_f64() > before[1].as_f64()
        },
        FIRST_FRAME_TIMEOUT,
    );
    browser.evaluate("document.getElementById('play').click(), true")?;
    match later {
        Ok(now) => println!(
            "web Play: (frames, ct) {before} -> {now}, paths {}",
            browser.evaluate("document.body.dataset.paths || null")?
        ),
        Err(error) => failures.push(format!("Play did not run the clock: {error}")),
    }
    Ok(failures)
}

/// Drops `name` made of `bytes` on the page, as a person drops a file from their desktop.
fn drop_file(browser: &mut Browser, name: &str, bytes: &[u8]) -> anyhow::Result<()> {
    use base64::Engine as _;
    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
    browser.evaluate(&format!(
        "(() => {{
            const bytes = Uint8Array.from(atob('{data}'), (c) => c.charCodeAt(0));
            const transfer = new DataTransfer();
            transfer.items.add(new File([bytes], {name:?}));
            window.dispatchEvent(new DragEvent('drop', {{ dataTransfer: transfer, cancelable: true }}));
            return true;
        }})()"
    ))?;
    Ok(())
}

/// A model dropped on the page is shown as `srt render MODEL` shows the file, and a broken one
/// is refused with the file named while the model shown stays.
fn check_model_drop(
    browser: &mut Browser,
    address: &str,
    out: &Path,
) -> anyhow::Result<Vec<String>> {
    let (width, height) = TEST_SIZE;
    let mut failures = Vec::new();
    browser.open(&format!(
        "{address}index.html?scene=fig7&width={width}&height={height}"
    ))?;
    browser.wait_for_title(|title| title == "srt ready (webgpu)", FIRST_FRAME_TIMEOUT)?;
    let spider = srt_scene::assets::embedded("models/spider.stl").context("the spider")?;
    let file = out.join("spider.stl");
    std::fs::write(&file, spider)?;
    drop_file(browser, "spider.stl", spider)?;
    let shown = browser.wait_for(
        "document.body.dataset.query",
        |query| query.as_str().is_some_and(|q| !q.contains("scene=")),
        FIRST_FRAME_TIMEOUT,
    )?;
    let query = shown.as_str().unwrap_or_default().to_owned();
    let reference = reference_of(&file.display().to_string(), &query, width, height)?;
    let at = canvas_corner(browser)?;
    let png = browser.screenshot(at, width, height)?;
    failures.extend(check_picture(
        out,
        &format!("dropped spider.stl {query}"),
        &png,
        &reference,
    )?);

    drop_file(browser, "broken.glb", b"not a glb")?;
    let status = browser.wait_for(
        "document.getElementById('status').textContent",
        |text| text.as_str().is_some_and(|t| t.contains("broken.glb")),
        Duration::from_secs(30),
    )?;
    let status = status.as_str().unwrap_or_default().to_owned();
    println!("web dropped broken.glb: the page says {status:?}");
    if !status.contains("glTF") {
        failures.push(format!("a broken glb: the page says {status:?}"));
    }
    let png = browser.screenshot(at, width, height)?;
    failures.extend(check_picture(
        out,
        "after broken.glb, still spider.stl",
        &png,
        &reference,
    )?);
    Ok(failures)
}

/// Where the page's canvas is, in CSS pixels from the page's top-left corner.
fn canvas_corner(browser: &mut Browser) -> anyhow::Result<(f64, f64)> {
    let corner = browser.evaluate(
        "(() => { const r = document.getElementById('canvas').getBoundingClientRect(); \
         return [r.left, r.top]; })()",
    )?;
    Ok((
        corner[0].as_f64().unwrap_or(0.0),
        corner[1].as_f64().unwrap_or(0.0),
    ))
}

/// Saves a screenshot of the whole page at `index.html?query` (1280×800 CSS pixels) to `path`
/// once its first frame is drawn.
///
/// # Errors
/// No browser, a page that reports an error, or an unwritable `path`.
pub fn screenshot(workspace: &Path, root: &Path, query: &str, path: &Path) -> anyhow::Result<()> {
    let address = serve(root, 0)?;
    let out = workspace.join("target/web-test");
    std::fs::create_dir_all(&out)?;
    let profile = out.join("profile-screenshot");
    let _ = std::fs::remove_dir_all(&profile);
    let executable = devtools::find_browser()?;
    let mut browser = Browser::start(&executable, &profile, &out.join("chromium-screenshot.log"))?;
    browser.set_viewport(1280, 800)?;
    browser.open(&format!("{address}index.html?{query}"))?;
    let title = browser.wait_for_title(
        |title| title.starts_with("srt ready") || title.starts_with("srt error"),
        FIRST_FRAME_TIMEOUT,
    )?;
    if !title.starts_with("srt ready") {
        bail!(
            "{title}; the page's console:\n{}",
            browser.console().join("\n")
        );
    }
    std::fs::write(path, browser.screenshot((0.0, 0.0), 1280, 800)?)
        .with_context(|| format!("cannot write {}", path.display()))?;
    println!("wrote {} ({title})", path.display());
    Ok(())
}

/// The scenes whose CPU frames `--time` times (issue 69: the web worker before and after).
const TIMED_SCENES: [&str; 2] = ["flythrough", "teaser"];

/// Frames timed after each scene's first.
const TIMED_FRAMES: usize = 5;

/// Times the CPU worker of each page in `pages` (built page directories) on [`TIMED_SCENES`]
/// in headless Chromium: the first frame of a fresh page load (scene and tracer built) and the
/// median of [`TIMED_FRAMES`] more, each drawn as the time control moves (the tracer's BVHs
/// kept); the times are the page's own (`data-frame-ms`: the worker's render, the transfer and
/// the canvas's update). Prints one line per page and scene.
///
/// # Errors
/// When a page cannot be served, loaded, or says it failed.
pub fn time_cpu_frames(workspace: &Path, pages: &[PathBuf]) -> anyhow::Result<()> {
    let out = workspace.join("target/web-test");
    std::fs::create_dir_all(&out)?;
    let executable = devtools::find_browser()?;
    for page in pages {
        let address = serve(page, 0)?;
        let profile = out.join("profile-time");
        let _ = std::fs::remove_dir_all(&profile);
        let mut browser = Browser::start(&executable, &profile, &out.join("chromium-time.log"))?;
        browser.set_viewport(1280, 800)?;
        for scene in TIMED_SCENES {
            browser.open(&format!(
                "{address}index.html?scene={scene}&width=1280&height=720&backend=cpu"
            ))?;
            let title = browser.wait_for_title(
                |title| title.starts_with("srt ready") || title.starts_with("srt error"),
                FIRST_FRAME_TIMEOUT,
            )?;
            if title != "srt ready (cpu)" {
                bail!("{}: {scene}: {title}", page.display());
            }
            let frame = "[Number(document.body.dataset.frames), \
                         Number(document.body.dataset.frameMs), \
                         document.getElementById('canvas').width, \
                         document.getElementById('canvas').height]";
            let first = browser.evaluate(frame)?;
            let mut later = Vec::with_capacity(TIMED_FRAMES);
            for step in 1..=TIMED_FRAMES {
                let frames = browser.evaluate("Number(document.body.dataset.frames)")?;
                browser.evaluate(&format!(
                    "(() => {{ const time = document.getElementById('time'); \
                     time.value = '{}'; time.dispatchEvent(new Event('input')); return true; }})()",
                    0.1 * step as f64
                ))?;
                let drawn = browser.wait_for(
                    frame,
                    |value| value[0].as_u64() > frames.as_u64(),
                    FIRST_FRAME_TIMEOUT,
                )?;
                later.push(drawn[1].as_f64().unwrap_or(f64::NAN));
            }
            later.sort_by(f64::total_cmp);
            println!(
                "web-time page={} scene={scene} canvas={}x{} first_ms={:.1} frame_ms={:.1} frames_ms={later:.1?}",
                page.display(),
                first[2],
                first[3],
                first[1].as_f64().unwrap_or(f64::NAN),
                later[later.len() / 2],
            );
        }
    }
    Ok(())
}

/// The exact CPU picture of the page address `case` at `width`×`height`: the scene loaded with
/// the address's values as `srt render` loads it with the same options.
fn reference_image(
    case: &str,
    width: u32,
    height: u32,
) -> anyhow::Result<srt_trace::RenderedImage> {
    let page = parse_query(case)?;
    reference_of(
        page.scene.as_deref().unwrap_or("teaser"),
        case,
        width,
        height,
    )
}

/// The exact CPU picture of the scene argument `argument` (a built-in scene's name or a file)
/// with the values of the page address `query`, as `srt render ARGUMENT` with the same options
/// renders it.
fn reference_of(
    argument: &str,
    query: &str,
    width: u32,
    height: u32,
) -> anyhow::Result<srt_trace::RenderedImage> {
    let page = parse_query(query)?;
    let loaded = SceneSource::resolve(argument)?.load_with(&page.overrides)?;
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    Ok(Tracer::new(&loaded.scene).render(settings, &|_| {}))
}

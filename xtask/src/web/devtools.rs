//! A headless Chromium driven over the Chrome DevTools Protocol: started with a debugging port,
//! reached over its WebSocket (tungstenite), and asked for the few commands the browser test
//! needs — open a page, read its title, capture a screenshot of a rectangle.

use std::io::{BufRead as _, BufReader};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};
use base64::Engine as _;
use serde_json::{Value, json};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

/// The browsers tried, in order, when `SRT_CHROMIUM` names none.
const BROWSERS: [&str; 3] = ["chromium", "chromium-browser", "google-chrome"];

/// How long one DevTools command may take.
const COMMAND_TIMEOUT: Duration = Duration::from_secs(120);

/// A running headless browser with one page open.
pub struct Browser {
    process: Child,
    socket: WebSocket<MaybeTlsStream<TcpStream>>,
    session: String,
    next_id: u64,
    /// The page's console messages and uncaught exceptions since the last [`Browser::open`].
    console: Vec<String>,
}

/// The browser executable: `SRT_CHROMIUM`, else the first of [`BROWSERS`] on the `PATH`.
///
/// # Errors
/// When there is none.
pub fn find_browser() -> anyhow::Result<PathBuf> {
    if let Some(path) = std::env::var_os("SRT_CHROMIUM") {
        return Ok(PathBuf::from(path));
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    BROWSERS
        .iter()
        .flat_map(|name| std::env::split_paths(&path).map(move |dir| dir.join(name)))
        .find(|candidate| candidate.is_file())
        .context(
            "no Chromium found (apt-get install chromium, or set SRT_CHROMIUM to a Chrome or \
             Chromium executable)",
        )
}

impl Browser {
    /// Starts `executable` headless with WebGPU enabled (SwiftShader where there is no GPU),
    /// device pixels equal to CSS pixels, its profile in `profile` and its messages in `log`.
    ///
    /// # Errors
    /// When it does not start or does not open its DevTools port within a minute.
    pub fn start(executable: &Path, profile: &Path, log: &Path) -> anyhow::Result<Self> {
        let mut process = Command::new(executable)
            .args([
                "--headless=new",
                "--no-sandbox",
                "--enable-unsafe-webgpu",
                // Vulkan through SwiftShader where there is no GPU: without it, headless Chromium
                // cannot create a WebGPU canvas's swap-chain images (its GL path has no backing
                // for them) and the device is lost at the first frame.
                "--enable-features=Vulkan",
                "--use-vulkan=swiftshader",
                "--use-angle=swiftshader",
                "--remote-debugging-port=0",
                "--hide-scrollbars",
                "--force-device-scale-factor=1",
                "--window-size=1024,768",
                "--no-first-run",
                "--no-default-browser-check",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .args(
                std::env::var("SRT_CHROMIUM_FLAGS")
                    .unwrap_or_default()
                    .split_whitespace(),
            )
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .with_context(|| format!("cannot start {}", executable.display()))?;
        let stderr = process.stderr.take().context("the browser's messages")?;
        let mut log = std::fs::File::create(log)
            .with_context(|| format!("cannot write {}", log.display()))?;
        let (found, endpoint) = mpsc::channel();
        std::thread::spawn(move || {
            use std::io::Write as _;
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if let Some(url) = line.strip_prefix("DevTools listening on ") {
                    let _ = found.send(url.trim().to_owned());
                }
                let _ = writeln!(log, "{line}");
            }
        });
        let url = endpoint
            .recv_timeout(Duration::from_secs(60))
            .context("the browser did not open its DevTools port within a minute")?;
        let (socket, _) = tungstenite::connect(&url)
            .with_context(|| format!("cannot reach the browser at {url}"))?;
        if let MaybeTlsStream::Plain(stream) = socket.get_ref() {
            stream.set_read_timeout(Some(COMMAND_TIMEOUT))?;
        }
        let mut browser = Self {
            process,
            socket,
            session: String::new(),
            next_id: 0,
            console: Vec::new(),
        };
        let target =
            browser.call_browser("Target.createTarget", json!({ "url": "about:blank" }))?;
        let target_id = target["targetId"].clone();
        let attached = browser.call_browser(
            "Target.attachToTarget",
            json!({ "targetId": target_id, "flatten": true }),
        )?;
        browser.session = attached["sessionId"]
            .as_str()
            .context("no DevTools session")?
            .to_owned();
        Ok(browser)
    }

    /// Sends `method` to the browser itself and returns its result.
    fn call_browser(&mut self, method: &str, params: Value) -> anyhow::Result<Value> {
        self.send(None, method, params)
    }

    /// Sends `method` to the page and returns its result.
    fn call(&mut self, method: &str, params: Value) -> anyhow::Result<Value> {
        let session = self.session.clone();
        self.send(Some(&session), method, params)
    }

    fn send(
        &mut self,
        session: Option<&str>,
        method: &str,
        params: Value,
    ) -> anyhow::Result<Value> {
        self.next_id += 1;
        let id = self.next_id;
        let mut message = json!({ "id": id, "method": method, "params": params });
        if let Some(session) = session {
            message["sessionId"] = json!(session);
        }
        self.socket
            .send(Message::text(message.to_string()))
            .with_context(|| format!("DevTools {method}"))?;
        loop {
            let reply = self
                .socket
                .read()
                .with_context(|| format!("DevTools {method}: no answer"))?;
            let Message::Text(text) = reply else {
                continue;
            };
            let reply: Value = serde_json::from_str(text.as_str())?;
            if let Some(line) = console_line(&reply) {
                self.console.push(line);
            }
            if reply["id"].as_u64() != Some(id) {
                continue; // an event, or another command's answer
            }
            if let Some(error) = reply.get("error") {
                bail!("DevTools {method} failed: {error}");
            }
            return Ok(reply["result"].clone());
        }
    }

    /// Opens `url` in the page.
    ///
    /// # Errors
    /// When the browser refuses.
    pub fn open(&mut self, url: &str) -> anyhow::Result<()> {
        self.call("Page.enable", json!({}))?;
        self.call("Runtime.enable", json!({}))?;
        self.console.clear();
        let result = self.call("Page.navigate", json!({ "url": url }))?;
        if let Some(error) = result.get("errorText") {
            bail!("cannot open {url}: {error}");
        }
        Ok(())
    }

    /// The value of the JavaScript expression `expression` in the page.
    ///
    /// # Errors
    /// When the browser refuses or the expression throws.
    pub fn evaluate(&mut self, expression: &str) -> anyhow::Result<Value> {
        let result = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "returnByValue": true, "awaitPromise": true }),
        )?;
        if let Some(exception) = result.get("exceptionDetails") {
            bail!("{expression} threw {exception}");
        }
        Ok(result["result"]["value"].clone())
    }

    /// The value of `expression` once `done` accepts it, checked every 100 ms for up to
    /// `timeout`.
    ///
    /// # Errors
    /// When `timeout` passes first (the last value is in the message).
    pub fn wait_for(
        &mut self,
        expression: &str,
        done: impl Fn(&Value) -> bool,
        timeout: Duration,
    ) -> anyhow::Result<Value> {
        let start = Instant::now();
        let mut value = Value::Null;
        while start.elapsed() < timeout {
            value = self.evaluate(expression)?;
            if done(&value) {
                return Ok(value);
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        bail!("{expression} was still {value} after {timeout:?}")
    }

    /// The page's title once `done` accepts it, checked every 100 ms for up to `timeout`.
    ///
    /// # Errors
    /// When `timeout` passes first (the last title is in the message).
    pub fn wait_for_title(
        &mut self,
        done: impl Fn(&str) -> bool,
        timeout: Duration,
    ) -> anyhow::Result<String> {
        let title = self.wait_for(
            "document.title",
            |title| done(title.as_str().unwrap_or_default()),
            timeout,
        )?;
        Ok(title.as_str().unwrap_or_default().to_owned())
    }

    /// Makes the page `width`×`height` CSS pixels large, one device pixel each.
    ///
    /// # Errors
    /// When the browser refuses.
    pub fn set_viewport(&mut self, width: u32, height: u32) -> anyhow::Result<()> {
        self.call(
            "Emulation.setDeviceMetricsOverride",
            json!({ "width": width, "height": height, "deviceScaleFactor": 1, "mobile": false }),
        )?;
        Ok(())
    }

    /// A PNG of the page's rectangle `width`×`height` at (`x`, `y`), in CSS pixels.
    ///
    /// # Errors
    /// When the browser refuses.
    pub fn screenshot(
        &mut self,
        (x, y): (f64, f64),
        width: u32,
        height: u32,
    ) -> anyhow::Result<Vec<u8>> {
        let result = self.call(
            "Page.captureScreenshot",
            json!({
                "format": "png",
                "clip": { "x": x, "y": y, "width": width, "height": height, "scale": 1 },
            }),
        )?;
        let data = result["data"]
            .as_str()
            .context("a screenshot without data")?;
        Ok(base64::engine::general_purpose::STANDARD.decode(data)?)
    }
}

impl Browser {
    /// The page's console messages and uncaught exceptions since the page was opened.
    #[must_use]
    pub fn console(&self) -> &[String] {
        &self.console
    }
}

/// A console message or an uncaught exception of a DevTools event, as one line.
fn console_line(event: &Value) -> Option<String> {
    let params = &event["params"];
    match event["method"].as_str()? {
        "Runtime.consoleAPICalled" => {
            let words: Vec<String> = params["args"]
                .as_array()?
                .iter()
                .map(|arg| match &arg["value"] {
                    Value::String(text) => text.clone(),
                    Value::Null => arg["description"].as_str().unwrap_or_default().to_owned(),
                    other => other.to_string(),
                })
                .collect();
            Some(format!(
                "console.{}: {}",
                params["type"].as_str()?,
                words.join(" ")
            ))
        }
        "Runtime.exceptionThrown" => {
            let details = &params["exceptionDetails"];
            let text = details["exception"]["description"]
                .as_str()
                .or_else(|| details["text"].as_str())?;
            Some(format!("exception: {text}"))
        }
        _ => None,
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.call_browser("Browser.close", json!({}));
        let _ = self.process.kill();
        let _ = self.process.wait();
    }
}

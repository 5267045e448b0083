//! The page's address as settings: `index.html?scene=fig7&width=320&height=180&time=5&embed=1`.
//! Every key has the meaning of the `srt render` option of the same name, so an embedded page
//! and the command draw the same picture (`time` is `--time`, the observer's clock). A key the page does not know, or a
//! value it cannot read, is refused with a message naming the key.

use srt_gpu::Method;
use srt_scene::{Choice, OverrideNames, Overrides, parse_vector};

/// The largest canvas side the page draws, in pixels (WebGPU's guaranteed texture size).
pub const MAX_CANVAS_SIDE: u32 = 8192;

/// Which renderer draws the page.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BackendChoice {
    /// WebGPU where the browser has it, else the CPU tracer.
    #[default]
    Auto,
    /// The exact CPU tracer in a Web Worker.
    Cpu,
    /// WebGPU, or an error.
    Webgpu,
}

srt_scene::choice!(BackendChoice, "backend", {
    Auto => "auto", "WebGPU where the browser has it, else the CPU tracer";
    Cpu => "cpu", "the exact CPU tracer in a Web Worker";
    Webgpu => "webgpu", "WebGPU, or an error";
});

/// The settings an address gives.
#[derive(Debug, Clone, PartialEq)]
pub struct PageQuery {
    /// The built-in scene (`scene`); `None`: the one shown now (at first, `teaser`).
    pub scene: Option<String>,
    /// The canvas size in CSS pixels (`width`, `height`); `None`: the page's own layout.
    pub size: Option<(u32, u32)>,
    /// Only the canvas, at the page's top-left corner (`embed=1`).
    pub embed: bool,
    /// Which renderer (`backend=auto|cpu|webgpu`).
    pub backend: BackendChoice,
    /// The GPU method (`method=auto|lrt|rt|polygon|image-based`).
    pub method: Method,
    /// Split view: the left half exact, the right half the polygon method (`split=1`).
    pub split: bool,
    /// Values in place of the scene's own (`ct`, `beta`, `observer_beta`, `effects`, `colour`,
    /// `exposure`), named by their keys in messages.
    pub overrides: Overrides,
}

impl Default for PageQuery {
    fn default() -> Self {
        Self {
            scene: None,
            size: None,
            embed: false,
            backend: BackendChoice::Auto,
            method: Method::Auto,
            split: false,
            overrides: Overrides {
                names: OverrideNames::KEYS,
                ..Overrides::default()
            },
        }
    }
}

/// A key or value of the address the page cannot use.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum QueryError {
    /// A key the page does not know.
    #[error("the address has an unknown key \"{0}\" (known: {known})", known = KEYS.join(", "))]
    UnknownKey(String),
    /// A value that is not what its key takes.
    #[error("{key}={value}: {reason}")]
    Value {
        /// The key.
        key: String,
        /// The value as written.
        value: String,
        /// What the key takes.
        reason: String,
    },
}

/// Every key the page reads.
pub const KEYS: [&str; 15] = [
    "scene",
    "width",
    "height",
    "embed",
    "backend",
    "method",
    "split",
    "time",
    "beta",
    "observer_beta",
    "projection",
    "effects",
    "colour",
    "exposure",
    "set",
];

/// Reads `query`, the part of the address after `?` (a leading `?` is allowed), with
/// percent-encoding and `+` for spaces as browsers write them.
///
/// # Errors
/// [`QueryError`] for the first unknown key or unreadable value.
pub fn parse_query(query: &str) -> Result<PageQuery, QueryError> {
    let mut page = PageQuery::default();
    let (mut width, mut height) = (None, None);
    for pair in query.trim_start_matches('?').split('&') {
        if pair.is_empty() {
            continue;
        }
        let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
        let key = decode(key);
        let value = decode(value);
        let bad = |reason: String| QueryError::Value {
            key: key.clone(),
            value: value.clone(),
            reason,
        };
        let rule = |reason: &str| bad(reason.to_owned());
        let overrides = &mut page.overrides;
        match key.as_str() {
            "scene" => page.scene = Some(value.clone()),
            "width" => width = Some(side(&value).ok_or_else(|| rule(SIDE_RULE))?),
            "height" => height = Some(side(&value).ok_or_else(|| rule(SIDE_RULE))?),
            "embed" => page.embed = flag(&value).ok_or_else(|| rule(FLAG_RULE))?,
            "split" => page.split = flag(&value).ok_or_else(|| rule(FLAG_RULE))?,
            "backend" => page.backend = chosen(&value).map_err(bad)?,
            "method" => page.method = chosen(&value).map_err(bad)?,
            "time" => overrides.time = Some(number(&value).ok_or_else(|| rule(NUMBER_RULE))?),
            "exposure" => {
                overrides.exposure = Some(number(&value).ok_or_else(|| rule(NUMBER_RULE))?);
            }
            "beta" => overrides.beta = Some(parse_vector(&value).map_err(bad)?),
            "observer_beta" => {
                overrides.observer_beta = Some(parse_vector(&value).map_err(bad)?);
            }
            "projection" => overrides.projection = Some(value.parse().map_err(bad)?),
            "effects" => overrides.effects = Some(chosen(&value).map_err(bad)?),
            "colour" => overrides.colour = Some(chosen(&value).map_err(bad)?),
            "set" => overrides.settings.push(value.parse().map_err(bad)?),
            _ => return Err(QueryError::UnknownKey(key)),
        }
    }
    page.size = match (width, height) {
        (None, None) => None,
        (Some(width), Some(height)) => Some((width, height)),
        (Some(_), None) | (None, Some(_)) => {
            return Err(QueryError::Value {
                key: if width.is_some() { "height" } else { "width" }.to_owned(),
                value: String::new(),
                reason: "width and height are given together".to_owned(),
            });
        }
    };
    Ok(page)
}

const SIDE_RULE: &str = "a canvas side is a whole number of pixels from 1 to 8192";
const FLAG_RULE: &str = "a switch is 1 or 0";
const NUMBER_RULE: &str = "not a finite number";

fn decode(text: &str) -> String {
    percent_encoding::percent_decode_str(&text.replace('+', " "))
        .decode_utf8_lossy()
        .into_owned()
}

fn side(value: &str) -> Option<u32> {
    value
        .parse::<u32>()
        .ok()
        .filter(|side| (1..=MAX_CANVAS_SIDE).contains(side))
}

fn flag(value: &str) -> Option<bool> {
    match value {
        "1" | "" | "true" => Some(true),
        "0" | "false" => Some(false),
        _ => None,
    }
}

fn number(value: &str) -> Option<f64> {
    value.trim().parse::<f64>().ok().filter(|x| x.is_finite())
}

/// The choice called `value`, or the message naming the choices there are.
fn chosen<T: Choice>(value: &str) -> Result<T, String> {
    T::parse(value).map_err(|unknown| unknown.to_string())
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use srt_scene::{Effects, SurfaceColour};

    use super::*;

    #[test]
    fn an_embed_address_reads_as_the_command_line_options() {
        let page = parse_query(
            "?scene=fig7&width=320&height=180&time=5.5&embed=1&backend=cpu&beta=0%2C0%2C0.9\
             &effects=searchlight&colour=spectral&method=rt&split=0",
        )
        .unwrap();
        assert_eq!(page.scene.as_deref(), Some("fig7"));
        assert_eq!(page.size, Some((320, 180)));
        assert!(page.embed && !page.split);
        assert_eq!(page.backend, BackendChoice::Cpu);
        assert_eq!(page.method, Method::Rt);
        assert_eq!(page.overrides.time, Some(5.5));
        assert_eq!(page.overrides.beta, Some(DVec3::new(0.0, 0.0, 0.9)));
        assert_eq!(page.overrides.effects, Some(Effects::Searchlight));
        assert_eq!(page.overrides.colour, Some(SurfaceColour::Spectral));
        assert_eq!(parse_query("").unwrap(), PageQuery::default());
        let set = parse_query("set=observer.fov_y_deg%3D60&set=object.cube.beta=0,0.5,0").unwrap();
        let keys: Vec<String> = set.overrides.settings.iter().map(|s| s.key()).collect();
        assert_eq!(keys, ["observer.fov_y_deg", "object.cube.beta"]);
    }

    #[test]
    fn bad_keys_and_values_are_named() {
        let unknown = parse_query("scene=fig7&sped=0.9").unwrap_err().to_string();
        assert!(
            unknown.contains("\"sped\"") && unknown.contains("beta"),
            "{unknown}"
        );
        for (query, key) in [
            ("time=soon", "time="),
            ("width=0&height=10", "width=0"),
            ("width=10", "height"),
            ("beta=0,0", "beta=0,0"),
            ("beta=0,0,NaN", "beta="),
            ("method=fast", "method=fast"),
            ("backend=gl", "backend=gl"),
            ("embed=yes", "embed=yes"),
            ("effects=all", "effects=all"),
            ("set=fov", "set=fov"),
        ] {
            let message = parse_query(query).unwrap_err().to_string();
            assert!(message.starts_with(key), "{query}: {message}");
        }
    }
}

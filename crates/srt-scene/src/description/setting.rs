//! Any scene file key given from a front end: `srt render --set observer.fov_y_deg=60`. A
//! [`Setting`] edits the description as the scene file's TOML would (the same keys, the same
//! types), and the result is judged by the scene file's own rules and messages: nothing a setting
//! can say escapes validation, and no key needs an option of its own.
//!
//! A key is the scene file's dotted path. Tables that the file may leave out are created
//! (`sky.star_field=2000`); an element of an array of tables (`[[object]]`, `[[light]]`) is
//! named by its index from 0 or by its `name`: `object.0.beta`, `object.cube.beta`. A value is
//! TOML (`60`, `"spectral"`, `[0, 0.9, 0]`, `{ type = "fisheye", fov_deg = 200 }`), or for
//! convenience in a shell, numbers separated by commas (`0,0.9,0`, an array) or a bare word
//! (`spectral`, a string).

use std::fmt;
use std::str::FromStr;

use super::error::SceneErrorKind;
use super::model::SceneDescription;

/// One `KEY=VALUE`: a scene file key and the TOML value it is given.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// The key's parts: `observer.fov_y_deg` is `["observer", "fov_y_deg"]`.
    path: Vec<String>,
    /// The value, as TOML.
    value: toml::Value,
    /// The value as given, for messages.
    text: String,
}

impl Setting {
    /// The setting of `key` (dotted, as [`Setting::from_str`] reads it) to `value`.
    ///
    /// # Errors
    /// An empty key or key part.
    pub fn new(key: &str, value: toml::Value) -> Result<Self, String> {
        let path = key_path(key)?;
        let text = value.to_string();
        Ok(Self { path, value, text })
    }

    /// The key, dotted: `observer.fov_y_deg`.
    #[must_use]
    pub fn key(&self) -> String {
        self.path.join(".")
    }

    /// Gives the key its value in `description`, which must then still read as a scene file
    /// (known keys, values of the right types). `option` names the front end's option in
    /// messages (`--set`). The values are not checked here: [`super::Overrides::apply`]
    /// validates the description after all its edits.
    ///
    /// # Errors
    /// [`SceneErrorKind::Override`] naming the option, the key and the value: the key leads
    /// through a value that is not a table, names an element that is not there, or the result
    /// does not read as a scene file (an unknown key, a value of the wrong type).
    ///
    /// # Panics
    /// Never: every description has a TOML representation.
    pub fn apply(
        &self,
        description: &mut SceneDescription,
        option: &str,
    ) -> Result<(), SceneErrorKind> {
        let refuse = |reason: String| SceneErrorKind::Override {
            option: format!("{option} {self}"),
            reason: format!("does not fit the scene file: {reason}"),
        };
        let mut document = toml::Value::try_from(&*description)
            .expect("a scene description is always representable in TOML");
        *self.slot(&mut document).map_err(refuse)? = self.value.clone();
        *description = document
            .try_into()
            .map_err(|error: toml::de::Error| refuse(error.message().trim_end().to_owned()))?;
        Ok(())
    }

    /// The place in `document` that the key names, created if it is a table's missing key.
    fn slot<'a>(&self, document: &'a mut toml::Value) -> Result<&'a mut toml::Value, String> {
        let mut here = document;
        for (depth, part) in self.path.iter().enumerate() {
            let so_far = || self.path[..depth].join(".");
            here = match here {
                toml::Value::Table(table) => table
                    .entry(part.clone())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new())),
                toml::Value::Array(elements) => {
                    let count = elements.len();
                    let found = match part.parse::<usize>() {
                        Ok(index) => index,
                        Err(_) => elements
                            .iter()
                            .position(|element| {
                                element.get("name").and_then(toml::Value::as_str) == Some(part)
                            })
                            .ok_or_else(|| {
                                format!(
                                    "{} has no element named {part:?} (name one by its `name` or \
                                     its index from 0)",
                                    so_far()
                                )
                            })?,
                    };
                    elements.get_mut(found).ok_or_else(|| {
                        format!("{} has {count} element(s), counted from 0", so_far())
                    })?
                }
                other => {
                    return Err(format!(
                        "{} is a {}, not a table",
                        so_far(),
                        other.type_str()
                    ));
                }
            };
        }
        Ok(here)
    }
}

impl fmt::Display for Setting {
    /// `KEY=VALUE`, the value as given.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.key(), self.text)
    }
}

impl FromStr for Setting {
    type Err = String;

    /// Reads `KEY=VALUE` (see the module's documentation for the value's forms).
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let (key, value) = text.split_once('=').ok_or_else(|| {
            format!("expected KEY=VALUE (e.g. observer.fov_y_deg=60), got {text:?}")
        })?;
        let value = value.trim();
        Ok(Self {
            path: key_path(key)?,
            value: parse_value(value),
            text: value.to_owned(),
        })
    }
}

/// The parts of a dotted key.
fn key_path(key: &str) -> Result<Vec<String>, String> {
    let path: Vec<String> = key
        .trim()
        .split('.')
        .map(|part| part.trim().to_owned())
        .collect();
    if path.iter().any(String::is_empty) {
        return Err(format!(
            "{key:?} is not a scene file key: expected parts joined by dots, e.g. observer.fov_y_deg"
        ));
    }
    Ok(path)
}

/// A value as TOML; else numbers separated by commas as an array; else the text as a string.
fn parse_value(text: &str) -> toml::Value {
    if let Ok(mut table) = format!("value = {text}").parse::<toml::Table>()
        && table.len() == 1
        && let Some(value) = table.remove("value")
    {
        return value;
    }
    let numbers: Result<Vec<toml::Value>, _> = text
        .split(',')
        .map(|part| part.trim().parse::<f64>().map(toml::Value::Float))
        .collect();
    match numbers {
        Ok(numbers) if numbers.len() > 1 => toml::Value::Array(numbers),
        _ => toml::Value::String(text.to_owned()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin::builtin;

    fn set(description: &mut SceneDescription, text: &str) -> Result<(), String> {
        let setting: Setting = text.parse()?;
        setting
            .apply(description, "--set")
            .map_err(|error| error.to_string())
    }

    #[test]
    fn values_read_as_toml_or_as_a_shell_would_give_them() {
        assert_eq!(parse_value("60"), toml::Value::Integer(60));
        assert_eq!(parse_value("\"a b\""), toml::Value::String("a b".into()));
        assert_eq!(
            parse_value("spectral"),
            toml::Value::String("spectral".into())
        );
        assert_eq!(parse_value("true"), toml::Value::Boolean(true));
        let vector = toml::Value::Array(vec![
            toml::Value::Float(0.0),
            toml::Value::Float(0.9),
            toml::Value::Float(-1.0),
        ]);
        assert_eq!(parse_value("0, 0.9,-1"), vector);
        assert_eq!(parse_value("[0.0, 0.9, -1.0]"), vector);
        assert!(matches!(
            parse_value("{ type = \"fisheye\" }"),
            toml::Value::Table(_)
        ));
        for bad in ["fov", "=3", "a..b=1", ".a=1"] {
            assert!(bad.parse::<Setting>().is_err(), "{bad}");
        }
    }

    #[test]
    fn a_setting_edits_what_the_scene_file_key_names() {
        let mut fig4 = builtin("fig4").expect("fig4");
        set(&mut fig4, "observer.fov_y_deg=60").expect("set");
        assert!((fig4.observer.fov_y_deg - 60.0).abs() < 1e-12);
        set(&mut fig4, "render.colour = spectral").expect("set");
        assert_eq!(fig4.render.colour, crate::scene::SurfaceColour::Spectral);
        set(&mut fig4, "object.cube.beta=0,0.5,0").expect("by name");
        set(&mut fig4, "object.0.offset=[1, 2, 3]").expect("by index");
        assert_eq!(fig4.objects[0].beta, [0.0, 0.5, 0.0]);
        assert_eq!(fig4.objects[0].offset, [1.0, 2.0, 3.0]);
        set(&mut fig4, "sky.star_field=100").expect("a table the file left out");
        assert_eq!(fig4.sky.as_ref().map(|sky| sky.star_field), Some(100));
        set(
            &mut fig4,
            "observer.projection={ type = \"fisheye\", fov_deg = 200 }",
        )
        .expect("set");
        assert_eq!(
            fig4.observer.projection,
            Some(crate::Projection::Fisheye { fov_deg: 200.0 })
        );
    }

    #[test]
    fn a_setting_the_scene_file_would_refuse_is_refused_with_its_key() {
        let fig4 = builtin("fig4").expect("fig4");
        for (text, mentions) in [
            (
                "observer.fov=60",
                &["--set observer.fov=60", "unknown field `fov`"][..],
            ),
            (
                "observer.fov_y_deg=wide",
                &["observer.fov_y_deg=wide", "invalid type"][..],
            ),
            (
                "object.ship.beta=0,0.5,0",
                &["object", "no element named \"ship\""][..],
            ),
            ("object.3.beta=0,0.5,0", &["object has 1 element"][..]),
            (
                "observer.fov_y_deg.x=1",
                &["observer.fov_y_deg is a float, not a table"][..],
            ),
        ] {
            let mut description = fig4.clone();
            let message = set(&mut description, text).expect_err(text);
            for word in mentions {
                assert!(message.contains(word), "{text}: {message}");
            }
            assert_eq!(
                description, fig4,
                "{text}: a refused setting changes nothing"
            );
        }
    }
}

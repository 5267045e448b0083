//! Errors of scene files: where (the file or the scene) and what is wrong.

use std::fmt;

use srt_physics::FrameError;

use crate::import::ImportError;
use crate::input_file::InputFileError;
use crate::limits::MAX_COORDINATE;
use crate::mesh::MeshError;
use crate::message::one_line;

/// Why a scene could not be loaded or built: where (the file, or the scene's name) and why.
///
/// Its message names both, e.g. `scenes/cube.toml: line 4, column 1: unknown field `colour`, …`
/// or `scene "demo": object "probe" has an invalid velocity or offset: speed |β| = 1.2 is not
/// below the speed of light (it must be < 1)`, on one line of at most
/// [`MAX_MESSAGE_CHARS`](crate::message::MAX_MESSAGE_CHARS) characters. An error in a value an
/// option gave ([`SceneErrorKind::Override`]) is about the option alone and names only it, e.g.
/// `--exposure must be a positive number, got -1.0`.
#[derive(Debug)]
pub struct SceneError {
    origin: String,
    kind: Box<SceneErrorKind>,
}

impl SceneError {
    /// An error about `origin` (a file path or a scene name, as it should appear in messages).
    #[must_use]
    pub fn new(origin: impl Into<String>, kind: SceneErrorKind) -> Self {
        Self {
            origin: origin.into(),
            kind: Box::new(kind),
        }
    }

    /// Where the error is: the scene file, or `scene "name"` for a description not read from a
    /// file.
    #[must_use]
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// What is wrong.
    #[must_use]
    pub fn kind(&self) -> &SceneErrorKind {
        &self.kind
    }

    /// The same error, said to be about `origin` instead.
    #[must_use]
    pub fn with_origin(self, origin: impl Into<String>) -> Self {
        Self {
            origin: origin.into(),
            kind: self.kind,
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let message = match *self.kind {
            SceneErrorKind::Override { .. } => self.kind.to_string(),
            _ => format!("{}: {}", self.origin, self.kind),
        };
        f.write_str(&one_line(&message))
    }
}

/// The kind is part of the message already, so it is not also given as the `source` (callers
/// that print the whole chain, as `{:#}` does, would say it twice); use [`SceneError::kind`].
impl std::error::Error for SceneError {}

/// The reason part of a [`SceneError`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneErrorKind {
    /// The scene file could not be read, is not a regular file, is too large or is not text.
    #[error("cannot read the scene file: {0}")]
    Io(InputFileError),
    /// The text is not valid TOML, or does not fit the format (unknown key, wrong type, missing
    /// key…). Line and column count from 1; columns count characters.
    #[error("line {line}, column {column}: {message}")]
    Syntax {
        /// Line of the offending text.
        line: usize,
        /// Column (in characters) of the offending text.
        column: usize,
        /// What the parser found wrong.
        message: String,
    },
    /// A value is out of its range or inconsistent with another one.
    #[error("{field} {reason}")]
    Value {
        /// The value concerned, e.g. `observer.fov_y_deg` or `shape.size of object "cube"`.
        field: String,
        /// What is wrong with it, e.g. `must be in (0, 180) degrees, got 200`.
        reason: String,
    },
    /// A value an option gave in place of the scene's own is out of its range or inconsistent
    /// with the scene ([`Overrides`](super::Overrides)).
    #[error("{option} {reason}")]
    Override {
        /// The option, perhaps with the value given, e.g. `--exposure` or `--beta 0.0,1.2,0.0`.
        option: String,
        /// What is wrong with it, e.g. `must be a positive number, got -1.0`.
        reason: String,
    },
    /// An object's velocity or offset is not usable (|β| ≥ 1, NaN…).
    #[error("{object} has an invalid velocity or offset: {error}")]
    Frame {
        /// The object, e.g. `object "probe"` or `object 3`.
        object: String,
        /// What [`Frame::new`](srt_physics::Frame::new) rejected.
        error: FrameError,
    },
    /// An object's model file could not be loaded (the message names the file).
    #[error("{object}: {error}")]
    Model {
        /// The object, e.g. `object "ship"`.
        object: String,
        /// The import error, naming the model file.
        error: ImportError,
    },
    /// An object's geometry, placed in its rest frame, reaches beyond ±[`MAX_COORDINATE`] (or is
    /// not finite).
    #[error(
        "{object} reaches {reach:e} scene units from its rest-frame origin once placed; every \
         coordinate must lie within ±{max:e} (check the model's units, scale and translate)",
        max = MAX_COORDINATE
    )]
    OutOfBounds {
        /// The object.
        object: String,
        /// The largest absolute coordinate (infinite if one is not finite).
        reach: f64,
    },
    /// The sky's star file could not be read or is not a valid star file (the message names it).
    #[error("{0}")]
    Sky(crate::sky::SkyError),
    /// Placing an object's geometry produced an invalid mesh (a transform with huge values).
    #[error("{object}: {error}")]
    Mesh {
        /// The object.
        object: String,
        /// What is wrong with the mesh.
        error: MeshError,
    },
}

/// Line and column (both from 1, the column in characters) of byte offset `offset` in `text`.
#[must_use]
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

pub(super) fn value_error(field: impl Into<String>, reason: impl Into<String>) -> SceneErrorKind {
    SceneErrorKind::Value {
        field: field.into(),
        reason: reason.into(),
    }
}

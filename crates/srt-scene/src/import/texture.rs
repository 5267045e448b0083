//! Texture images: decoding (PNG, JPEG, BMP, TGA; the format is guessed from the content, the
//! file extension is the fallback) into RGBA8 [`Texture`]s, and a per-model cache so that parts
//! sharing an image share one [`Arc`]. Files are read through [`crate::input_file`] and texels
//! charged to the scene's [`Budget`]; a texture that cannot be loaded for any reason (missing,
//! not a regular file, too large, undecodable) is a warning that says why, and the base colour
//! is used.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::limits::Budget;
use crate::mesh::Texture;
use crate::textures::load_image;

/// Texture files loaded so far for one model, by path; `None` for files that failed.
#[derive(Debug, Default)]
pub(super) struct TextureCache {
    files: HashMap<PathBuf, Option<Arc<Texture>>>,
}

impl TextureCache {
    /// The texture in file `path`, loaded once. On failure, pushes a warning naming the file and
    /// `user` (e.g. `material "wood"`) and returns `None`; later calls for the same file return
    /// `None` without another warning.
    pub(super) fn file(
        &mut self,
        path: &Path,
        user: &str,
        warnings: &mut Vec<String>,
        budget: &mut Budget,
    ) -> Option<Arc<Texture>> {
        if let Some(texture) = self.files.get(path) {
            return texture.clone();
        }
        let result = load_image(path, budget);
        let texture = match result {
            Ok(texture) => Some(Arc::new(texture)),
            Err(error) => {
                warnings.push(format!(
                    "texture \"{}\" of {user} cannot be loaded ({error}); using the base colour",
                    path.display()
                ));
                None
            }
        };
        self.files.insert(path.to_owned(), texture.clone());
        texture
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::textures::decode_image;

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        let mut budget = Budget::new();
        assert!(decode_image(b"not an image", None, "x", &mut budget).is_err());
        assert!(decode_image(b"", Some("tga"), "x", &mut budget).is_err());
        let truncated = b"\x89PNG\r\n\x1a\n\0\0";
        assert!(decode_image(truncated, Some("png"), "x", &mut budget).is_err());
    }

    #[test]
    fn a_missing_file_warns_once() {
        let mut cache = TextureCache::default();
        let mut warnings = Vec::new();
        let mut budget = Budget::new();
        let path = Path::new("/nonexistent/texture.png");
        let user = "material \"m\"";
        assert!(cache.file(path, user, &mut warnings, &mut budget).is_none());
        assert!(cache.file(path, user, &mut warnings, &mut budget).is_none());
        assert_eq!(warnings.len(), 1);
        assert!(warnings[0].contains("texture.png"), "{}", warnings[0]);
    }
}

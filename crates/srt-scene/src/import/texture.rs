//! Texture images: decoding (PNG, JPEG, BMP, TGA; the format is guessed from the content, the
//! file extension is the fallback) into RGBA8 [`Texture`]s, and a per-model cache so that parts
//! sharing an image share one [`Arc`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::mesh::Texture;

/// Decodes an encoded image (see [`crate::textures::decode_image`]).
pub(super) fn decode(
    bytes: &[u8],
    extension: Option<&str>,
    source: String,
) -> Result<Texture, String> {
    crate::textures::decode_image(bytes, extension, &source)
}

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
    ) -> Option<Arc<Texture>> {
        if let Some(texture) = self.files.get(path) {
            return texture.clone();
        }
        let extension = path.extension().and_then(|e| e.to_str());
        let result = std::fs::read(path)
            .map_err(|e| e.to_string())
            .and_then(|bytes| decode(&bytes, extension, path.display().to_string()));
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

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        assert!(decode(b"not an image", None, "x".into()).is_err());
        assert!(decode(b"", Some("tga"), "x".into()).is_err());
        assert!(decode(b"\x89PNG\r\n\x1a\n\0\0", Some("png"), "x".into()).is_err());
    }

    #[test]
    fn a_missing_file_warns_once() {
        let mut cache = TextureCache::default();
        let mut warnings = Vec::new();
        let path = Path::new("/nonexistent/texture.png");
        assert!(cache.file(path, "material \"m\"", &mut warnings).is_none());
        assert!(cache.file(path, "material \"m\"", &mut warnings).is_none());
        assert_eq!(warnings.len(), 1);
        assert!(warnings[0].contains("texture.png"), "{}", warnings[0]);
    }
}

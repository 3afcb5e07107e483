//! Resolves `map_Kd` names and decodes textures once per file (shared through `Arc`).

use super::mesh::TextureImage;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Decoded textures by resolved path. A failure is cached too, so a broken file shared by
/// several materials is reported (and retried) once.
#[derive(Default)]
pub struct TextureCache {
    loaded: HashMap<PathBuf, Result<Arc<TextureImage>, String>>,
}

impl TextureCache {
    pub fn new() -> Self {
        Self::default()
    }

    /// Loads `path`, decoding it only the first time. The error names the path and the cause.
    pub fn load(&mut self, path: &Path) -> Result<Arc<TextureImage>, String> {
        self.loaded
            .entry(path.to_owned())
            .or_insert_with(|| decode(path).map(Arc::new))
            .clone()
    }
}

/// Turns a `map_Kd` value into a path relative to the MTL's directory.
///
/// Handles option flags (`-bm 0.5 file.jpg`: the file is the last word), Windows separators,
/// and falls back to a case-insensitive match in the directory, because many OBJ exports come
/// from case-insensitive file systems.
pub fn resolve_texture_path(mtl_dir: &Path, map_kd: &str) -> PathBuf {
    let value = map_kd.trim();
    let name = if value.starts_with('-') {
        value.split_whitespace().last().unwrap_or(value)
    } else {
        value
    };
    let path = mtl_dir.join(name.replace('\\', "/"));
    if path.exists() {
        return path;
    }
    case_insensitive_match(&path).unwrap_or(path)
}

fn case_insensitive_match(path: &Path) -> Option<PathBuf> {
    let dir = path.parent()?;
    let wanted = path.file_name()?.to_str()?;
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.eq_ignore_ascii_case(wanted))
        })
}

fn decode(path: &Path) -> Result<TextureImage, String> {
    let reader = image::ImageReader::open(path)
        .map_err(|e| format!("cannot open {}: {e}", path.display()))?
        .with_guessed_format()
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let rgba = reader
        .decode()
        .map_err(|e| format!("cannot decode {}: {e}", path.display()))?
        .to_rgba8();
    let (width, height) = rgba.dimensions();
    if width == 0 || height == 0 {
        return Err(format!("{} has no pixels", path.display()));
    }
    Ok(TextureImage {
        path: path.to_owned(),
        width,
        height,
        rgba8: rgba.into_raw(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_and_separators() {
        let dir = Path::new("/nonexistent-dir");
        assert_eq!(
            resolve_texture_path(dir, "-bm 0.3 tex\\a.png"),
            dir.join("tex/a.png")
        );
        assert_eq!(
            resolve_texture_path(dir, " my file.png "),
            dir.join("my file.png")
        );
    }

    #[test]
    fn missing_file_error_names_path() {
        let mut cache = TextureCache::new();
        let e = cache.load(Path::new("/nonexistent-dir/x.png")).unwrap_err();
        assert!(e.contains("/nonexistent-dir/x.png"), "{e}");
        // The failure is cached: asking again gives the same answer without a new attempt.
        assert_eq!(
            cache.load(Path::new("/nonexistent-dir/x.png")).unwrap_err(),
            e
        );
    }
}

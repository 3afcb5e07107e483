//! Resolves `map_Kd` names and decodes textures once per file (shared through `Arc`).

use super::mesh::TextureImage;
use std::collections::HashMap;
use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
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

/// Turns a `map_Kd` value (its bytes: a file name need not be UTF-8) into a path relative to
/// the MTL's directory.
///
/// Handles option flags (`-bm 0.5 file.jpg`: the file is the last word), Windows separators,
/// and falls back to a case-insensitive match in the directory, because many OBJ exports come
/// from case-insensitive file systems.
pub fn resolve_texture_path(mtl_dir: &Path, map_kd: impl AsRef<[u8]>) -> PathBuf {
    let value = map_kd.as_ref().trim_ascii();
    let name = if value.starts_with(b"-") {
        value
            .split(u8::is_ascii_whitespace)
            .rfind(|w| !w.is_empty())
            .unwrap_or(value)
    } else {
        value
    };
    let name: Vec<u8> = name
        .iter()
        .map(|&b| if b == b'\\' { b'/' } else { b })
        .collect();
    let path = mtl_dir.join(OsString::from_vec(name));
    if path.exists() {
        return path;
    }
    case_insensitive_match(&path).unwrap_or(path)
}

/// The `map_Kd` values of an MTL file's bytes that are not UTF-8, by the text the MTL parser
/// sees (each invalid sequence replaced by U+FFFD): a Latin-1 file name is found by its bytes
/// instead of a mangled name that names no file.
pub fn non_utf8_map_kd(mtl: &[u8]) -> HashMap<String, OsString> {
    let mut names = HashMap::new();
    for line in mtl.split(|&b| b == b'\n') {
        let line = line.trim_ascii();
        let Some(value) = line.strip_prefix(b"map_Kd") else {
            continue;
        };
        if !value.first().is_some_and(u8::is_ascii_whitespace) {
            continue;
        }
        let value = value.trim_ascii();
        if std::str::from_utf8(value).is_err() {
            let seen = String::from_utf8_lossy(value).trim().to_owned();
            names.insert(seen, OsString::from_vec(value.to_vec()));
        }
    }
    names
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
    let file = super::input::open_regular(path)
        .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let mut reader = image::ImageReader::new(std::io::BufReader::new(file));
    // As `ImageReader::open`: the extension's format unless the bytes say otherwise.
    if let Ok(format) = image::ImageFormat::from_path(path) {
        reader.set_format(format);
    }
    let reader = reader
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
    use std::os::unix::ffi::OsStrExt;

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
    fn latin1_names_keep_their_bytes() {
        let mtl = b"newmtl m\r\nmap_Kd  caf\xe9.png \r\nmap_Kd plain.png\n";
        let names = non_utf8_map_kd(mtl);
        assert_eq!(names.len(), 1);
        let raw = &names["caf\u{fffd}.png"];
        assert_eq!(raw.as_bytes(), b"caf\xe9.png");
        let dir = Path::new("/nonexistent-dir");
        assert_eq!(
            resolve_texture_path(dir, raw.as_bytes())
                .as_os_str()
                .as_bytes(),
            b"/nonexistent-dir/caf\xe9.png"
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

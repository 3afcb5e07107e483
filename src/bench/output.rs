//! Writing a run's files: text written atomically, scene specs as file names.

use crate::error::Result;
use std::path::Path;

/// Write `text` to `path` atomically, creating its directory.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    crate::files::write_atomic(path, text.as_bytes())
}

/// A scene spec as a file-name part: `box:venus` -> `box-venus`.
pub fn file_stem(spec: &str) -> String {
    spec.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

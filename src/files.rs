//! Output files written atomically: the bytes go to a temporary file beside the target, which
//! is then renamed over it, so an interrupted run leaves the previous file or none, never a
//! truncated one.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Write `bytes` to `path` atomically, creating its directory.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| Error::Io { path, source }
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
    }
    let tmp = temporary(path);
    std::fs::write(&tmp, bytes).map_err(io(&tmp))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io(path)(e)
    })
}

/// `dir/.name.tmp-<pid>`: hidden, in the same directory (rename is atomic only within one
/// file system), and distinct per process.
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("ssgi-files-{}", std::process::id()));
        let path = dir.join("sub/report.json");
        write_atomic(&path, b"old").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        let names: Vec<_> = std::fs::read_dir(path.parent().unwrap())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("report.json")]);
        // A directory in the way: the error names the path, the old directory stays.
        let err = write_atomic(&dir.join("sub"), b"x")
            .unwrap_err()
            .to_string();
        assert!(err.contains("sub"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

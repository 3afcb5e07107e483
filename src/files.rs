//! Output files written atomically: the bytes go to a temporary file beside the target, which
//! is then renamed over it, so an interrupted run leaves the previous file or none, never a
//! truncated one.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Test hook (tests/interrupt.rs), never set in normal use: when this environment variable is
/// set to a non-empty string that the destination's path contains, [`write_atomic`] prints
/// `paused before renaming <tmp> to <dest>` on stderr once the temporary file is whole and
/// then blocks until the process is killed, so a test can SIGKILL it at the moment a plain
/// write would have left a truncated file.
pub const PAUSE_BEFORE_RENAME: &str = "SSGI_TEST_PAUSE_BEFORE_RENAME";

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
    pause_before_rename(&tmp, path);
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

/// The [`PAUSE_BEFORE_RENAME`] test hook; unset, it costs one environment lookup per file.
fn pause_before_rename(tmp: &Path, dest: &Path) {
    let Some(needle) = std::env::var_os(PAUSE_BEFORE_RENAME).filter(|v| !v.is_empty()) else {
        return;
    };
    if !dest.to_string_lossy().contains(&*needle.to_string_lossy()) {
        return;
    }
    eprintln!(
        "paused before renaming {} to {}",
        tmp.display(),
        dest.display()
    );
    // Parked until killed (park may wake spuriously, hence the loop).
    loop {
        std::thread::park();
    }
}

/// Encode `rgba` as PNG and write it atomically (`write_atomic`).
pub fn write_png_rgba8(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    let mut png = std::io::Cursor::new(Vec::new());
    image::write_buffer_with_format(
        &mut png,
        rgba,
        width,
        height,
        image::ColorType::Rgba8,
        image::ImageFormat::Png,
    )
    .map_err(|e| Error::ImageWrite {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_atomic(path, &png.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("ssgi-files-{}-{name}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        dir
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let dir = scratch("replace");
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

    /// The new bytes go to a new file: the previous one is never truncated or rewritten in
    /// place (as `fs::write` would), so a reader that opened it, like a process killed
    /// mid-write, sees it whole.
    #[test]
    fn the_previous_file_is_never_rewritten_in_place() {
        let dir = scratch("in-place");
        let path = dir.join("report.json");
        write_atomic(&path, b"{\"previous\": true}").unwrap();
        let mut opened = std::fs::File::open(&path).unwrap();
        write_atomic(&path, b"{}").unwrap();
        let mut held = String::new();
        opened.read_to_string(&mut held).unwrap();
        assert_eq!(
            held, "{\"previous\": true}",
            "the previous file was rewritten in place"
        );
        assert_eq!(std::fs::read(&path).unwrap(), b"{}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

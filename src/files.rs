//! Output files written atomically: the bytes go to a temporary file beside the target, which
//! is then renamed over it, so an interrupted run leaves the previous file or none, never a
//! truncated one. Every output is checked (its directory created, a temporary file made and
//! removed there) before a run renders anything, so a bad path fails in a second, not after
//! the run.

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
    // A signal that exits at once removes it (`interrupt`).
    let _unfinished = crate::interrupt::temporary(&tmp);
    // Errors name the user's path: the temporary file is ours.
    std::fs::write(&tmp, bytes).map_err(io(path))?;
    pause_before_rename(&tmp, path);
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io(path)(e)
    })
}

/// Check before a run that `dir` can take its files: created with its parents if missing,
/// refused if it is something else, and a file can be made in it. `option` names it.
pub fn prepare_dir(dir: &Path, option: &str) -> Result<()> {
    let fail = |message: String| Error::Output {
        option: option.to_string(),
        path: dir.to_path_buf(),
        message,
    };
    if let Some((existing, what)) = blocked_by(dir) {
        return Err(fail(if existing == dir {
            format!("it is {what}, not a directory")
        } else {
            format!("{} is {what}, not a directory", existing.display())
        }));
    }
    std::fs::create_dir_all(dir).map_err(|e| fail(format!("cannot create it ({e})")))?;
    let name = format!(".ssgi-probe-{}", std::process::id());
    probe(&dir.join(name)).map_err(|e| fail(format!("cannot write into it ({e})")))
}

/// Check before a run that the file `path` can be written: its directory created with its
/// parents, a temporary file made and removed there (as [`write_atomic`] will), and `path`
/// not a directory. `option` names it.
pub fn prepare_file(path: &Path, option: &str) -> Result<()> {
    let fail = |message: String| Error::Output {
        option: option.to_string(),
        path: path.to_path_buf(),
        message,
    };
    if path.is_dir() {
        return Err(fail("it is a directory; give a file name".into()));
    }
    if path.file_name().is_none() {
        return Err(fail("it names no file".into()));
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        if let Some((existing, what)) = blocked_by(dir) {
            return Err(fail(format!(
                "{} is {what}, not a directory",
                existing.display()
            )));
        }
        std::fs::create_dir_all(dir)
            .map_err(|e| fail(format!("cannot create {} ({e})", dir.display())))?;
    }
    probe(&temporary(path)).map_err(|e| fail(format!("cannot write there ({e})")))
}

/// [`prepare_file`] for a PNG: the name must end in `.png` (ssgi writes PNG only, and bytes
/// under another extension would be misread).
pub fn prepare_png(path: &Path, option: &str) -> Result<()> {
    let png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        return Err(Error::Output {
            option: option.to_string(),
            path: path.to_path_buf(),
            message: "ssgi writes PNG images only: give the file name the extension .png".into(),
        });
    }
    prepare_file(path, option)
}

/// Why `dir` cannot become a directory: it, or the nearest of its ancestors that exists, is
/// something else (that path, and what it is).
fn blocked_by(dir: &Path) -> Option<(&Path, &'static str)> {
    let existing = dir
        .ancestors()
        .find(|a| !a.as_os_str().is_empty() && a.exists())?;
    if existing.is_dir() {
        return None;
    }
    let what = crate::scene::input::not_regular(existing).unwrap_or("a regular file");
    Some((existing, what))
}

/// Create the file `path` and remove it (one left by a killed run of this pid stays).
fn probe(path: &Path) -> std::io::Result<()> {
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
    {
        Ok(_) => std::fs::remove_file(path),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => Err(e),
    }
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

//! Opening the files a user names (models, materials, textures, scene and keyframe files):
//! regular files only. Opening a FIFO blocks until something writes to it, and a device such
//! as /dev/zero never ends, so anything else is refused before it is opened, saying what it is.

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// What `path` is when it exists but is not a regular file (symbolic links followed):
/// "a directory", "a FIFO (named pipe)", ...; None for a regular file or a missing path.
pub fn not_regular(path: &Path) -> Option<&'static str> {
    let kind = std::fs::metadata(path).ok()?.file_type();
    if kind.is_file() {
        return None;
    }
    use std::os::unix::fs::FileTypeExt;
    Some(if kind.is_dir() {
        "a directory"
    } else if kind.is_fifo() {
        "a FIFO (named pipe)"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "not a regular file"
    })
}

/// The error for a path that is not a regular file.
fn refused(kind: &str) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("it is {kind}, not a regular file"),
    )
}

/// Open `path` for reading if it is a regular file.
pub fn open_regular(path: &Path) -> io::Result<File> {
    if let Some(kind) = not_regular(path) {
        return Err(refused(kind));
    }
    File::open(path)
}

/// Read the regular file `path` whole; a file over `limit` bytes is refused (it is read no
/// further than that, so a file that grows while read cannot exhaust memory either).
pub fn read_regular(path: &Path, limit: Option<u64>) -> io::Result<Vec<u8>> {
    let file = open_regular(path)?;
    let too_big = |limit: u64| {
        let size = if limit.is_multiple_of(1 << 20) {
            format!("{} MiB", limit >> 20)
        } else {
            format!("{limit} bytes")
        };
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("it is larger than the limit of {size}"),
        )
    };
    let mut bytes = Vec::new();
    match limit {
        Some(limit) => {
            if file.metadata()?.len() > limit {
                return Err(too_big(limit));
            }
            file.take(limit + 1).read_to_end(&mut bytes)?;
            if bytes.len() as u64 > limit {
                return Err(too_big(limit));
            }
        }
        None => {
            let mut file = file;
            file.read_to_end(&mut bytes)?;
        }
    }
    Ok(bytes)
}

/// [`read_regular`] as UTF-8 text.
pub fn read_regular_text(path: &Path) -> io::Result<String> {
    String::from_utf8(read_regular(path, None)?).map_err(|e| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_and_directories_are_refused_without_opening_them() {
        let e = read_regular(Path::new("/dev/zero"), None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "it is a character device, not a regular file"
        );
        let e = open_regular(Path::new("/")).unwrap_err();
        assert_eq!(e.to_string(), "it is a directory, not a regular file");
        assert_eq!(not_regular(Path::new("/nonexistent-ssgi")), None);
    }

    #[test]
    fn the_limit_is_checked_before_reading() {
        let path = std::env::temp_dir().join(format!("ssgi-input-{}", std::process::id()));
        std::fs::write(&path, [b'x'; 2048]).unwrap();
        assert_eq!(read_regular(&path, Some(2048)).unwrap().len(), 2048);
        let e = read_regular(&path, Some(1024)).unwrap_err().to_string();
        assert_eq!(e, "it is larger than the limit of 1024 bytes");
        std::fs::remove_file(&path).unwrap();
    }
}

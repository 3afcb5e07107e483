//! Writing a table run's files into its output directory.

use super::table_report::TableReport;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Write `text` to `path` atomically, creating its directory.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    crate::files::write_atomic(path, text.as_bytes())
}

/// The last frame of every row as `<scene>-<row>.png` in `dir`; returns the file names,
/// per scene, in report order.
pub fn write_last_frames(dir: &Path, report: &TableReport) -> Result<Vec<Vec<String>>> {
    let mut names = Vec::new();
    for s in &report.scenes {
        let mut scene_names = Vec::new();
        for row in &s.rows {
            let Some(image) = &row.image else { continue };
            let Some(rgba) = image.rgba8() else { continue };
            let name = format!("{}-{}.png", file_stem(&s.spec), row.kind.short());
            crate::frontend::png::write_rgba8(&dir.join(&name), image.width, image.height, &rgba)?;
            scene_names.push(name);
        }
        names.push(scene_names);
    }
    Ok(names)
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

/// `report.json`, `report.md` and `<table>.csv` (one row per table row) in `dir`; `extra_md`
/// is appended to the Markdown. Returns the paths written.
pub fn write_report(
    dir: &Path,
    report: &TableReport,
    title: &str,
    extra_md: &str,
) -> Result<Vec<PathBuf>> {
    let json = serde_json::to_string_pretty(report)
        .map_err(|e| Error::Config(format!("JSON encoding failed: {e}")))?;
    let mut md = super::markdown::render(report, title);
    md += extra_md;
    let files = [
        (dir.join("report.json"), json),
        (dir.join("report.md"), md),
        (
            dir.join(format!("{}.csv", report.table)),
            super::csv::summary(report),
        ),
    ];
    let mut written = Vec::new();
    for (path, text) in files {
        write_text(&path, &text)?;
        written.push(path);
    }
    Ok(written)
}

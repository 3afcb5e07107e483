//! What the tables share: the facts a report of its own format opens with (format version,
//! table, command, program, device, whether frames were presented), a pass's median, the
//! warmup count, and the one writer of `report.json`, `report.md` and `<table>.csv`.

use crate::vk::DeviceInfo;
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct TableRun {
    pub version: u32,
    pub table: &'static str,
    pub command: String,
    pub ssgi_version: &'static str,
    pub device: String,
    pub driver: String,
    pub device_type: String,
    pub window: bool,
    pub present_mode: Option<&'static str>,
}

impl TableRun {
    /// report.md's heading for rows that share one size, frame count and warmup: the title,
    /// the command, and where and how it ran.
    pub fn markdown_header(
        &self,
        title: &str,
        size: (u32, u32),
        frames: u32,
        warmup: u32,
    ) -> String {
        format!(
            "# {title}\n\nCommand: `{}`\n\nDevice: {} ({}), {}x{}, {frames} frames measured per row \
             after {warmup} warmup frames, ssgi {}.\n\n",
            self.command, self.device, self.driver, size.0, size.1, self.ssgi_version
        )
    }

    /// Version 1 of `table`'s format, run by `command` on `device`; `present_mode` is the
    /// window's (`None` offscreen).
    pub fn new(
        table: &'static str,
        command: String,
        device: &DeviceInfo,
        present_mode: Option<&'static str>,
    ) -> Self {
        Self {
            version: 1,
            table,
            command,
            ssgi_version: env!("CARGO_PKG_VERSION"),
            device: device.name.clone(),
            driver: device.driver.clone(),
            device_type: device.device_type.clone(),
            window: present_mode.is_some(),
            present_mode,
        }
    }
}

/// Median ms of `pass` in `report` (`None` when it never ran).
pub fn pass_ms(report: &crate::bench::Report, pass: crate::passes::PassId) -> Option<f64> {
    report
        .passes
        .iter()
        .find(|p| p.name == pass.name())
        .and_then(|p| p.median_ms)
}

/// A number with `digits` decimals, or `-`.
pub fn fixed(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".into(), |v| format!("{v:.digits$}"))
}

/// Warmup frames of a table whose rows take `--warmup` as a count (`converged`: none).
pub fn warmup_frames(opts: &crate::bench::TableOptions) -> u32 {
    match opts.warmup {
        crate::bench::warmup::Warmup::Frames(n) => n,
        crate::bench::warmup::Warmup::Converged => 0,
    }
}

/// Create the table's output directory (and its parents), checked as every command's outputs
/// are before it renders.
pub fn create_out(out: &std::path::Path) -> crate::error::Result<()> {
    crate::files::prepare_dir(out, "--out")
}

/// Write a table's `report.json` (of `report`), `report.md` and `<table>.csv` into `out`.
pub fn write_reports<R: Serialize>(
    out: &std::path::Path,
    table: &str,
    report: &R,
    markdown: String,
    csv: String,
) -> crate::error::Result<Vec<std::path::PathBuf>> {
    let json = serde_json::to_string_pretty(report)
        .map_err(|e| crate::error::Error::Config(format!("JSON encoding failed: {e}")))?;
    let files = [
        (out.join("report.json"), json),
        (out.join("report.md"), markdown),
        (out.join(format!("{table}.csv")), csv),
    ];
    let mut written = Vec::new();
    for (path, text) in files {
        crate::bench::output::write_text(&path, &text)?;
        written.push(path);
    }
    Ok(written)
}

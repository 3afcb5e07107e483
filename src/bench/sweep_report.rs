//! What `ssgi sweep` writes: sweep.csv (one row per combination), sweep.json (everything),
//! sweep.md (tables with Pareto-optimal rows marked, per buffer), and one scatter plot per
//! buffer (time on x, ground-truth error on y, one series per technique, the front drawn).

use super::ground_truth::TruthQuality;
use super::measure::Buffer;
use super::output::write_text;
use super::pareto::front_polyline;
use super::scatter::{write_scatter_plot, ScatterPlot, ScatterSeries};
use super::sweep::{error_of, points, time_label, time_of, SweepRow};
use crate::error::Result;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Where and on what the sweep ran, for the reports' headers.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SweepHeader {
    pub command: String,
    pub scene: String,
    pub path: String,
    pub size: [u32; 2],
    pub frames: u32,
    pub warmup: u32,
    /// The warmup ran along the path before its time 0 (`--warmup converged`), not held at
    /// its first camera.
    pub warmup_along_path: bool,
    /// Path time per frame: frame i at i / fps seconds.
    pub fps: f32,
    pub device: String,
    pub driver: String,
    pub reference_rays_per_second: f64,
}

fn buffers_in(rows: &[SweepRow]) -> Vec<Buffer> {
    Buffer::ALL
        .into_iter()
        .filter(|b| rows.iter().any(|r| r.truth.contains_key(b.name())))
        .collect()
}

fn fmt(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v:.6}"))
}

/// sweep.csv: keys, group times, and per buffer the ground-truth and converged errors.
pub fn csv(rows: &[SweepRow]) -> String {
    let keys: Vec<String> = rows.first().map_or(Vec::new(), |r| {
        r.label.iter().map(|(k, _)| k.clone()).collect()
    });
    let groups: Vec<String> = rows
        .first()
        .map_or(Vec::new(), |r| r.ms.keys().cloned().collect());
    let buffers = buffers_in(rows);
    let mut head: Vec<String> = keys.clone();
    head.extend(groups.iter().map(|g| format!("{g}_ms")));
    for b in &buffers {
        let n = b.name();
        head.extend([
            format!("{n}_rmse"),
            format!("{n}_rel_mse"),
            format!("{n}_max_abs"),
            format!("{n}_psnr"),
            format!("{n}_rmse_vs_converged"),
            format!("{n}_pareto"),
        ]);
        if *b == Buffer::Final {
            head.push("final_flip".into());
            head.push("final_flip_vs_converged".into());
        }
    }
    let mut out = head.join(",") + "\n";
    for r in rows {
        let mut cells: Vec<String> = r.label.iter().map(|(_, v)| v.replace(',', ";")).collect();
        cells.extend(groups.iter().map(|g| fmt(r.ms.get(g).copied().flatten())));
        for b in &buffers {
            let t = r.truth.get(b.name());
            cells.push(fmt(t.map(|t| t.error.rmse)));
            cells.push(fmt(t.map(|t| t.error.rel_mse)));
            cells.push(fmt(t.map(|t| t.error.max_abs)));
            cells.push(fmt(t.map(|t| t.error.psnr).filter(|p| p.is_finite())));
            let c = r.converged.get(b.name());
            cells.push(fmt(c.map(|c| c.error.rmse)));
            cells.push(
                r.pareto
                    .get(b.name())
                    .map_or(String::new(), |p| p.to_string()),
            );
            if *b == Buffer::Final {
                cells.push(fmt(t.and_then(|t| t.flip)));
                cells.push(fmt(c.and_then(|c| c.flip)));
            }
        }
        out += &(cells.join(",") + "\n");
    }
    out
}

/// An error in sweep.md: five decimals, "-" where there is none.
fn error_cell(v: Option<f64>) -> String {
    v.map_or("-".into(), |v| format!("{v:.5}"))
}

/// sweep.md: one table per buffer, rows sorted by time, Pareto-optimal rows marked ★.
pub fn markdown(
    header: &SweepHeader,
    rows: &[SweepRow],
    quality: &BTreeMap<String, TruthQuality>,
) -> String {
    let mut s = format!(
        "# Sweep: {} along `{}`\n\n`{}`\n\n{}x{}, {} measured frames ({:.2} s of the path at {} fps) \
         after {} warmup frames {}; \
         device {} (driver {}). Times are medians of per-frame GPU time over the measured \
         frames, all measured in this one process. Errors are of the last frame, against the \
         CPU ground truth (`ssgi reference`) and against the converged estimator of the same \
         technique. ★ = Pareto-optimal in (time, error) for that buffer.\n\n",
        header.scene,
        header.path,
        header.command,
        header.size[0],
        header.size[1],
        header.frames,
        header.frames as f32 / header.fps,
        header.fps,
        header.warmup,
        if header.warmup_along_path {
            "along the path before its time 0 (`--warmup converged`: the moving steady state)"
        } else {
            "at the path's first camera"
        },
        header.device,
        header.driver
    );
    let unsettled: Vec<String> = rows
        .iter()
        .filter(|r| header.warmup_along_path && !r.warmup_settled)
        .map(|r| {
            let pairs: Vec<String> = r.label.iter().map(|(k, v)| format!("{k}={v}")).collect();
            pairs.join(", ")
        })
        .collect();
    if !unsettled.is_empty() {
        s += &format!(
            "**The work counters had not settled by the end of the warmup for:** {}.\n\n",
            unsettled.join("; ")
        );
    }
    s += "## Ground truth\n\n| buffer | samples/pixel | standard error | bound (1/10 of smallest error) | met |\n|---|---|---|---|---|\n";
    for (b, q) in quality {
        s += &format!(
            "| {b} | {} | {:.2e} | {} | {} |\n",
            q.samples_per_pixel,
            q.standard_error,
            q.bound.map_or("-".into(), |v| format!("{v:.2e}")),
            if q.bound_met { "yes" } else { "**no**" }
        );
    }
    s += &format!(
        "\nReference tracing: {:.2} Mrays/s.\n",
        header.reference_rays_per_second / 1e6
    );
    for b in buffers_in(rows) {
        let metric = if b == Buffer::Final { "FLIP" } else { "RMSE" };
        // The final image is also scored in FLIP against its converged estimator.
        let (flip_head, flip_rule) = if b == Buffer::Final {
            (" FLIP vs converged |", "---|")
        } else {
            ("", "")
        };
        s += &format!(
            "\n## {} (time: {})\n\n| | configuration | ms | {metric} vs truth | rel. MSE | PSNR | RMSE vs converged |{flip_head}\n|---|---|---|---|---|---|---|{flip_rule}\n",
            b.name(),
            time_label(b)
        );
        let mut order: Vec<&SweepRow> = rows.iter().collect();
        order.sort_by(|a, c| {
            time_of(a, b)
                .unwrap_or(f64::INFINITY)
                .total_cmp(&time_of(c, b).unwrap_or(f64::INFINITY))
        });
        for r in order {
            let Some(t) = r.truth.get(b.name()) else {
                continue;
            };
            let star = if r.pareto.get(b.name()) == Some(&true) {
                "★"
            } else {
                ""
            };
            let c = r.converged.get(b.name());
            let flip_cell = if b == Buffer::Final {
                format!(" {} |", error_cell(c.and_then(|c| c.flip)))
            } else {
                String::new()
            };
            s += &format!(
                "| {star} | {} | {} | {} | {:.4} | {} | {} |{flip_cell}\n",
                row_label(r, "base"),
                time_of(r, b).map_or("-".into(), |v| format!("{v:.3}")),
                error_cell(error_of(r, b)),
                t.error.rel_mse,
                if t.error.psnr.is_finite() {
                    format!("{:.1}", t.error.psnr)
                } else {
                    "∞".into()
                },
                error_cell(c.map(|e| e.error.rmse)),
            );
        }
    }
    s
}

/// The series a row belongs to: every varied key but the last (the last is the swept axis).
fn series_name(r: &SweepRow) -> String {
    let n = r.label.len().saturating_sub(1);
    let parts: Vec<String> = r.label[..n]
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect();
    if parts.is_empty() {
        "all".into()
    } else {
        parts.join(", ")
    }
}

/// One scatter plot per buffer; returns the files written.
pub fn plots(dir: &Path, header: &SweepHeader, rows: &[SweepRow]) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for b in buffers_in(rows) {
        let mut names: Vec<String> = Vec::new();
        for r in rows {
            let n = series_name(r);
            if !names.contains(&n) {
                names.push(n);
            }
        }
        let series: Vec<ScatterSeries<'_>> = names
            .iter()
            .map(|n| ScatterSeries {
                name: n,
                points: rows
                    .iter()
                    .filter(|r| series_name(r) == *n)
                    .filter_map(|r| Some((time_of(r, b)?, error_of(r, b)?)))
                    .collect(),
            })
            .collect();
        let points = points(rows, b);
        let optimal: Vec<bool> = rows
            .iter()
            .map(|r| r.pareto.get(b.name()) == Some(&true))
            .collect();
        let title = format!(
            "{}: {} ({}x{})",
            header.scene,
            b.name(),
            header.size[0],
            header.size[1]
        );
        let x_label = format!("GPU ms ({})", time_label(b));
        let y_label = if b == Buffer::Final {
            "FLIP vs ground truth"
        } else {
            "RMSE vs ground truth"
        };
        let plot = ScatterPlot {
            title: &title,
            x_label: &x_label,
            y_label,
            series,
            front: front_polyline(&points, &optimal),
            log_y: false,
            size: (900, 600),
        };
        let path = dir.join(format!("sweep_{}.png", b.name()));
        write_scatter_plot(&plot, &path)?;
        written.push(path);
    }
    Ok(written)
}

/// README.md of a sweep's directory: the exact command, the machine, and what each file is,
/// so a results folder explains itself when committed.
fn readme_text(h: &SweepHeader) -> String {
    format!(
        "# Sweep: {} along `{}`, {}x{}\n\nDevice {} (driver {}).\n\n```sh\n{}\n```\n\n\
         `sweep.md`: per buffer, every combination's median GPU time and its error against \
         the CPU ground truth and the converged estimator (Pareto-optimal rows ★); \
         `sweep.csv` / `sweep.json`: the same data (JSON with per-pass medians and the ground \
         truth's standard errors); `sweep_<buffer>.png`: time against ground-truth error with \
         the Pareto front; `maps/NN-<buffer>.png`: absolute error of combination NN's last \
         frame against the ground truth (FLIP for `NN-final-flip.png`), \
         `maps/NN-<buffer>-vs-converged.png` against the converged estimator.\n",
        h.scene, h.path, h.size[0], h.size[1], h.device, h.driver, h.command
    )
}

/// A row's varied keys as `key=value, ...`, or `base` when it varies nothing.
fn row_label(row: &SweepRow, base: &str) -> String {
    if row.label.is_empty() {
        return base.to_string();
    }
    let parts: Vec<String> = row.label.iter().map(|(k, v)| format!("{k}={v}")).collect();
    parts.join(", ")
}

/// README.md of a sweep's `maps/` folder: which combination each prefix is, and the command.
pub fn maps_readme_text(h: &SweepHeader, rows: &[SweepRow]) -> String {
    let mut s = format!(
        "# Error maps of the sweep of {} along `{}`\n\nPer combination and buffer, the \
         absolute error of the last frame against the ground truth (`NN-<buffer>.png`, magma) \
         and FLIP of the final image (`NN-final-flip.png`), and against the converged \
         estimator of the same technique (`NN-<buffer>-vs-converged.png`, the same scale: what \
         sampling and reuse add, without the technique's bias); made by\n\n```sh\n{}\n```\n\n",
        h.scene, h.path, h.command
    );
    for (i, row) in rows.iter().enumerate() {
        s += &format!("- `{i:02}`: {}\n", row_label(row, "the base configuration"));
    }
    s
}

/// Write sweep.csv, sweep.json, sweep.md, README.md and the plots into `dir`.
pub fn write(
    dir: &Path,
    header: &SweepHeader,
    rows: &[SweepRow],
    quality: &BTreeMap<String, TruthQuality>,
) -> Result<Vec<PathBuf>> {
    let mut files = vec![
        dir.join("sweep.csv"),
        dir.join("sweep.json"),
        dir.join("sweep.md"),
    ];
    write_text(&files[0], &csv(rows))?;
    let json = serde_json::json!({
        "version": 1,
        "header": header,
        "ground_truth": quality,
        "rows": rows,
    });
    let text = serde_json::to_string_pretty(&json)
        .map_err(|e| crate::error::Error::Config(e.to_string()))?;
    write_text(&files[1], &text)?;
    write_text(&files[2], &markdown(header, rows, quality))?;
    let readme = dir.join("README.md");
    write_text(&readme, &readme_text(header))?;
    files.push(readme);
    files.extend(plots(dir, header, rows)?);
    Ok(files)
}

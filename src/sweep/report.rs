//! What `ssgi sweep` writes: sweep.csv (one row per combination), sweep.json (everything),
//! sweep.md (tables with Pareto-optimal rows marked, per buffer), and one scatter plot per
//! buffer (time on x, ground-truth error on y, one series per technique, the front drawn).

use super::{error_of, points, time_label, time_of, SweepRow};
use crate::bench::ground_truth::TruthQuality;
use crate::bench::measure::Buffer;
use crate::bench::output::write_text;
use crate::bench::sheet::{Cell, Column, Sheet};
use crate::error::Result;
use crate::plot::pareto::front_polyline;
use crate::plot::scatter::{write_scatter_plot, ScatterPlot, ScatterSeries};
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

/// The sheet of a sweep: per row its keys (CSV) or configuration (Markdown), the groups'
/// times (CSV), and per buffer, one Markdown table each, the time on its axis and the errors
/// against the ground truth and the converged estimator, Pareto-optimal rows marked ★.
fn sheet<'r>(rows: &[SweepRow]) -> Sheet<'static, &'r SweepRow> {
    let buffers = buffers_in(rows);
    let mut sheet = Sheet::new(Vec::new());
    for &b in &buffers {
        let n = b.name();
        sheet.extend([Column::md("", move |r: &&SweepRow| {
            Cell::text(if r.pareto.get(n) == Some(&true) {
                "★"
            } else {
                ""
            })
        })
        .part(n)]);
    }
    sheet.extend([Column::md("configuration", |r: &&SweepRow| {
        Cell::text(row_label(r, "base"))
    })]);
    let first = rows.first();
    for (i, (k, _)) in first.map_or(&[][..], |r| &r.label[..]).iter().enumerate() {
        sheet.extend([Column::csv(k.clone(), move |r: &&SweepRow| {
            // A comma inside a value would read as two keys' worth of fields elsewhere.
            Cell::text(
                r.label
                    .get(i)
                    .map_or(String::new(), |(_, v)| v.replace(',', ";")),
            )
        })]);
    }
    for g in first.map_or(Vec::new(), |r| r.ms.keys().cloned().collect()) {
        let key = format!("{g}_ms");
        sheet.extend([Column::csv(key, move |r: &&SweepRow| {
            Cell::num(r.ms.get(&g).copied().flatten(), 6)
        })]);
    }
    for &b in &buffers {
        let n = b.name();
        let truth = move |r: &SweepRow| r.truth.get(n).cloned();
        let converged = move |r: &SweepRow| r.converged.get(n).cloned();
        let metric = if b == Buffer::Final { "FLIP" } else { "RMSE" };
        let mut columns = vec![
            Column::md("ms", move |r: &&SweepRow| Cell::num(time_of(r, b), 3)),
            Column::md(format!("{metric} vs truth"), move |r: &&SweepRow| {
                Cell::num(error_of(r, b), 5)
            }),
            Column::csv(format!("{n}_rmse"), move |r: &&SweepRow| {
                Cell::num(truth(r).map(|t| t.error.rmse), 6)
            }),
            Column::new(format!("{n}_rel_mse"), "rel. MSE", move |r: &&SweepRow| {
                Cell::num(truth(r).map(|t| t.error.rel_mse), 4)
            }),
            Column::csv(format!("{n}_max_abs"), move |r: &&SweepRow| {
                Cell::num(truth(r).map(|t| t.error.max_abs), 6)
            }),
            Column::csv(format!("{n}_psnr"), move |r: &&SweepRow| {
                Cell::num(truth(r).map(|t| t.error.psnr).filter(|p| p.is_finite()), 6)
            }),
            Column::md("PSNR", move |r: &&SweepRow| {
                match truth(r).map(|t| t.error.psnr) {
                    Some(p) if !p.is_finite() => Cell::text("∞"),
                    p => Cell::num(p, 1),
                }
            }),
            Column::new(
                format!("{n}_rmse_vs_converged"),
                "RMSE vs converged",
                move |r: &&SweepRow| Cell::num(converged(r).map(|c| c.error.rmse), 5),
            ),
            Column::csv(format!("{n}_pareto"), move |r: &&SweepRow| {
                r.pareto
                    .get(n)
                    .map_or(Cell::Empty, |p| Cell::text(p.to_string()))
            }),
        ];
        if b == Buffer::Final {
            columns.extend([
                Column::csv("final_flip", move |r: &&SweepRow| {
                    Cell::num(truth(r).and_then(|t| t.flip), 6)
                }),
                Column::new(
                    "final_flip_vs_converged",
                    "FLIP vs converged",
                    move |r: &&SweepRow| Cell::num(converged(r).and_then(|c| c.flip), 5),
                ),
            ]);
        }
        sheet.extend(columns.into_iter().map(|c| c.part(n)));
    }
    sheet
}

/// sweep.csv: keys, group times, and per buffer the ground-truth and converged errors.
pub fn csv(rows: &[SweepRow]) -> String {
    let refs: Vec<&SweepRow> = rows.iter().collect();
    sheet(rows).csv(&refs)
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
    let sheet = sheet(rows);
    for b in buffers_in(rows) {
        s += &format!("\n## {} (time: {})\n\n", b.name(), time_label(b));
        let mut order: Vec<&SweepRow> = rows
            .iter()
            .filter(|r| r.truth.contains_key(b.name()))
            .collect();
        order.sort_by(|a, c| {
            time_of(a, b)
                .unwrap_or(f64::INFINITY)
                .total_cmp(&time_of(c, b).unwrap_or(f64::INFINITY))
        });
        s += &sheet.markdown_part(&order, b.name());
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

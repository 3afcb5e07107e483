//! `report.md`: a table report as Markdown — run facts and exact configuration, the timing
//! table with the thesis's numbers beside ours, the speed-up ratios, the error table, notes.

use super::measure::Buffer;
use super::reuse_rows::{RowKind, COLUMNS};
use super::table_report::{group_present, TableReport};

fn num(v: Option<f64>, decimals: usize) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.decimals$}"))
}

fn ratio(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.2}x"))
}

/// Column heading of a timing group.
fn heading(group: &str) -> &str {
    match group {
        "ao" => "SSAO",
        "indirect" => "Indirect",
        "reproject" => "Reproject",
        "total" => "Total",
        other => other,
    }
}

pub fn render(r: &TableReport, title: &str) -> String {
    let mut md = format!("# {title}\n\n");
    md += &header(r);
    md += &timing_table(r);
    md += &speedup_table(r);
    md += &error_table(r);
    md += &truth_table(r);
    md += &files_section(r);
    md += "## Notes\n\n";
    for note in r
        .notes
        .iter()
        .chain(r.scenes.iter().filter_map(|s| s.note.as_ref()))
    {
        md += &format!("- {note}\n");
    }
    md += "\n";
    md
}

fn header(r: &TableReport) -> String {
    let config = serde_json::to_string_pretty(&r.base_config).unwrap_or_default();
    let mut md = format!(
        "Produced by `{}` (ssgi {}).\n\n\
         | | |\n|---|---|\n\
         | device | {} ({}) |\n| driver | {} |\n| Vulkan | {} |\n| resolution | {}x{} |\n\
         | frames shown | {} |\n\
         | frames | {} measured per row ({:.2} s of the path at {} fps), after {} warmup frames {} |\n\
         | timing | median per-frame GPU time from timestamp queries, ms; fps = 1000 / ms |\n\
         | thesis | {} |\n\n",
        r.command,
        r.ssgi_version,
        r.device,
        r.device_type,
        r.driver,
        r.api_version,
        r.width,
        r.height,
        match &r.present_mode {
            Some(mode) => format!("presented to a window every frame (present mode {mode})"),
            None => "offscreen (no window)".to_string(),
        },
        r.frames,
        r.frames as f32 / r.fps,
        r.fps,
        r.warmup,
        if r.warmup_along_path {
            "along the path before its time 0 (`--warmup converged`)"
        } else {
            "at the path's first camera"
        },
        r.thesis_setup,
    );
    md += &format!(
        "Rows: **{}** (reverse reprojection cache for AO, shadows and indirect light), **{}** \
         (one fixed pattern per frame), **{}** ({} frame held at the last camera after the \
         frame whose buffers are the reference; timed to show what convergence costs).\n\n",
        RowKind::Reuse.label(r.base_config.effects),
        RowKind::NoReuse.label(r.base_config.effects),
        RowKind::Reference.label(r.base_config.effects),
        super::reuse_rows::REFERENCE_FRAMES,
    );
    md += &format!("Error reference: {}.\n\n", r.reference);
    md += &format!(
        "Base configuration (rows change only `temporal.reuse`, `ao.patterns` and `pcf`, as \
         in each row's `config` in report.json):\n\n```json\n{config}\n```\n\n"
    );
    md
}

/// Timing groups of `COLUMNS` that some row measured (a group whose passes never ran, like
/// indirect light when it is off, gets no column).
fn timing_columns(r: &TableReport) -> Vec<&'static str> {
    COLUMNS
        .into_iter()
        .filter(|g| {
            r.scenes
                .iter()
                .flat_map(|s| &s.rows)
                .any(|row| row.ms.get(*g).copied().flatten().is_some())
        })
        .collect()
}

/// Error buffers that some row has.
fn error_buffers(r: &TableReport) -> Vec<Buffer> {
    Buffer::ALL
        .into_iter()
        .filter(|b| {
            r.scenes
                .iter()
                .flat_map(|s| &s.rows)
                .any(|row| row.error.contains_key(b.name()))
        })
        .collect()
}

fn timing_table(r: &TableReport) -> String {
    let thesis = r.scenes.iter().any(|s| s.thesis.is_some());
    let columns = timing_columns(r);
    let mut md = "## Timing\n\n| Scene | Row |".to_string();
    for g in &columns {
        md += &format!(" {} ms | {} fps |", heading(g), heading(g));
    }
    md += " SSAO pixels / frame | recomputed |";
    let indirect = r.base_config.effects.indirect;
    let thesis_columns = match (thesis, indirect) {
        (false, _) => 0,
        (true, true) => 3,
        (true, false) => 2,
    };
    if thesis {
        md += " thesis SSAO fps |";
        if indirect {
            md += " thesis indirect fps |";
        }
        md += " thesis total fps |";
    }
    md += "\n|---|---|";
    md += &"---:|".repeat(columns.len() * 2 + 2 + thesis_columns);
    md += "\n";
    for s in &r.scenes {
        for row in &s.rows {
            md += &format!("| {} | {} |", s.name, row.label);
            for g in &columns {
                let ms = row.ms.get(*g).copied().flatten();
                md += &format!(" {} | {} |", num(ms, 3), num(ms.map(|m| 1000.0 / m), 1));
            }
            md += &format!(
                " {} | {} |",
                num(row.ssao_pixels_per_frame, 0),
                row.recomputed_fraction
                    .map_or("-".into(), |f| format!("{:.1}%", 100.0 * f))
            );
            if thesis {
                let fps = s.thesis.and_then(|t| match row.kind {
                    RowKind::Reuse => Some(t.reuse),
                    RowKind::NoReuse => Some(t.no_reuse),
                    RowKind::Reference => None,
                });
                match fps {
                    Some(f) if indirect => {
                        md += &format!(" {} | {} | {} |", f.ssao, f.indirect, f.total)
                    }
                    Some(f) => md += &format!(" {} | {} |", f.ssao, f.total),
                    None => md += &" |".repeat(thesis_columns),
                }
            }
            md += "\n";
        }
    }
    md += "\n";
    md
}

/// Our groups beside the thesis's columns.
const SPEEDUP_COLUMNS: [(&str, &str); 3] =
    [("ao", "SSAO"), ("indirect", "Indirect"), ("total", "Total")];

fn speedup_table(r: &TableReport) -> String {
    let mut md = "## Speed-up of reuse over no reuse\n\nOurs: no-reuse ms / reuse ms, \
                  measured in one process on one device. Thesis: reuse fps / no-reuse fps.\n\n\
                  | Scene |"
        .to_string();
    let effects = r.base_config.effects;
    let columns: Vec<(&str, &str)> = SPEEDUP_COLUMNS
        .into_iter()
        .filter(|(g, _)| group_present(g, &effects))
        .collect();
    for (_, name) in &columns {
        md += &format!(" ours {name} | thesis {name} |");
    }
    md += "\n|---|";
    md += &"---:|".repeat(2 * columns.len());
    md += "\n";
    for s in &r.scenes {
        md += &format!("| {} |", s.name);
        for &(group, _) in &columns {
            let thesis = s.thesis_speedups.map(|t| match group {
                "ao" => t.ssao,
                "indirect" => t.indirect,
                _ => t.total,
            });
            md += &format!(
                " {} | {} |",
                ratio(s.speedups.get(group).copied().flatten()),
                ratio(thesis)
            );
        }
        md += "\n";
    }
    md += "\n";
    md
}

fn error_table(r: &TableReport) -> String {
    let mut md = "## Error against the converged reference\n\nLast frame of each row vs the \
                  reference from the same camera, over geometry pixels.\n\n| Scene | Row |"
        .to_string();
    let buffers = error_buffers(r);
    for b in &buffers {
        md += &format!(" {} RMSE | {} max |", b.name(), b.name());
    }
    md += " pixels |\n|---|---|";
    md += &"---:|".repeat(buffers.len() * 2 + 1);
    md += "\n";
    for s in &r.scenes {
        for row in &s.rows {
            md += &format!("| {} | {} |", s.name, row.label);
            let mut pixels = None;
            for b in &buffers {
                match row.error.get(b.name()) {
                    Some(e) => {
                        pixels = Some(e.pixels);
                        md += &format!(" {} | {} |", num(e.rmse, 5), num(e.max_abs, 4));
                        if e.non_finite > 0 {
                            md += &format!(" ({} non-finite) ", e.non_finite);
                        }
                    }
                    None => md += " - | - |",
                }
            }
            md += &format!(" {} |\n", pixels.map_or("-".into(), |p| p.to_string()));
        }
    }
    md += "\n";
    md
}

fn truth_table(r: &TableReport) -> String {
    let mut md = "## Error against the ground truth\n\nLast frame of each row vs the CPU \
                  ray-traced ground truth of the same camera (`ssgi reference`; \
                  docs/REFERENCE.md), over the pixels both cover: RMSE per buffer, FLIP for \
                  the final image.\n\n| Scene | Row |"
        .to_string();
    let buffers = error_buffers(r);
    for b in &buffers {
        md += &format!(" {} RMSE |", b.name());
    }
    md += " final FLIP |\n|---|---|";
    md += &"---:|".repeat(buffers.len() + 1);
    md += "\n";
    for s in &r.scenes {
        for row in &s.rows {
            md += &format!("| {} | {} |", s.name, row.label);
            for b in &buffers {
                let e = row.truth.get(b.name()).map(|t| t.error.rmse);
                md += &format!(" {} |", num(e, 5));
            }
            let flip = row.truth.get("final").and_then(|t| t.flip);
            md += &format!(" {} |\n", num(flip, 4));
        }
    }
    md += "\nGround truth per scene (samples per pixel, standard error; the bound is a tenth \
           of the smallest error measured against it):\n\n";
    for s in &r.scenes {
        let parts: Vec<String> = s
            .ground_truth
            .iter()
            .map(|(b, q)| {
                format!(
                    "{b} {} spp, se {:.1e}{}",
                    q.samples_per_pixel,
                    q.standard_error,
                    if q.bound_met {
                        ""
                    } else {
                        " (above the bound)"
                    }
                )
            })
            .collect();
        md += &format!("- {}: {}\n", s.name, parts.join("; "));
    }
    md += "\n";
    md
}

/// Per scene: its camera path and files (CSV linked, PNG shown).
fn files_section(r: &TableReport) -> String {
    let mut md = "## Per scene\n\n".to_string();
    for s in &r.scenes {
        md += &format!(
            "### {}\n\nScene `{}`: {} triangles (for the box scenes, model + room). Camera \
             path: `{}`.\n\n",
            s.name, s.spec, s.triangles, s.path
        );
        for f in s.files.iter().filter(|f| !f.ends_with(".png")) {
            md += &format!("- [{f}]({f})\n");
        }
        md += "\n";
        for f in s.files.iter().filter(|f| f.ends_with(".png")) {
            md += &format!("![{f}]({f})\n");
        }
        md += "\n";
    }
    md += "Images `<scene>-<row>.png` are the last frame of each row (the reference's is the \
           image the errors are measured against).\n\n";
    md
}

/// Legend of the walkthrough plots.
pub const WALKTHROUGH_LEGEND: &str =
    "Plots: `-time` shows the per-frame GPU time of the whole frame (total), of SSAO (+ blur) \
     and of the indirect light (gather + upsample + fix-up), with reuse and without; `-recomputed` shows the SSAO \
     pixels computed in each frame over width x height (without reuse that is every geometry \
     pixel). The CSV holds the same series, one row per frame.\n\n";

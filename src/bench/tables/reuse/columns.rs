//! `report.md` and `<table>.csv` of the reuse tables (`thesis-4.1`, `thesis-walkthroughs`,
//! `dynamic`): one sheet of every row of every scene (timing, error against the converged
//! reference, error against the ground truth), the CSV holding all of it and the Markdown
//! showing it part by part, with the run's facts, the speed-ups and the notes around it.

use super::report::{group_present, SceneResult, TableReport};
use super::rows::{RowKind, RowResult, COLUMNS, REFERENCE_FRAMES};
use super::thesis::Fps;
use crate::bench::compare::groups;
use crate::bench::measure::Buffer;
use crate::bench::sheet::{notes_section, Cell, Column, Sheet};

/// A row of the sheet: one row of one scene.
pub struct Line<'a> {
    scene: &'a SceneResult,
    row: &'a RowResult,
}

const TIMING: &str = "timing";
const ERROR: &str = "error";
const TRUTH: &str = "truth";

/// Every row of every scene, in report order.
fn lines(r: &TableReport) -> Vec<Line<'_>> {
    r.scenes
        .iter()
        .flat_map(|scene| scene.rows.iter().map(move |row| Line { scene, row }))
        .collect()
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

/// The thesis's columns: our timing group, the CSV key, the heading and the value.
type ThesisColumn = (&'static str, &'static str, &'static str, fn(&Fps) -> f64);
const THESIS_COLUMNS: [ThesisColumn; 3] = [
    ("ao", "ssao", "SSAO", |f| f.ssao),
    ("indirect", "indirect", "Indirect", |f| f.indirect),
    ("total", "total", "Total", |f| f.total),
];

/// The thesis's frame rates for a row's kind (the reference row has none).
fn thesis_fps(l: &Line) -> Option<Fps> {
    l.scene.thesis.and_then(|t| match l.row.kind {
        RowKind::Reuse => Some(t.reuse),
        RowKind::NoReuse => Some(t.no_reuse),
        RowKind::Reference => None,
    })
}

/// The columns of `r`: the groups and buffers its effects have. Markdown shows the groups of
/// `COLUMNS` that some row measured, and the thesis's numbers when a scene has them; the CSV
/// has every column.
fn sheet<'r>(r: &TableReport) -> Sheet<'static, Line<'r>> {
    let effects = r.base_config.effects;
    let measured = |g: &str| {
        r.scenes
            .iter()
            .flat_map(|s| &s.rows)
            .any(|row| row.ms.get(g).copied().flatten().is_some())
    };
    let mut sheet = Sheet::new(vec![
        Column::csv("scene", |l: &Line| Cell::text(&l.scene.spec)),
        Column::md("Scene", |l: &Line| Cell::text(&l.scene.name)),
        Column::csv("row", |l: &Line| Cell::text(l.row.kind.short())),
        Column::md("Row", |l: &Line| Cell::text(&l.row.label)),
    ]);
    for (g, _) in groups()
        .into_iter()
        .filter(|(g, _)| group_present(g, &r.base_config))
    {
        let shown = COLUMNS.contains(&g) && measured(g);
        let ms = move |l: &Line| Cell::num(l.row.ms.get(g).copied().flatten(), 3);
        let fps = move |l: &Line| Cell::num(l.row.fps.get(g).copied().flatten(), 1);
        for mut c in [
            Column::new(format!("{g}_ms"), format!("{} ms", heading(g)), ms),
            Column::new(format!("{g}_fps"), format!("{} fps", heading(g)), fps),
        ] {
            if !shown {
                c = c.csv_only();
            }
            sheet.extend([c.part(TIMING)]);
        }
    }
    sheet.extend([
        Column::new(
            "ssao_pixels_per_frame",
            "SSAO pixels / frame",
            |l: &Line| Cell::num(l.row.ssao_pixels_per_frame, 0),
        )
        .part(TIMING),
        Column::new("recomputed_fraction", "recomputed", |l: &Line| {
            l.row.recomputed_fraction.map_or(Cell::Empty, Cell::Percent)
        })
        .part(TIMING),
    ]);
    let thesis = r.scenes.iter().any(|s| s.thesis.is_some());
    let thesis_columns = THESIS_COLUMNS
        .into_iter()
        .filter(|(g, ..)| *g != "indirect" || effects.indirect);
    for (_, key, _, value) in thesis_columns {
        let name = if key == "ssao" { "SSAO" } else { key };
        let c = Column::new(
            format!("thesis_{key}_fps"),
            format!("thesis {name} fps"),
            move |l: &Line| Cell::num(thesis_fps(l).map(|f| value(&f)), 0),
        )
        .part(TIMING);
        sheet.extend([if thesis { c } else { c.csv_only() }]);
    }
    let buffers: Vec<Buffer> = Buffer::ALL
        .into_iter()
        .filter(|b| b.present(&r.base_config))
        .collect();
    for &b in &buffers {
        let n = b.name();
        let error = move |l: &Line| l.row.error.get(n).cloned();
        sheet.extend([
            Column::new(format!("{n}_rmse"), format!("{n} RMSE"), move |l: &Line| {
                Cell::num(error(l).and_then(|e| e.rmse), 5)
            })
            .part(ERROR),
            Column::new(
                format!("{n}_max_abs"),
                format!("{n} max"),
                move |l: &Line| Cell::num(error(l).and_then(|e| e.max_abs), 4),
            )
            .part(ERROR),
        ]);
    }
    let first = buffers.first().map_or("final", |b| b.name());
    sheet.extend([
        Column::new("non_finite", "non-finite", |l: &Line| {
            Cell::int(l.row.error.values().map(|e| e.non_finite).sum::<usize>())
        })
        .part(ERROR),
        Column::new("pixels", "pixels", move |l: &Line| {
            l.row
                .error
                .get(first)
                .map_or(Cell::Empty, |e| Cell::int(e.pixels))
        })
        .part(ERROR),
    ]);
    for &b in &buffers {
        let n = b.name();
        sheet.extend([Column::new(
            format!("{n}_truth_rmse"),
            format!("{n} RMSE"),
            move |l: &Line| Cell::num(l.row.truth.get(n).map(|t| t.error.rmse), 5),
        )
        .part(TRUTH)]);
    }
    sheet.extend([Column::new("final_truth_flip", "final FLIP", |l: &Line| {
        Cell::num(l.row.truth.get("final").and_then(|t| t.flip), 4)
    })
    .part(TRUTH)]);
    sheet
}

/// `<table>.csv`: every column of every row.
pub fn csv(r: &TableReport) -> String {
    sheet(r).csv(&lines(r))
}

/// `report.md`.
pub fn markdown(r: &TableReport, title: &str) -> String {
    let (sheet, lines) = (sheet(r), lines(r));
    let mut md = format!("# {title}\n\n");
    md += &header(r);
    md += "## Timing\n\n";
    md += &sheet.markdown_part(&lines, TIMING);
    md += &speedups(r);
    md += "\n## Error against the converged reference\n\nLast frame of each row vs the \
           reference from the same camera, over geometry pixels.\n\n";
    md += &sheet.markdown_part(&lines, ERROR);
    md += "\n## Error against the ground truth\n\nLast frame of each row vs the CPU \
           ray-traced ground truth of the same camera (`ssgi reference`; docs/REFERENCE.md), \
           over the pixels both cover: RMSE per buffer, FLIP for the final image.\n\n";
    md += &sheet.markdown_part(&lines, TRUTH);
    md += &truth_quality(r);
    md += &files_section(r);
    md += &notes_section(
        r.notes
            .iter()
            .chain(r.scenes.iter().filter_map(|s| s.note.as_ref())),
    );
    md + "\n"
}

fn header(r: &TableReport) -> String {
    let config = serde_json::to_string_pretty(&r.base_config).unwrap_or_default();
    let presented = match &r.present_mode {
        Some(mode) => format!("presented to a window every frame (present mode {mode})"),
        None => "offscreen (no window)".to_string(),
    };
    let warmup = if r.warmup_along_path {
        "along the path before its time 0 (`--warmup converged`)"
    } else {
        "at the path's first camera"
    };
    let effects = r.base_config.effects;
    format!(
        "Produced by `{}` (ssgi {}).\n\n\
         | | |\n|---|---|\n\
         | device | {} ({}) |\n| driver | {} |\n| Vulkan | {} |\n| resolution | {}x{} |\n\
         | frames shown | {presented} |\n\
         | frames | {} measured per row ({:.2} s of the path at {} fps), after {} warmup frames {warmup} |\n\
         | timing | median per-frame GPU time from timestamp queries, ms; fps = 1000 / ms |\n\
         | thesis | {} |\n\n\
         Rows: **{}** (reverse reprojection cache for AO, shadows and indirect light), **{}** \
         (one fixed pattern per frame), **{}** ({REFERENCE_FRAMES} frame held at the last \
         camera after the frame whose buffers are the reference; timed to show what \
         convergence costs).\n\n\
         Error reference: {}.\n\n\
         Base configuration (rows change only `temporal.reuse`, `ao.patterns` and `pcf`, as in \
         each row's `config` in report.json):\n\n```json\n{config}\n```\n\n",
        r.command,
        r.ssgi_version,
        r.device,
        r.device_type,
        r.driver,
        r.api_version,
        r.width,
        r.height,
        r.frames,
        r.frames as f32 / r.fps,
        r.fps,
        r.warmup,
        r.thesis_setup,
        RowKind::Reuse.label(effects),
        RowKind::NoReuse.label(effects),
        RowKind::Reference.label(effects),
        r.reference,
    )
}

/// Per scene: no-reuse ms / reuse ms beside the thesis's fps ratio, for its columns.
fn speedups(r: &TableReport) -> String {
    let mut sheet = Sheet::new(vec![Column::md("Scene", |s: &&SceneResult| {
        Cell::text(&s.name)
    })]);
    for (g, _, name, thesis) in THESIS_COLUMNS
        .into_iter()
        .filter(|c| group_present(c.0, &r.base_config))
    {
        sheet.extend([
            Column::md(format!("ours {name}"), move |s: &&SceneResult| {
                Cell::times(s.speedups.get(g).copied().flatten())
            }),
            Column::md(format!("thesis {name}"), move |s: &&SceneResult| {
                Cell::times(s.thesis_speedups.map(|f| thesis(&f)))
            }),
        ]);
    }
    let scenes: Vec<&SceneResult> = r.scenes.iter().collect();
    "\n## Speed-up of reuse over no reuse\n\nOurs: no-reuse ms / reuse ms, measured in one \
     process on one device. Thesis: reuse fps / no-reuse fps.\n\n"
        .to_string()
        + &sheet.markdown(&scenes)
}

/// The ground truth's samples and standard error per scene and buffer.
fn truth_quality(r: &TableReport) -> String {
    let mut md = "\nGround truth per scene (samples per pixel, standard error; the bound is a \
                  tenth of the smallest error measured against it):\n\n"
        .to_string();
    for s in &r.scenes {
        let parts: Vec<String> = s
            .ground_truth
            .iter()
            .map(|(b, q)| {
                let above = if q.bound_met {
                    ""
                } else {
                    " (above the bound)"
                };
                format!(
                    "{b} {} spp, se {:.1e}{above}",
                    q.samples_per_pixel, q.standard_error
                )
            })
            .collect();
        md += &format!("- {}: {}\n", s.name, parts.join("; "));
    }
    md + "\n"
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
    md + "Images `<scene>-<row>.png` are the last frame of each row (the reference's is the \
          image the errors are measured against).\n\n"
}

/// Legend of the walkthrough plots.
pub const WALKTHROUGH_LEGEND: &str =
    "Plots: `-time` shows the per-frame GPU time of the whole frame (total), of SSAO (+ blur) \
     and of the indirect light (gather + upsample + fix-up), with reuse and without; \
     `-recomputed` shows the SSAO pixels computed in each frame over width x height (without \
     reuse that is every geometry pixel). The CSV holds the same series, one row per frame.\n\n";

//! A reuse table's per-frame series of one scene (walkthroughs, dynamic): `<stem>.csv`, one
//! row per frame with and without reuse, and its PNG plots of GPU time and recomputed pixels.

use super::report::SceneResult;
use super::rows::{FrameSample, RowKind};
use crate::bench::compare::groups;
use crate::bench::sheet::{Cell, Column, Sheet};
use crate::error::Result;
use crate::plot::line::{
    write_line_plot, LinePlot, Series, NO_REUSE_AO_COLOR, NO_REUSE_COLOR, NO_REUSE_INDIRECT_COLOR,
    REUSE_AO_COLOR, REUSE_COLOR, REUSE_INDIRECT_COLOR,
};
use plotters::style::RGBColor;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Per-frame series for reuse and no reuse: each group's GPU ms and the fraction of pixels
/// whose SSAO was computed (and, with reuse, disoccluded) in that frame; a frame one side
/// lacks has empty fields there.
pub fn frames(reuse: &[FrameSample], no_reuse: &[FrameSample], pixels: u64) -> String {
    let by_frame = |s: &[FrameSample]| -> BTreeMap<u64, FrameSample> {
        s.iter().map(|f| (f.frame, f.clone())).collect()
    };
    let (a, b) = (by_frame(reuse), by_frame(no_reuse));
    let mut sheet = Sheet::new(vec![Column::csv("frame", |f: &u64| Cell::int(*f))]);
    for (kind, side) in [("reuse", &a), ("no_reuse", &b)] {
        for (g, _) in groups() {
            sheet.extend([Column::csv(format!("{kind}_{g}_ms"), move |f: &u64| {
                Cell::num(side.get(f).and_then(|s| s.ms.get(g).copied()), 3)
            })]);
        }
    }
    type Count = fn(&FrameSample) -> Option<u64>;
    let counts: [(&str, &BTreeMap<u64, FrameSample>, Count); 3] = [
        ("reuse_recomputed_fraction", &a, |s| s.ssao_computed_pixels),
        ("no_reuse_recomputed_fraction", &b, |s| {
            s.ssao_computed_pixels
        }),
        ("reuse_disoccluded_fraction", &a, |s| s.disoccluded_pixels),
    ];
    for (key, side, count) in counts {
        sheet.extend([Column::csv(key, move |f: &u64| {
            let n = side.get(f).and_then(count);
            Cell::num(n.map(|n| n as f64 / pixels.max(1) as f64), 4)
        })]);
    }
    let frames: BTreeSet<u64> = a.keys().chain(b.keys()).copied().collect();
    sheet.csv(&frames.into_iter().collect::<Vec<_>>())
}

/// `<stem>.csv`, `<stem>-time.png` and `<stem>-recomputed.png` in `out` (the per-frame time
/// and recomputed pixels with and without reuse); returns their names.
pub fn write_series(s: &SceneResult, stem: &str, out: &Path) -> Result<Vec<String>> {
    let samples = |kind| s.row(kind).map(|r| r.samples()).unwrap_or_default();
    let (reuse, no_reuse) = (samples(RowKind::Reuse), samples(RowKind::NoReuse));
    let pixels = s
        .row(RowKind::Reuse)
        .map_or(1, |r| r.report.width as u64 * r.report.height as u64);
    let csv_name = format!("{stem}.csv");
    crate::bench::output::write_text(&out.join(&csv_name), &frames(&reuse, &no_reuse, pixels))?;
    let ms = |group: &'static str| move |f: &FrameSample| f.ms.get(group).copied();
    let fraction = |f: &FrameSample| f.ssao_computed_pixels.map(|n| n as f64 / pixels as f64);
    let time_name = format!("{stem}-time.png");
    let title = format!("{}: GPU time per frame", s.name);
    write_line_plot(
        &LinePlot {
            title: &title,
            x_label: "frame",
            y_label: "GPU ms",
            series: vec![
                series("total, reuse", REUSE_COLOR, &reuse, ms("total")),
                series("total, no reuse", NO_REUSE_COLOR, &no_reuse, ms("total")),
                series("AO, reuse", REUSE_AO_COLOR, &reuse, ms("ao")),
                series("AO, no reuse", NO_REUSE_AO_COLOR, &no_reuse, ms("ao")),
                series(
                    "indirect, reuse",
                    REUSE_INDIRECT_COLOR,
                    &reuse,
                    ms("indirect"),
                ),
                series(
                    "indirect, no reuse",
                    NO_REUSE_INDIRECT_COLOR,
                    &no_reuse,
                    ms("indirect"),
                ),
            ],
            size: (900, 480),
        },
        &out.join(&time_name),
    )?;
    let recomputed_name = format!("{stem}-recomputed.png");
    let title = format!("{}: recomputed pixels per frame", s.name);
    write_line_plot(
        &LinePlot {
            title: &title,
            x_label: "frame",
            y_label: "fraction of pixels",
            series: vec![
                series("reuse", REUSE_COLOR, &reuse, fraction),
                series("no reuse", NO_REUSE_COLOR, &no_reuse, fraction),
            ],
            size: (900, 480),
        },
        &out.join(&recomputed_name),
    )?;
    Ok(vec![csv_name, time_name, recomputed_name])
}

/// One plot line: `y` of every sample that has it, against the frame number.
fn series<'a>(
    name: &'a str,
    color: RGBColor,
    samples: &[FrameSample],
    y: impl Fn(&FrameSample) -> Option<f64>,
) -> Series<'a> {
    Series {
        name,
        color,
        points: samples
            .iter()
            .filter_map(|f| y(f).map(|v| (f.frame as f64, v)))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(frame: u64, total: f64, computed: u64) -> FrameSample {
        FrameSample {
            frame,
            ms: [("total".to_string(), total)].into_iter().collect(),
            ssao_computed_pixels: Some(computed),
            disoccluded_pixels: None,
        }
    }

    #[test]
    fn frames_align_by_frame_and_leave_gaps_empty() {
        let reuse = [sample(0, 1.0, 10), sample(1, 2.0, 5)];
        let no_reuse = [sample(1, 4.0, 100)];
        let csv = frames(&reuse, &no_reuse, 100);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3, "{csv}");
        let header: Vec<&str> = lines[0].split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let row1: Vec<&str> = lines[2].split(',').collect();
        assert_eq!(row1[0], "1");
        assert_eq!(row1[col("reuse_total_ms")], "2");
        assert_eq!(row1[col("no_reuse_total_ms")], "4");
        assert_eq!(row1[col("reuse_recomputed_fraction")], "0.05");
        assert_eq!(row1[col("no_reuse_recomputed_fraction")], "1");
        let row0: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(row0[col("no_reuse_total_ms")], "");
        assert_eq!(row0.len(), header.len());
    }
}

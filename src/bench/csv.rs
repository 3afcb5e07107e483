//! CSV output: one row per table row (summary), and one row per frame of a walkthrough.
//! Fields are numbers, fixed identifiers and scene names without commas; empty = no value.

use super::compare::groups;
use super::measure::Buffer;
use super::reuse_rows::{FrameSample, RowKind};
use super::table_report::{group_present, TableReport};
use std::collections::BTreeMap;

fn opt(v: Option<f64>) -> String {
    v.map_or_else(String::new, |v| format!("{v}"))
}

fn field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Every row of every scene: timings per group, pixels, errors, the thesis's fps.
pub fn summary(r: &TableReport) -> String {
    let effects = r.base_config.effects;
    let groups: Vec<&str> = groups()
        .iter()
        .map(|(g, _)| *g)
        .filter(|g| group_present(g, &effects))
        .collect();
    let buffers: Vec<Buffer> = Buffer::ALL
        .into_iter()
        .filter(|b| b.present(&effects))
        .collect();
    let mut header = vec!["scene".to_string(), "row".to_string()];
    for g in &groups {
        header.push(format!("{g}_ms"));
        header.push(format!("{g}_fps"));
    }
    header.extend(["ssao_pixels_per_frame", "recomputed_fraction"].map(String::from));
    for b in &buffers {
        header.push(format!("{}_rmse", b.name()));
        header.push(format!("{}_max_abs", b.name()));
    }
    for b in &buffers {
        header.push(format!("{}_truth_rmse", b.name()));
    }
    header.push("final_truth_flip".into());
    header.push("thesis_ssao_fps".into());
    if effects.indirect {
        header.push("thesis_indirect_fps".into());
    }
    header.push("thesis_total_fps".into());
    let mut out = header.join(",") + "\n";
    for s in &r.scenes {
        for row in &s.rows {
            let mut f = vec![field(&s.spec), row.kind.short().to_string()];
            for g in &groups {
                f.push(opt(row.ms.get(*g).copied().flatten()));
                f.push(opt(row.fps.get(*g).copied().flatten()));
            }
            f.push(opt(row.ssao_pixels_per_frame));
            f.push(opt(row.recomputed_fraction));
            for b in &buffers {
                let e = row.error.get(b.name());
                f.push(opt(e.and_then(|e| e.rmse)));
                f.push(opt(e.and_then(|e| e.max_abs)));
            }
            for b in &buffers {
                f.push(opt(row.truth.get(b.name()).map(|t| t.error.rmse)));
            }
            f.push(opt(row.truth.get("final").and_then(|t| t.flip)));
            let thesis = s.thesis.and_then(|t| match row.kind {
                RowKind::Reuse => Some(t.reuse),
                RowKind::NoReuse => Some(t.no_reuse),
                RowKind::Reference => None,
            });
            f.push(opt(thesis.map(|t| t.ssao)));
            if effects.indirect {
                f.push(opt(thesis.map(|t| t.indirect)));
            }
            f.push(opt(thesis.map(|t| t.total)));
            out += &(f.join(",") + "\n");
        }
    }
    out
}

/// Per-frame series of a walkthrough: for reuse and no reuse, each group's GPU ms and the
/// fraction of pixels whose SSAO was computed (and, with reuse, disoccluded) in that frame.
pub fn frames(reuse: &[FrameSample], no_reuse: &[FrameSample], pixels: u64) -> String {
    let by_frame = |s: &[FrameSample]| -> BTreeMap<u64, FrameSample> {
        s.iter().map(|f| (f.frame, f.clone())).collect()
    };
    let (a, b) = (by_frame(reuse), by_frame(no_reuse));
    let mut header = vec!["frame".to_string()];
    for kind in ["reuse", "no_reuse"] {
        for (g, _) in groups() {
            header.push(format!("{kind}_{g}_ms"));
        }
    }
    header.extend(
        [
            "reuse_recomputed_fraction",
            "no_reuse_recomputed_fraction",
            "reuse_disoccluded_fraction",
        ]
        .map(String::from),
    );
    let mut out = header.join(",") + "\n";
    let fraction = |n: Option<u64>| opt(n.map(|n| n as f64 / pixels.max(1) as f64));
    let frames: std::collections::BTreeSet<u64> = a.keys().chain(b.keys()).copied().collect();
    for frame in frames {
        let mut f = vec![frame.to_string()];
        for side in [&a, &b] {
            for (g, _) in groups() {
                f.push(opt(side.get(&frame).and_then(|s| s.ms.get(g).copied())));
            }
        }
        f.push(fraction(a.get(&frame).and_then(|s| s.ssao_computed_pixels)));
        f.push(fraction(b.get(&frame).and_then(|s| s.ssao_computed_pixels)));
        f.push(fraction(a.get(&frame).and_then(|s| s.disoccluded_pixels)));
        out += &(f.join(",") + "\n");
    }
    out
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

    #[test]
    fn fields_with_commas_are_quoted() {
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"x\""), "\"say \"\"x\"\"\"");
        assert_eq!(field("box:venus"), "box:venus");
    }
}

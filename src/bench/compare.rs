//! Two configurations measured in one run, side by side, with speed-up ratios computed from
//! the same process on the same device (never from separate runs).

use super::report::Report;
use super::stats::summarize;
use crate::passes::PassId;
use serde::Serialize;
use std::collections::BTreeMap;

/// A named group of passes whose summed per-frame time is compared (`total`: every pass).
pub type Group = (&'static str, Vec<PassId>);

/// The groups compared, in report order: the reprojection, each effect's (its registration's
/// `timing_groups`, in registry order; effects that do one job by other means, like the
/// indirect light's filters, share a group's name, and the group holds all their passes: a
/// run records one effect's), the total.
pub fn groups() -> Vec<Group> {
    let mut v: Vec<Group> = vec![("reproject", vec![PassId::REPROJECT])];
    let declared = crate::effects::REGISTRY
        .iter()
        .flat_map(|r| r.timing_groups.iter());
    for &(name, passes) in declared {
        match v.iter_mut().find(|(n, _)| *n == name) {
            Some((_, all)) => {
                for p in passes {
                    if !all.contains(p) {
                        all.push(*p);
                    }
                }
            }
            None => v.push((name, passes.to_vec())),
        }
    }
    v.push(("total", Vec::new()));
    v
}

/// Whether the timing row `name` belongs to a group of `passes` (every pass when empty).
pub fn in_group(passes: &[PassId], name: &str) -> bool {
    passes.is_empty() || passes.iter().any(|p| p.name() == name)
}

#[derive(Clone, Debug, Serialize)]
pub struct GroupRatio {
    /// Median milliseconds of the group over the measured frames that recorded it, in the
    /// first and second configuration.
    pub first_ms: Option<f64>,
    pub second_ms: Option<f64>,
    /// second / first of the medians: how many times faster the first configuration is.
    pub speedup: Option<f64>,
    /// Mean milliseconds of the group over every measured frame of the path, a frame that
    /// skipped it counting 0: the path's GPU time in the group over its frame count.
    pub first_path_ms: Option<f64>,
    pub second_path_ms: Option<f64>,
    /// second / first of the path means: the speed-up over the whole walk, what a user pays.
    pub path_speedup: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    pub version: u32,
    pub what: String,
    pub labels: [String; 2],
    pub runs: [Report; 2],
    pub groups: BTreeMap<String, GroupRatio>,
}

/// Per measured frame, the sum of `passes` (all passes when empty), or `None` where the
/// frame recorded none of them (skipped).
fn group_sums(report: &Report, passes: &[PassId]) -> Vec<Option<f64>> {
    report
        .frames
        .iter()
        .filter(|f| !f.warmup)
        .map(|f| {
            let mut ran = f
                .passes
                .iter()
                .filter(|(n, _)| in_group(passes, n))
                .peekable();
            ran.peek()?;
            Some(ran.map(|(_, ms)| ms).sum())
        })
        .collect()
}

/// Median over the measured frames that recorded the group of its per-frame sum of `passes`
/// (all passes when empty); `None` when no frame did.
pub fn group_median(report: &Report, passes: &[PassId]) -> Option<f64> {
    let sums: Vec<f64> = group_sums(report, passes).into_iter().flatten().collect();
    summarize(&sums).map(|s| s.median)
}

/// Mean over every measured frame of the per-frame sum of `passes`, a frame that recorded
/// none of them counting 0; `None` when no frame recorded any.
pub fn group_path_mean(report: &Report, passes: &[PassId]) -> Option<f64> {
    let sums = group_sums(report, passes);
    if sums.iter().all(Option::is_none) {
        return None;
    }
    Some(sums.iter().flatten().sum::<f64>() / sums.len() as f64)
}

/// b / a where both are positive.
fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if a > 0.0 && b > 0.0 => Some(b / a),
        _ => None,
    }
}

impl Comparison {
    pub fn new(what: &str, labels: [&str; 2], runs: [Report; 2]) -> Self {
        let groups = groups()
            .iter()
            .map(|(name, passes)| {
                let first = group_median(&runs[0], passes);
                let second = group_median(&runs[1], passes);
                let first_path = group_path_mean(&runs[0], passes);
                let second_path = group_path_mean(&runs[1], passes);
                (
                    name.to_string(),
                    GroupRatio {
                        first_ms: first,
                        second_ms: second,
                        speedup: ratio(first, second),
                        first_path_ms: first_path,
                        second_path_ms: second_path,
                        path_speedup: ratio(first_path, second_path),
                    },
                )
            })
            .collect();
        Self {
            version: super::report::REPORT_VERSION,
            what: what.to_string(),
            labels: labels.map(str::to_string),
            runs,
            groups,
        }
    }

    pub fn table(&self) -> String {
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
        let x = |v: Option<f64>| v.map_or("-".into(), |s| format!("{s:.2}x"));
        let mut out = format!(
            "{}: {} vs {} over the same camera path on the same device: GPU ms per frame, the \
             median over the frames that ran the group and the mean over every frame of the \
             path (a skipped frame costs 0)\n",
            self.what, self.labels[0], self.labels[1]
        );
        out += &format!(
            "{:<9} {:>14} {:>14} {:>9}   {:>14} {:>14} {:>9}\n",
            "group",
            format!("{} med", self.labels[0]),
            format!("{} med", self.labels[1]),
            "speed-up",
            format!("{} path", self.labels[0]),
            format!("{} path", self.labels[1]),
            "path"
        );
        for (name, g) in &self.groups {
            out += &format!(
                "{:<9} {:>14} {:>14} {:>9}   {:>14} {:>14} {:>9}\n",
                name,
                f(g.first_ms),
                f(g.second_ms),
                x(g.speedup),
                f(g.first_path_ms),
                f(g.second_path_ms),
                x(g.path_speedup)
            );
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::report::{FrameRow, TotalRow};

    fn frame(index: u64, passes: &[(&str, f64)]) -> FrameRow {
        FrameRow {
            index,
            warmup: false,
            passes: passes.iter().map(|(n, ms)| (n.to_string(), *ms)).collect(),
            skipped: Vec::new(),
            skip_reasons: BTreeMap::new(),
            counters: BTreeMap::new(),
            flicker: None,
        }
    }

    fn report(frames: Vec<FrameRow>) -> Report {
        Report {
            version: 1,
            device: String::new(),
            driver: String::new(),
            width: 1,
            height: 1,
            config: serde_json::Value::Null,
            measured_frames: frames.len(),
            skipped_frames: frames.iter().filter(|f| f.passes.is_empty()).count(),
            passes: Vec::new(),
            total: TotalRow {
                median_ms: None,
                mean_ms: None,
                p95_ms: None,
                fps_equivalent: None,
            },
            counter_means: BTreeMap::new(),
            frames,
            flicker: None,
        }
    }

    /// A path that ends and holds: most frames of both rows are skipped. Every group both
    /// rows ran has a median over its recorded frames and a path mean with skipped frames
    /// at 0, and the path speed-up is the ratio of the walk's GPU time.
    #[test]
    fn groups_survive_skipped_frames() {
        let walk = |ms: f64, recorded: u64| {
            (0..10)
                .map(|i| match i < recorded {
                    true => frame(i, &[("ssao", ms), ("gbuffer", 1.0)]),
                    false => frame(i, &[]),
                })
                .collect::<Vec<_>>()
        };
        let c = Comparison::new(
            "reuse",
            ["on", "off"],
            [report(walk(1.0, 3)), report(walk(4.0, 2))],
        );
        let ao = &c.groups["ao"];
        assert_eq!(
            (ao.first_ms, ao.second_ms, ao.speedup),
            (Some(1.0), Some(4.0), Some(4.0))
        );
        assert_eq!(
            (ao.first_path_ms, ao.second_path_ms),
            (Some(0.3), Some(0.8))
        );
        assert!((ao.path_speedup.unwrap() - 8.0 / 3.0).abs() < 1e-12);
        let total = &c.groups["total"];
        assert_eq!((total.first_ms, total.second_ms), (Some(2.0), Some(5.0)));
        // A group neither row ran has no numbers.
        let indirect = &c.groups["indirect"];
        assert_eq!((indirect.first_ms, indirect.path_speedup), (None, None));
        assert!(!c
            .table()
            .lines()
            .find(|l| l.starts_with("ao"))
            .unwrap()
            .contains('-'));
    }
}

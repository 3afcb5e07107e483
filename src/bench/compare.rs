//! Two configurations measured in one run, side by side, with speed-up ratios computed from
//! the same process on the same device (never from separate runs).

use super::report::Report;
use super::stats::summarize;
use crate::passes::PassId;
use serde::Serialize;
use std::collections::BTreeMap;

/// Pass groups whose summed per-frame time is compared.
pub const GROUPS: &[(&str, &[PassId])] = &[
    ("reproject", &[PassId::Reproject]),
    (
        "ao",
        &[
            PassId::AoPositionChain,
            PassId::Ssao,
            PassId::SsaoRefresh,
            PassId::Blur,
        ],
    ),
    ("shadow", &[PassId::Shadow, PassId::ShadowRefresh]),
    ("direct", &[PassId::Direct]),
    (
        "indirect",
        &[
            PassId::IndirectGather,
            PassId::IndirectUpsample,
            PassId::IndirectFixup,
            PassId::IndirectRefresh,
        ],
    ),
    (
        "ssdo",
        &[
            PassId::SsdoSamples,
            PassId::Ssdo,
            PassId::SsdoBounce,
            PassId::SsdoRefresh,
            PassId::SsdoResolve,
            PassId::SsdoBilateral,
            PassId::SsdoUpsample,
        ],
    ),
    ("total", &[]),
];

/// Whether the timing row `name` belongs to a group of `passes` (every pass when empty).
pub fn in_group(passes: &[PassId], name: &str) -> bool {
    passes.is_empty() || passes.iter().any(|p| p.name() == name)
}

#[derive(Clone, Debug, Serialize)]
pub struct GroupRatio {
    /// Median per-frame milliseconds of the group in the first and second configuration.
    pub first_ms: Option<f64>,
    pub second_ms: Option<f64>,
    /// second / first: how many times faster the first configuration is.
    pub speedup: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    pub version: u32,
    pub what: String,
    pub labels: [String; 2],
    pub runs: [Report; 2],
    pub groups: BTreeMap<String, GroupRatio>,
}

/// Median over measured frames of the per-frame sum of `passes` (all passes when empty).
pub fn group_median(report: &Report, passes: &[PassId]) -> Option<f64> {
    let sums: Vec<f64> = report
        .frames
        .iter()
        .filter(|f| !f.warmup)
        .map(|f| {
            f.passes
                .iter()
                .filter(|(n, _)| in_group(passes, n))
                .map(|(_, ms)| ms)
                .sum()
        })
        .collect();
    summarize(&sums).map(|s| s.median).filter(|m| *m > 0.0)
}

impl Comparison {
    pub fn new(what: &str, labels: [&str; 2], runs: [Report; 2]) -> Self {
        let groups = GROUPS
            .iter()
            .map(|(name, passes)| {
                let first = group_median(&runs[0], passes);
                let second = group_median(&runs[1], passes);
                let speedup = match (first, second) {
                    (Some(a), Some(b)) => Some(b / a),
                    _ => None,
                };
                (
                    name.to_string(),
                    GroupRatio {
                        first_ms: first,
                        second_ms: second,
                        speedup,
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
        let mut out = format!(
            "{}: {} vs {} (median per-frame GPU ms over the same camera path, same device)\n",
            self.what, self.labels[0], self.labels[1]
        );
        out += &format!(
            "{:<8} {:>14} {:>14} {:>9}\n",
            "group", self.labels[0], self.labels[1], "speed-up"
        );
        for (name, g) in &self.groups {
            out += &format!(
                "{:<8} {:>14} {:>14} {:>9}\n",
                name,
                f(g.first_ms),
                f(g.second_ms),
                g.speedup.map_or("-".into(), |s| format!("{s:.2}x"))
            );
        }
        out
    }
}

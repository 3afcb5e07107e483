//! The benchmark report: per-pass statistics and per-frame timings, as a table and as JSON.
//!
//! JSON format, version 1 (later versions only add fields):
//! ```text
//! { "version": 1, "device": str, "driver": str, "width": u32, "height": u32,
//!   "config": { ... },   // measure::report_config: scene, path, run length, render config, device
//!   "passes": [ { "name", "median_ms", "mean_ms", "p95_ms", "fps_equivalent",
//!                 "recorded", "skipped" } ],          // over measured frames (after warmup);
//!                                                     // times are null if never recorded
//!   "total":  { "median_ms", "mean_ms", "p95_ms", "fps_equivalent" },  // sum of passes per frame,
//!                                                     // over the measured frames that did work
//!   "skipped_frames": n,  // measured frames that recorded no pass (`--skip-unchanged`)
//!   "counter_means": { name: mean },  // each counter's mean over measured frames, and
//!                                     // <effect>_samples_per_pixel = sum of <effect>_samples
//!                                     //   / sum of <effect>_computed_pixels,
//!                                     // <pass>_lane_efficiency = sum of <pass>_active_invocations
//!                                     //   / sum of <pass>_invocations
//!   "frames": [ { "index", "warmup", "passes": { name: ms }, "skipped": [name],
//!                 "skip_reasons": { name: "unchanged" | "converged" },
//!                 "counters": { name: n } } ] }     // every frame, warmup ones marked
//! ```

use super::stats::summarize;
use crate::vk::FrameTiming;
use serde::Serialize;
use std::collections::BTreeMap;

pub const REPORT_VERSION: u32 = 1;

#[derive(Clone, Debug, Serialize)]
pub struct PassRow {
    pub name: String,
    pub median_ms: Option<f64>,
    pub mean_ms: Option<f64>,
    pub p95_ms: Option<f64>,
    pub fps_equivalent: Option<f64>,
    pub recorded: usize,
    pub skipped: usize,
}

#[derive(Clone, Debug, Serialize)]
pub struct TotalRow {
    pub median_ms: Option<f64>,
    pub mean_ms: Option<f64>,
    pub p95_ms: Option<f64>,
    pub fps_equivalent: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct FrameRow {
    pub index: u64,
    /// A warmup frame: rendered, left out of `passes` and `total`.
    pub warmup: bool,
    pub passes: BTreeMap<String, f64>,
    pub skipped: Vec<String>,
    /// Why each skipped pass was skipped.
    pub skip_reasons: BTreeMap<String, &'static str>,
    pub counters: BTreeMap<String, u64>,
    /// With `bench --flicker`: this frame's difference from the frame before it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flicker: Option<FrameFlicker>,
}

/// Chen et al.'s flicker measure for one frame: the mean squared RGB difference from the
/// previous frame, of the output (0..1 as encoded) and of the indirect light (linear).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FrameFlicker {
    pub final_msd: f64,
    pub indirect_msd: Option<f64>,
}

/// The flicker measure over the measured frames (`bench --flicker`).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FlickerSummary {
    pub final_msd_mean: Option<f64>,
    pub indirect_msd_mean: Option<f64>,
    /// Chen et al.: flicker is barely notable below this.
    pub threshold: f64,
    /// Measured frames whose output difference is below the threshold.
    pub frames_below: usize,
}

/// "The flickering becomes barely notable when the measured difference is less than 2.5e-5."
pub const FLICKER_THRESHOLD: f64 = 2.5e-5;

#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub version: u32,
    pub device: String,
    pub driver: String,
    pub width: u32,
    pub height: u32,
    pub config: serde_json::Value,
    /// Frames after warmup, over which `passes` and `total` are computed.
    pub measured_frames: usize,
    /// Measured frames that recorded no pass at all: left out of `total`.
    pub skipped_frames: usize,
    pub passes: Vec<PassRow>,
    pub total: TotalRow,
    pub counter_means: BTreeMap<String, f64>,
    pub frames: Vec<FrameRow>,
    /// With `bench --flicker`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flicker: Option<FlickerSummary>,
}

/// Each counter's mean over the measured frames that report it, and for an effect that counts
/// both `<effect>_samples` and `<effect>_computed_pixels`, its mean sample count per computed
/// pixel, `<effect>_samples_per_pixel` (a ratio of sums: frames weigh by their pixels).
fn counter_means(measured: &[&FrameTiming]) -> BTreeMap<String, f64> {
    let mut sums: BTreeMap<String, (f64, usize)> = BTreeMap::new();
    for t in measured {
        for (name, v) in &t.counters {
            let e = sums.entry(name.to_string()).or_default();
            e.0 += *v as f64;
            e.1 += 1;
        }
    }
    let mut means: BTreeMap<String, f64> = sums
        .iter()
        .map(|(n, (sum, count))| (n.clone(), sum / *count as f64))
        .collect();
    for (name, (samples, _)) in &sums {
        let Some(effect) = name.strip_suffix("_samples") else {
            continue;
        };
        match sums.get(&format!("{effect}_computed_pixels")) {
            Some((pixels, _)) if *pixels > 0.0 => {
                means.insert(format!("{effect}_samples_per_pixel"), samples / pixels);
            }
            _ => {}
        }
    }
    for (pass, efficiency) in lane_efficiencies(&sums) {
        means.insert(format!("{pass}_lane_efficiency"), efficiency);
    }
    means
}

/// Per pass with work-efficiency counters (`<pass>_invocations`, `<pass>_active_invocations`):
/// active over launched lanes, a ratio of sums over the frames (frames weigh by their lanes).
/// A GPU charges a launched lane whether or not it works; lavapipe charges the work.
pub(crate) fn lane_efficiencies(sums: &BTreeMap<String, (f64, usize)>) -> Vec<(String, f64)> {
    sums.iter()
        .filter_map(|(name, (launched, _))| {
            let pass = name.strip_suffix("_invocations")?;
            if pass.ends_with("_active") || *launched <= 0.0 {
                return None;
            }
            let (active, _) = sums.get(&format!("{pass}_active_invocations"))?;
            Some((pass.to_string(), active / launched))
        })
        .collect()
}

fn fps(ms: Option<f64>) -> Option<f64> {
    ms.filter(|m| *m > 0.0).map(|m| 1000.0 / m)
}

impl Report {
    /// Build from every frame's timing; statistics use frames with index >= `warmup`, in the
    /// order of `pass_order`.
    pub fn new(
        device: &crate::vk::DeviceInfo,
        width: u32,
        height: u32,
        config: serde_json::Value,
        pass_order: &[&str],
        timings: &[FrameTiming],
        warmup: u64,
    ) -> Self {
        let measured: Vec<&FrameTiming> = timings.iter().filter(|t| t.frame >= warmup).collect();
        // Rows for the passes this configuration has (ran or was skipped at least once).
        let present = |name: &&&str| {
            timings
                .iter()
                .any(|t| t.passes.iter().any(|(n, _)| n == *name) || t.skipped(name))
        };
        let passes = pass_order
            .iter()
            .filter(present)
            .map(|name| {
                let times: Vec<f64> = measured
                    .iter()
                    .flat_map(|t| t.passes.iter())
                    .filter(|(n, _)| n == name)
                    .filter_map(|(_, ms)| *ms)
                    .collect();
                let recorded = measured
                    .iter()
                    .filter(|t| t.passes.iter().any(|(n, _)| n == name))
                    .count();
                let skipped = measured.iter().filter(|t| t.skipped(name)).count();
                let s = summarize(&times);
                PassRow {
                    name: name.to_string(),
                    median_ms: s.map(|s| s.median),
                    mean_ms: s.map(|s| s.mean),
                    p95_ms: s.map(|s| s.p95),
                    fps_equivalent: fps(s.map(|s| s.median)),
                    recorded,
                    skipped,
                }
            })
            .collect();
        // A frame that recorded nothing (every pass unchanged or converged) is counted apart,
        // so it does not pull the frame-time statistics towards zero.
        let worked: Vec<&&FrameTiming> = measured.iter().filter(|t| !t.passes.is_empty()).collect();
        let totals: Vec<f64> = worked
            .iter()
            .map(|t| t.passes.iter().filter_map(|(_, ms)| *ms).sum())
            .collect();
        let s = summarize(&totals);
        let frames = timings
            .iter()
            .map(|t| FrameRow {
                index: t.frame,
                warmup: t.frame < warmup,
                passes: t
                    .passes
                    .iter()
                    .filter_map(|(n, ms)| ms.map(|ms| (n.to_string(), ms)))
                    .collect(),
                skipped: t.skipped.iter().map(|s| s.pass.to_string()).collect(),
                skip_reasons: t
                    .skipped
                    .iter()
                    .map(|s| (s.pass.to_string(), s.reason.name()))
                    .collect(),
                counters: t
                    .counters
                    .iter()
                    .map(|(n, v)| (n.to_string(), *v))
                    .collect(),
                flicker: None,
            })
            .collect();
        Report {
            version: REPORT_VERSION,
            device: device.name.clone(),
            driver: device.driver.clone(),
            width,
            height,
            config,
            measured_frames: measured.len(),
            skipped_frames: measured.len() - worked.len(),
            passes,
            total: TotalRow {
                median_ms: s.map(|s| s.median),
                mean_ms: s.map(|s| s.mean),
                p95_ms: s.map(|s| s.p95),
                fps_equivalent: fps(s.map(|s| s.median)),
            },
            counter_means: counter_means(&measured),
            frames,
            flicker: None,
        }
    }

    /// Add the flicker measure of frames (index, measure) to their rows and summarize it
    /// over the measured (non-warmup) frames.
    pub fn attach_flicker(&mut self, measures: &[(u64, FrameFlicker)]) {
        for (index, f) in measures {
            if let Some(row) = self.frames.iter_mut().find(|r| r.index == *index) {
                row.flicker = Some(*f);
            }
        }
        let measured: Vec<&FrameFlicker> = self
            .frames
            .iter()
            .filter(|r| !r.warmup)
            .filter_map(|r| r.flicker.as_ref())
            .collect();
        let mean = |v: Vec<f64>| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
        self.flicker = Some(FlickerSummary {
            final_msd_mean: mean(measured.iter().map(|f| f.final_msd).collect()),
            indirect_msd_mean: mean(measured.iter().filter_map(|f| f.indirect_msd).collect()),
            threshold: FLICKER_THRESHOLD,
            frames_below: measured
                .iter()
                .filter(|f| f.final_msd < FLICKER_THRESHOLD)
                .count(),
        });
    }

    /// The human-readable table.
    pub fn table(&self) -> String {
        let mut out = format!(
            "{} ({}) {}x{}, {} frames measured\n",
            self.device, self.driver, self.width, self.height, self.measured_frames
        );
        if self.skipped_frames > 0 {
            out += &format!(
                "{} of them skipped entirely (nothing changed; `total` is over the other {})\n",
                self.skipped_frames,
                self.measured_frames - self.skipped_frames
            );
        }
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
        let f1 = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1}"));
        out += &format!(
            "{:<18} {:>10} {:>10} {:>10} {:>10} {:>9} {:>8}\n",
            "pass", "median ms", "mean ms", "p95 ms", "fps equiv", "recorded", "skipped"
        );
        for p in &self.passes {
            out += &format!(
                "{:<18} {:>10} {:>10} {:>10} {:>10} {:>9} {:>8}\n",
                p.name,
                f(p.median_ms),
                f(p.mean_ms),
                f(p.p95_ms),
                f1(p.fps_equivalent),
                p.recorded,
                p.skipped
            );
        }
        out += &format!(
            "{:<18} {:>10} {:>10} {:>10} {:>10}\n",
            "total",
            f(self.total.median_ms),
            f(self.total.mean_ms),
            f(self.total.p95_ms),
            f1(self.total.fps_equivalent)
        );
        if !self.counter_means.is_empty() {
            let means: Vec<String> = self
                .counter_means
                .iter()
                .map(|(n, v)| format!("{n} {v:.1}"))
                .collect();
            out += &format!("counters (mean per frame): {}\n", means.join(", "));
            let lanes: Vec<String> = self
                .counter_means
                .iter()
                .filter_map(|(n, v)| {
                    Some(format!("{} {v:.2}", n.strip_suffix("_lane_efficiency")?))
                })
                .collect();
            if !lanes.is_empty() {
                out += &format!(
                    "lane efficiency (active / launched invocations): {}\n",
                    lanes.join(", ")
                );
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(counters: Vec<(&'static str, u64)>) -> FrameTiming {
        FrameTiming {
            frame: 0,
            passes: Vec::new(),
            skipped: Vec::new(),
            counters,
        }
    }

    #[test]
    fn counter_means_average_and_samples_per_pixel_weighs_by_pixels() {
        let a = frame(vec![("fx_computed_pixels", 100), ("fx_samples", 1000)]);
        let b = frame(vec![("fx_computed_pixels", 300), ("fx_samples", 15000)]);
        let m = counter_means(&[&a, &b]);
        assert_eq!(m["fx_computed_pixels"], 200.0);
        assert_eq!(m["fx_samples"], 8000.0);
        // 16000 samples over 400 pixels, not the mean of 10 and 50.
        assert_eq!(m["fx_samples_per_pixel"], 40.0);
        let lanes = counter_means(&[
            &frame(vec![
                ("indirect_fixup_invocations", 128),
                ("indirect_fixup_active_invocations", 64),
            ]),
            &frame(vec![
                ("indirect_fixup_invocations", 64),
                ("indirect_fixup_active_invocations", 64),
            ]),
        ]);
        assert_eq!(lanes["indirect_fixup_lane_efficiency"], 128.0 / 192.0);
        let none = counter_means(&[&frame(vec![("fx_computed_pixels", 0), ("fx_samples", 0)])]);
        assert!(!none.contains_key("fx_samples_per_pixel"));
    }
}

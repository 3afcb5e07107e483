//! The last second of frames for the overlay: per-pass GPU time (median and p95), the
//! thesis's timing groups summed per frame, the frame rate, the counters' means and the lane
//! efficiency of the passes that count their invocations.

use crate::bench::compare::{groups, in_group};
use crate::bench::report::lane_efficiencies;
use crate::bench::stats::{summarize, Summary};
use crate::vk::FrameTiming;
use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

/// How far back the overlay's statistics reach.
pub const WINDOW: Duration = Duration::from_secs(1);

/// Frames received within the last [`WINDOW`].
#[derive(Default)]
pub struct History {
    gpu: VecDeque<(Instant, FrameTiming)>,
    wall: VecDeque<(Instant, f64)>,
}

/// One timing row: a pass, or a group (its passes summed per frame).
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub name: String,
    pub time: Summary,
    /// Frames of the window that recorded it.
    pub frames: usize,
}

/// A group and the passes in it that ran within the window.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupRows {
    pub group: Row,
    pub passes: Vec<Row>,
}

/// What the overlay shows of the last second.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Window {
    /// Presented frames per second (from the median frame time) and the median wall-clock
    /// frame time.
    pub fps: f64,
    pub frame_ms: Option<f64>,
    /// The recorded frames' GPU total (every timed pass summed per frame).
    pub total: Option<Row>,
    pub groups: Vec<GroupRows>,
    /// Passes in no group (the G-buffer, composite, antialiasing, the overlay itself).
    pub other: Vec<Row>,
    /// Frames timed, and how many of them recorded nothing (nothing changed).
    pub timed: usize,
    pub skipped: usize,
    /// Counter means over the recorded frames, in first-seen order.
    pub counters: Vec<(&'static str, f64)>,
    /// Per counting pass: active over launched invocations, summed over the window.
    pub lane_efficiency: Vec<(String, f64)>,
}

impl History {
    pub fn add_gpu(&mut self, now: Instant, t: FrameTiming) {
        self.gpu.push_back((now, t));
        self.trim(now);
    }

    pub fn add_wall(&mut self, now: Instant, ms: f64) {
        self.wall.push_back((now, ms));
        self.trim(now);
    }

    /// Drop what is older than the window, but the newest entry: a device slower than a
    /// frame a second (lavapipe at large sizes) still shows its last frame.
    fn trim(&mut self, now: Instant) {
        let old = |t: &Instant| now.saturating_duration_since(*t) > WINDOW;
        while self.gpu.len() > 1 && self.gpu.front().is_some_and(|(t, _)| old(t)) {
            self.gpu.pop_front();
        }
        while self.wall.len() > 1 && self.wall.front().is_some_and(|(t, _)| old(t)) {
            self.wall.pop_front();
        }
    }

    /// The GPU timings within the window before `now`, oldest first, and the seconds they
    /// span (from the oldest's arrival).
    pub fn frames(&mut self, now: Instant) -> (Vec<FrameTiming>, f64) {
        self.trim(now);
        let span = self.gpu.front().map_or(0.0, |(t, _)| {
            now.saturating_duration_since(*t).as_secs_f64()
        });
        (self.gpu.iter().map(|(_, t)| t.clone()).collect(), span)
    }

    /// The statistics of the frames within the window before `now`.
    pub fn window(&mut self, now: Instant) -> Window {
        self.trim(now);
        let frames: Vec<&FrameTiming> = self.gpu.iter().map(|(_, t)| t).collect();
        let recorded: Vec<&FrameTiming> = frames
            .iter()
            .copied()
            .filter(|t| t.passes.iter().any(|(_, ms)| ms.is_some()))
            .collect();
        let walls: Vec<f64> = self.wall.iter().map(|(_, ms)| *ms).collect();
        let frame_ms = summarize(&walls).map(|s| s.median);
        let mut w = Window {
            // From the median frame time: steady under a one-frame hitch.
            fps: frame_ms
                .filter(|ms| *ms > 0.0)
                .map_or(0.0, |ms| 1000.0 / ms),
            frame_ms,
            timed: frames.len(),
            skipped: frames.len() - recorded.len(),
            ..Window::default()
        };
        let pass_names = first_seen(recorded.iter().flat_map(|t| {
            t.passes
                .iter()
                .filter(|(_, ms)| ms.is_some())
                .map(|(n, _)| *n)
        }));
        let row = |name: &str, keep: &dyn Fn(&str) -> bool| -> Option<Row> {
            let sums: Vec<f64> = recorded
                .iter()
                .filter(|t| t.passes.iter().any(|(n, ms)| ms.is_some() && keep(n)))
                .map(|t| {
                    t.passes
                        .iter()
                        .filter(|(n, _)| keep(n))
                        .filter_map(|(_, ms)| *ms)
                        .sum()
                })
                .collect();
            Some(Row {
                name: name.to_string(),
                time: summarize(&sums)?,
                frames: sums.len(),
            })
        };
        let mut grouped = Vec::new();
        for (name, passes) in groups() {
            if passes.is_empty() {
                w.total = row(name, &|_| true);
                continue;
            }
            let Some(group) = row(name, &|n| in_group(&passes, n)) else {
                continue;
            };
            let members: Vec<Row> = pass_names
                .iter()
                .filter(|n| in_group(&passes, n))
                .filter_map(|n| row(n, &|m| m == *n))
                .collect();
            grouped.extend(members.iter().map(|r| r.name.clone()));
            w.groups.push(GroupRows {
                group,
                passes: members,
            });
        }
        w.other = pass_names
            .iter()
            .filter(|n| !grouped.iter().any(|g| g == *n))
            .filter_map(|n| row(n, &|m| m == *n))
            .collect();
        let counter_names = first_seen(
            recorded
                .iter()
                .flat_map(|t| t.counters.iter().map(|(n, _)| *n)),
        );
        let mut sums = BTreeMap::new();
        for name in counter_names {
            let values: Vec<u64> = recorded
                .iter()
                .filter_map(|t| t.counters.iter().find(|(n, _)| *n == name).map(|c| c.1))
                .collect();
            let sum = values.iter().sum::<u64>() as f64;
            w.counters.push((name, sum / values.len().max(1) as f64));
            sums.insert(name.to_string(), (sum, values.len()));
        }
        // As the bench report computes it: a ratio of sums over the frames.
        w.lane_efficiency = lane_efficiencies(&sums);
        w
    }
}

fn first_seen(names: impl Iterator<Item = &'static str>) -> Vec<&'static str> {
    let mut v = Vec::new();
    for n in names {
        if !v.contains(&n) {
            v.push(n);
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vk::{SkipReason, Skipped};

    fn frame(
        i: u64,
        passes: &[(&'static str, f64)],
        counters: &[(&'static str, u64)],
    ) -> FrameTiming {
        FrameTiming {
            frame: i,
            passes: passes.iter().map(|(n, ms)| (*n, Some(*ms))).collect(),
            counters: counters.to_vec(),
            ..Default::default()
        }
    }

    #[test]
    fn groups_sum_their_passes_per_frame_and_the_rest_is_other() {
        let mut h = History::default();
        let t0 = Instant::now();
        for i in 0..4u64 {
            let x = i as f64;
            h.add_gpu(
                t0,
                frame(
                    i,
                    &[
                        ("gbuffer", 1.0),
                        ("reproject", 0.5),
                        ("ssao", 1.0 + x),
                        ("overlay", 0.25),
                    ],
                    &[
                        ("ssao_invocations", 100),
                        ("ssao_active_invocations", 25 + i),
                    ],
                ),
            );
        }
        h.add_gpu(
            t0,
            FrameTiming {
                frame: 4,
                skipped: vec![Skipped {
                    pass: "gbuffer",
                    reason: SkipReason::Unchanged,
                }],
                ..Default::default()
            },
        );
        let w = h.window(t0);
        assert_eq!((w.timed, w.skipped), (5, 1));
        let total = w.total.unwrap();
        // Per-frame totals 2.75, 3.75, 4.75, 5.75.
        assert_eq!(total.time.median, 4.25);
        assert_eq!(total.time.p95, 5.75);
        let reproject = &w.groups[0];
        assert_eq!(reproject.group.name, "reproject");
        assert_eq!(reproject.group.time.median, 0.5);
        let ao = w
            .groups
            .iter()
            .find(|g| g.group.name == "ao")
            .expect("ao group");
        assert_eq!(ao.group.time.median, 2.5);
        assert_eq!(ao.passes[0].name, "ssao");
        let other: Vec<&str> = w.other.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(other, ["gbuffer", "overlay"]);
        assert_eq!(w.counters[1], ("ssao_active_invocations", 26.5));
        assert_eq!(w.lane_efficiency, vec![("ssao".to_string(), 0.265)]);
    }

    #[test]
    fn frames_older_than_the_window_drop_out() {
        let mut h = History::default();
        let t0 = Instant::now();
        h.add_gpu(t0, frame(0, &[("gbuffer", 9.0)], &[]));
        h.add_wall(t0, 100.0);
        let later = t0 + WINDOW + Duration::from_millis(10);
        // Alone, the old frame stays: a slow device shows its last frame.
        assert_eq!(h.window(later).total.unwrap().time.median, 9.0);
        h.add_gpu(later, frame(1, &[("gbuffer", 1.0)], &[]));
        for ms in [10.0, 10.0, 40.0, 10.0] {
            h.add_wall(later, ms);
        }
        let w = h.window(later);
        assert_eq!(w.total.unwrap().time.median, 1.0);
        assert_eq!(w.frame_ms, Some(10.0));
        assert_eq!(w.fps, 100.0, "from the median frame time");
    }
}

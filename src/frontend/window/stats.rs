//! Frame-time and per-pass GPU time averages for the viewer's window title.

use crate::vk::FrameTiming;
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

/// Frame-time and per-pass GPU averages for the window title, refreshed ~4x per second.
pub(super) struct Stats {
    since: Instant,
    frames: u32,
    wall_ms: f64,
    gpu: BTreeMap<&'static str, (f64, u32)>,
    order: Vec<&'static str>,
    /// GPU timings received, and how many of them were frames skipped entirely (nothing
    /// changed: `--skip-unchanged`).
    timed: u32,
    skipped: u32,
}

impl Stats {
    pub(super) fn new() -> Self {
        Self {
            since: Instant::now(),
            frames: 0,
            wall_ms: 0.0,
            gpu: BTreeMap::new(),
            order: Vec::new(),
            timed: 0,
            skipped: 0,
        }
    }

    pub(super) fn add_wall(&mut self, ms: f64) {
        self.frames += 1;
        self.wall_ms += ms;
    }

    pub(super) fn add_gpu(&mut self, t: &FrameTiming) {
        self.timed += 1;
        if t.passes.is_empty() && !t.skipped.is_empty() {
            self.skipped += 1;
        }
        for (name, ms) in &t.passes {
            if let Some(ms) = ms {
                if !self.order.contains(name) {
                    self.order.push(name);
                }
                let e = self.gpu.entry(name).or_insert((0.0, 0));
                e.0 += ms;
                e.1 += 1;
            }
        }
    }

    /// The title text when a refresh is due (then the averages start over).
    pub(super) fn title(&mut self, prefix: &str) -> Option<String> {
        if self.since.elapsed() < Duration::from_millis(250) || self.frames == 0 {
            return None;
        }
        let frame_ms = self.wall_ms / self.frames as f64;
        let mut total = 0.0;
        let mut passes = Vec::new();
        for name in &self.order {
            if let Some((sum, n)) = self.gpu.get(name) {
                let ms = sum / *n as f64;
                total += ms;
                passes.push(format!("{name} {ms:.2}"));
            }
        }
        let mut title = format!(
            "{prefix} | {frame_ms:.1} ms ({:.0} fps) | GPU {total:.2} ms: {}",
            1000.0 / frame_ms.max(1e-3),
            passes.join(", ")
        );
        if self.skipped > 0 {
            title += &format!(
                " | {} of {} frames skipped (nothing changed)",
                self.skipped, self.timed
            );
        }
        *self = Stats {
            order: std::mem::take(&mut self.order),
            ..Stats::new()
        };
        Some(title)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn title_averages_frame_time_and_passes() {
        let mut stats = Stats::new();
        assert_eq!(stats.title("x"), None, "nothing measured yet");
        for ms in [10.0, 30.0] {
            stats.add_wall(ms);
            stats.add_gpu(&FrameTiming {
                frame: 0,
                passes: vec![("gbuffer", Some(ms / 10.0)), ("direct", None)],
                ..Default::default()
            });
        }
        stats.since -= Duration::from_secs(1);
        let title = stats.title("ssgi").unwrap();
        assert_eq!(title, "ssgi | 20.0 ms (50 fps) | GPU 2.00 ms: gbuffer 2.00");
        assert_eq!(stats.frames, 0, "averages start over");
    }

    #[test]
    fn title_counts_skipped_frames() {
        let mut stats = Stats::new();
        stats.add_wall(10.0);
        stats.add_gpu(&FrameTiming {
            frame: 0,
            passes: vec![("gbuffer", Some(1.0))],
            ..Default::default()
        });
        stats.add_gpu(&FrameTiming {
            frame: 1,
            skipped: vec![crate::vk::Skipped {
                pass: "gbuffer",
                reason: crate::vk::SkipReason::Unchanged,
            }],
            ..Default::default()
        });
        stats.since -= Duration::from_secs(1);
        let title = stats.title("ssgi").unwrap();
        assert!(
            title.ends_with("| 1 of 2 frames skipped (nothing changed)"),
            "{title}"
        );
    }
}

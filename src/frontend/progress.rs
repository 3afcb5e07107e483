//! Progress of long runs on stderr: a bar on a terminal that stays hidden for runs shorter
//! than a second, and otherwise (a log, CI, `nohup`), where a redrawn bar would be invisible
//! or garbage, a plain line after the first frame (the run is rendering) and every 30 seconds.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Seconds between two progress lines when stderr is not a terminal.
const LINE_EVERY: Duration = Duration::from_secs(30);

pub struct Progress {
    bar: ProgressBar,
    start: Instant,
    shown: bool,
    enabled: bool,
    terminal: bool,
    label: String,
    total: u64,
    done: u64,
    last_line: Instant,
}

impl Progress {
    pub fn new(total: u64, label: &str, enabled: bool) -> Self {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "{msg} [{bar:40}] {pos}/{len} frames ({per_sec}, eta {eta})",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(label.to_string());
        let now = Instant::now();
        Self {
            bar,
            start: now,
            shown: false,
            enabled,
            terminal: std::io::stderr().is_terminal(),
            label: label.to_string(),
            total,
            done: 0,
            last_line: now,
        }
    }

    pub fn inc(&mut self) {
        self.bar.inc(1);
        self.done += 1;
        if !self.enabled {
            return;
        }
        if self.terminal {
            if !self.shown && self.start.elapsed() > Duration::from_secs(1) {
                self.bar.set_draw_target(ProgressDrawTarget::stderr());
                self.shown = true;
            }
        } else if self.done == 1 || self.last_line.elapsed() >= LINE_EVERY {
            self.last_line = Instant::now();
            let secs = self.start.elapsed().as_secs_f64();
            let per_frame = secs / self.done as f64;
            // Milliseconds for fast frames (a small image on a GPU or lavapipe), else seconds.
            let rate = if per_frame < 0.1 {
                format!("{:.2} ms per frame", per_frame * 1e3)
            } else {
                format!("{per_frame:.2} s per frame")
            };
            eprintln!(
                "{}: {}/{} frames, {:.0} s ({rate})",
                self.label, self.done, self.total, secs
            );
        }
    }

    pub fn finish(&self) {
        if self.shown {
            self.bar.finish_and_clear();
        }
    }
}

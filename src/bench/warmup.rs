//! The frames before measuring: a fixed number, or (`converged`) frames along the path until
//! the effects' GPU work counters settle, so the statistics describe the cache's steady state
//! at the path's speed rather than its start-up (every pixel new on the first frame).

use crate::error::Result;
use crate::frontend::progress::Progress;
use crate::frontend::sink::FrameSink;
use crate::renderer::Renderer;
use crate::scene::path::frame_time;
use crate::scene::CameraPath;
use crate::vk::FrameTiming;
use serde::Serialize;

/// Most frames a converged warmup renders before giving up: 10 s of path at 60 fps.
pub const MAX_CONVERGED_WARMUP: u32 = 600;

/// Relative change of the mean work between two consecutive windows that counts as settled.
const SETTLED_CHANGE: f64 = 0.05;
/// Work below this share of the pixels counts as none: a converged static view computes
/// nothing, and noise around zero has no relative change to speak of.
const SETTLED_FLOOR: f64 = 0.001;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Warmup {
    Frames(u32),
    /// Until the counters settle (at most `MAX_CONVERGED_WARMUP` frames).
    Converged,
}

/// `--warmup`: a frame count, or `converged` (the job bounds the count).
pub fn parse_warmup(s: &str) -> std::result::Result<Warmup, String> {
    match s.trim() {
        "converged" => Ok(Warmup::Converged),
        n => n
            .parse::<u32>()
            .map(Warmup::Frames)
            .map_err(|_| format!("{s:?} is neither a frame count nor `converged`")),
    }
}

/// Rotation limits of path frames a `converged` warmup of a sweep or table renders before the
/// measured frames: one cycle for the first pixels to converge, one for the work to repeat,
/// one to check that it does (`settled` compares the last two).
pub const STEADY_CYCLES: u32 = 3;

/// The warmup of runs that must all measure the same frames (sweeps and tables compare every
/// run's last frame with one ground truth): `Frames(n)` is n frames held at the path's first
/// camera; `Converged` is the `STEADY_CYCLES` rotation limits of path leading up to its time
/// 0, along the path (`RunSpec::warmup_along_path`), at most `MAX_CONVERGED_WARMUP` frames.
/// Returns (frames, along the path).
pub fn before_path(w: Warmup, rotation_limit: u32) -> (u32, bool) {
    match w {
        Warmup::Frames(n) => (n, false),
        Warmup::Converged => (
            (STEADY_CYCLES * rotation_limit.max(4)).min(MAX_CONVERGED_WARMUP),
            true,
        ),
    }
}

/// How the warmup went, for the report.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Outcome {
    /// "frames" or "converged".
    pub mode: &'static str,
    /// Frames rendered before the measured ones.
    pub frames: u32,
    /// The counters settled (always true for a fixed count).
    pub settled: bool,
}

impl Outcome {
    pub fn describe(&self) -> String {
        match (self.mode, self.settled) {
            ("frames", _) => format!("warmup: {} frames", self.frames),
            (_, true) => format!("warmup: converged after {} frames", self.frames),
            _ => format!(
                "warmup: the work counters did not settle within {} frames; measuring anyway",
                self.frames
            ),
        }
    }
}

/// A frame's work: the pixels every effect computed (`*_computed_pixels`).
pub fn work(t: &FrameTiming) -> u64 {
    t.counters
        .iter()
        .filter(|(name, _)| name.ends_with("_computed_pixels"))
        .map(|(_, n)| n)
        .sum()
}

/// Whether the work of the last `2 window` frames has settled: the means of the two halves
/// differ by at most `SETTLED_CHANGE` of the larger, or both lie below `SETTLED_FLOOR` of
/// `pixels`.
pub fn settled(work: &[u64], window: usize, pixels: u64) -> bool {
    let window = window.max(1);
    if work.len() < 2 * window {
        return false;
    }
    let tail = &work[work.len() - 2 * window..];
    let mean = |s: &[u64]| s.iter().sum::<u64>() as f64 / s.len() as f64;
    let (a, b) = (mean(&tail[..window]), mean(&tail[window..]));
    let floor = SETTLED_FLOOR * pixels as f64;
    (a <= floor && b <= floor) || (a - b).abs() <= SETTLED_CHANGE * a.max(b)
}

/// Render the warmup frames along `path` (frame i at i / fps); returns their timings (those
/// already collected) and the outcome. The measured frames continue at frame `frames`.
pub fn run(
    renderer: &mut Renderer,
    sink: &mut dyn FrameSink,
    path: &CameraPath,
    fps: f32,
    warmup: Warmup,
    progress: bool,
) -> Result<(Vec<FrameTiming>, Outcome)> {
    let base = renderer.scene.camera;
    let orbit = renderer.scene.orbit();
    let (limit, mode) = match warmup {
        Warmup::Frames(n) => (n, "frames"),
        Warmup::Converged => (MAX_CONVERGED_WARMUP, "converged"),
    };
    // A pixel's accumulation cycle: the work repeats with it.
    let window = renderer.config.temporal.rotation_limit.max(4) as usize;
    let pixels = renderer.config.width as u64 * renderer.config.height as u64;
    let mut timings: Vec<FrameTiming> = Vec::new();
    let mut signal: Vec<u64> = Vec::new();
    let mut bar = Progress::new(limit as u64, "warmup", progress);
    sink.begin(&renderer.scene.name);
    let converging = warmup == Warmup::Converged;
    let mut frames = 0;
    let mut steady = !converging;
    // Each frame polls for Ctrl-C: a signal stops the run between frames.
    let _scope = crate::interrupt::graceful();
    while frames < limit && !(converging && steady) {
        let camera = path.camera_at(&base, &orbit, frame_time(frames, fps));
        renderer.set_time(frame_time(frames, fps));
        let done = sink.frame(renderer, &camera)?;
        signal.extend(done.iter().map(work));
        timings.extend(done);
        frames += 1;
        bar.inc();
        if converging {
            steady = settled(&signal, window, pixels);
        }
    }
    bar.finish();
    Ok((
        timings,
        Outcome {
            mode,
            frames,
            settled: steady,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_counts_and_converged() {
        assert_eq!(parse_warmup("10"), Ok(Warmup::Frames(10)));
        assert_eq!(parse_warmup("0"), Ok(Warmup::Frames(0)));
        assert_eq!(parse_warmup("converged"), Ok(Warmup::Converged));
        assert!(parse_warmup("-1").is_err());
        assert!(parse_warmup("soon").is_err());
    }

    #[test]
    fn settles_on_a_plateau_and_on_zero_but_not_on_a_ramp() {
        let pixels = 10_000;
        // Start-up: everything new, then falling.
        let ramp: Vec<u64> = (0..40).map(|i| 10_000 - i * 200).collect();
        assert!(!settled(&ramp, 10, pixels));
        // A moving camera's steady state: noise around a level.
        let plateau: Vec<u64> = (0..40).map(|i| 1_000 + (i % 3) * 10).collect();
        assert!(settled(&plateau, 10, pixels));
        // A converged static view: nothing computed.
        let zero = vec![0u64; 20];
        assert!(settled(&zero, 10, pixels));
        // Too few frames to judge.
        assert!(!settled(&zero[..19], 10, pixels));
    }
}

//! Computing a reference as the commands need it: build the BVH, trace the primary rays, take
//! what the cache has, refine each buffer to a sample count or a standard-error target (with a
//! progress bar), save back to the cache.

use super::store;
use super::trace::{direct_is_exact, RefBuffer, Reference, Settings};
use crate::error::Result;
use crate::scene::accel::Accel;
use crate::scene::{Camera, Scene};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::PathBuf;

/// A reference being computed, with its BVH and cache entry.
pub struct Session<'a> {
    pub scene: &'a Scene,
    pub accel: Accel,
    pub reference: Reference,
    pub key: String,
    /// Where the cache entry lives (None: --no-cache).
    pub cache: Option<PathBuf>,
    /// Whether the cache had an entry when the session started.
    pub from_cache: bool,
    pub progress: bool,
}

/// Most samples per half and pixel a standard-error target may ask for (2^16: a 256x256 AO
/// buffer then costs 8.6e9 rays; past that the target is reported as missed, not chased).
pub const MAX_SAMPLES_PER_HALF: u32 = 1 << 16;

impl<'a> Session<'a> {
    pub fn start(
        scene: &'a Scene,
        camera: Camera,
        width: u32,
        height: u32,
        settings: Settings,
        cache: Option<PathBuf>,
        progress: bool,
    ) -> Result<Self> {
        let accel = Accel::new(&scene.mesh);
        let mut reference = Reference::new(&accel, scene, camera, width, height, settings);
        let key = store::key(scene, &camera, width, height, &settings);
        let from_cache = match &cache {
            Some(dir) => store::load(dir, &key, &mut reference)?,
            None => false,
        };
        Ok(Self {
            scene,
            accel,
            reference,
            key,
            cache,
            from_cache,
            progress,
        })
    }

    /// Refine `buffer` to at least `per_half` samples per half and pixel. Ctrl-C stops the
    /// tracing early with `Error::Interrupted`; the partial sums are then never saved.
    pub fn ensure(&mut self, buffer: RefBuffer, per_half: u32) -> Result<()> {
        let per_half = match buffer {
            RefBuffer::Direct | RefBuffer::Shadow if direct_is_exact(&self.reference.settings) => 1,
            _ => per_half.min(MAX_SAMPLES_PER_HALF),
        };
        let have = self.reference.estimate(buffer).per_half;
        if have >= per_half {
            return Ok(());
        }
        let bar = bar(
            self.reference.height as u64,
            buffer,
            per_half,
            self.progress,
        );
        let add = per_half - have;
        // The tracer polls for Ctrl-C before each row; the check below reports it.
        let scope = crate::interrupt::graceful();
        self.reference
            .refine(&self.accel, self.scene, buffer, add, &|n| bar.inc(n));
        bar.finish_and_clear();
        let stopped = crate::interrupt::check();
        drop(scope);
        stopped
    }

    /// Refine `buffer` until its standard error over `mask` is at most `target` (absolute),
    /// doubling the samples; returns whether the target was met within the cap.
    pub fn refine_to(&mut self, buffer: RefBuffer, target: f64, mask: &[bool]) -> Result<bool> {
        loop {
            let e = self.reference.estimate(buffer);
            if e.per_half > 0 && e.standard_error(mask) <= target {
                return Ok(true);
            }
            if e.per_half >= MAX_SAMPLES_PER_HALF
                || (direct_is_exact(&self.reference.settings)
                    && matches!(buffer, RefBuffer::Direct | RefBuffer::Shadow)
                    && e.per_half > 0)
            {
                return Ok(false);
            }
            let next = (e.per_half * 2).max(64);
            self.ensure(buffer, next)?;
        }
    }

    /// Save the sums to the cache (no-op without one).
    pub fn save(&mut self) -> Result<()> {
        match &self.cache {
            Some(dir) => store::save(dir, &self.key, &mut self.reference),
            None => Ok(()),
        }
    }
}

fn bar(rows: u64, buffer: RefBuffer, per_half: u32, enabled: bool) -> ProgressBar {
    let target = if enabled {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(rows), target);
    if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} rows (eta {eta})")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(format!(
        "reference {}: {} samples/pixel",
        buffer.name(),
        2 * per_half as u64
    ));
    bar
}

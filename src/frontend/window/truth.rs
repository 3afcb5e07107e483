//! The viewer's ground truth on demand (G): `ssgi reference`'s tracer for the current view, on
//! CPU threads beside the renderer, at `ssgi reference`'s default sample counts, through its
//! cache (a view traced before is read back, not traced again). The viewer then scores its
//! frame as the sweep does (`bench::ground_truth::errors`: per-buffer RMSE over the geometry
//! pixels, FLIP for the final image). Moving the camera cancels it: the tracer stops at its
//! next step and nothing is reported or cached.

use crate::error::{Error, Result};
use crate::reference::run::Session;
use crate::reference::trace::{
    RefBuffer, Reference, Settings, DEFAULT_AO_SAMPLES, DEFAULT_INDIRECT_SAMPLES,
    DEFAULT_SOFT_SHADOW_SAMPLES,
};
use crate::scene::{Camera, Scene};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;

/// Samples per half and pixel of each buffer: `ssgi reference`'s defaults (its
/// `--ao-samples`, `--shadow-samples`, `--indirect-samples` are two halves of these).
pub const TARGETS: [(RefBuffer, u32); 3] = [
    (RefBuffer::Ao, DEFAULT_AO_SAMPLES),
    (RefBuffer::Direct, DEFAULT_SOFT_SHADOW_SAMPLES),
    (RefBuffer::Indirect, DEFAULT_INDIRECT_SAMPLES),
];

/// A tracing job in the background.
pub struct TruthJob {
    camera: Camera,
    /// The scene as traced (posed when the job started): the scoring needs its light.
    scene: Scene,
    cancel: Arc<AtomicBool>,
    /// Finished share of the samples, in thousandths.
    permille: Arc<AtomicU32>,
    handle: Option<JoinHandle<Result<Option<Reference>>>>,
}

impl TruthJob {
    /// Trace `scene` (posed: nothing left to move) from `camera` at `size`.
    pub fn start(
        scene: Scene,
        camera: Camera,
        size: (u32, u32),
        settings: Settings,
        cache: Option<PathBuf>,
    ) -> Self {
        let cancel = Arc::new(AtomicBool::new(false));
        let permille = Arc::new(AtomicU32::new(0));
        let (stop, done) = (cancel.clone(), permille.clone());
        let traced = scene.clone();
        let handle =
            std::thread::spawn(move || trace(&traced, camera, size, settings, cache, &stop, &done));
        Self {
            camera,
            scene,
            cancel,
            permille,
            handle: Some(handle),
        }
    }

    /// The camera it traces from.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Finished share, 0 to 1.
    pub fn progress(&self) -> f32 {
        self.permille.load(Ordering::Relaxed) as f32 / 1000.0
    }

    /// Stop it: the tracer returns at its next step, unsaved; its thread is left to end.
    pub fn cancel(mut self) {
        self.cancel.store(true, Ordering::Relaxed);
        self.handle.take();
    }

    /// The reference once the tracer is done (`None` while it runs).
    pub fn poll(&mut self) -> Option<Result<Reference>> {
        if !self.handle.as_ref()?.is_finished() {
            return None;
        }
        self.wait()
    }

    /// Wait for the tracer (scripted runs: `wait=truth`).
    pub fn wait(&mut self) -> Option<Result<Reference>> {
        let handle = self.handle.take()?;
        Some(match handle.join() {
            Ok(Ok(Some(r))) => Ok(r),
            Ok(Ok(None)) => Err(Error::Interrupted),
            Ok(Err(e)) => Err(e),
            Err(_) => Err(Error::Window("the ground-truth tracer panicked".into())),
        })
    }
}

/// The tracer: each buffer refined in steps to its target (cancellation is checked between
/// steps), then saved to the cache. `None` when cancelled.
fn trace(
    scene: &Scene,
    camera: Camera,
    (width, height): (u32, u32),
    settings: Settings,
    cache: Option<PathBuf>,
    cancel: &AtomicBool,
    permille: &AtomicU32,
) -> Result<Option<Reference>> {
    let mut session = Session::start(scene, camera, width, height, settings, cache, false)?;
    let total: u64 = TARGETS.iter().map(|(_, n)| *n as u64).sum();
    let mut before = 0u64;
    for (buffer, target) in TARGETS {
        loop {
            let have = session.reference.estimate(buffer).per_half;
            let done = before + have.min(target) as u64;
            permille.store((1000 * done / total.max(1)) as u32, Ordering::Relaxed);
            if cancel.load(Ordering::Relaxed) {
                return Ok(None);
            }
            if have >= target {
                break;
            }
            // Sixteen steps per buffer (at least 8 samples each): a cancel waits for at most
            // a sixteenth of a buffer's tracing.
            let next = (have + (target / 16).max(8)).min(target);
            session.ensure(buffer, next)?;
            // Exact direct light needs one sample: `ensure` stops there.
            if session.reference.estimate(buffer).per_half == have {
                break;
            }
        }
        before += target as u64;
    }
    permille.store(1000, Ordering::Relaxed);
    session.save()?;
    Ok(Some(session.reference))
}

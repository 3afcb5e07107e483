//! The ground truth on demand (G): tracing the held view in the background, scoring the frame
//! on screen against it, and its FLIP map shown in place of the image (M).

use super::super::truth::TruthJob;
use super::App;
use crate::bench::ground_truth;
use crate::bench::measure::read_frame;
use crate::error::Result;
use crate::reference::store::default_dir;
use crate::reference::{Reference, Settings};
use crate::scene::Camera;
use crate::vk::{upload_image, Access, Image, ImageDesc, Tracker};

impl App {
    /// G: trace the ground truth of the held view in the background, or cancel the tracing.
    pub(super) fn toggle_truth(&mut self) {
        if let Some(job) = self.truth.job.take() {
            job.cancel();
            self.truth.text.clear();
            self.report("ground truth cancelled (G)".into());
            return;
        }
        let r = &self.renderer;
        let camera = self.viewer.camera_or(r);
        let scene = r.scene.posed(self.viewer.scene_time);
        let settings = Settings::for_render(&r.config, &scene);
        let (w, h) = (r.config.width, r.config.height);
        eprintln!(
            "ground truth: tracing {w}x{h} from the held camera on {} threads (G or moving \
             cancels)",
            rayon::current_num_threads()
        );
        self.truth.job = Some(TruthJob::start(
            scene,
            camera,
            (w, h),
            settings,
            Some(default_dir()),
        ));
    }

    /// Each frame: a camera other than the traced one cancels the job; a finished one scores
    /// the frame.
    pub(super) fn check_truth(&mut self, camera: &Camera) -> Result<()> {
        let Some(job) = self.truth.job.as_mut() else {
            return Ok(());
        };
        if job.camera() != *camera {
            if let Some(job) = self.truth.job.take() {
                job.cancel();
            }
            self.truth.text.clear();
            self.report("ground truth cancelled: the camera moved".into());
            return Ok(());
        }
        let progress = job.progress();
        match job.poll() {
            None => {
                self.truth.text = vec![format!(
                    "ground truth: {:.0}% traced (G cancels)",
                    100.0 * progress
                )];
                Ok(())
            }
            Some(result) => match self.truth.job.take() {
                Some(job) => self.score_truth(&job, result),
                None => Ok(()),
            },
        }
    }

    /// The frame now on screen against the traced reference, as the sweep scores it.
    pub(super) fn score_truth(&mut self, job: &TruthJob, result: Result<Reference>) -> Result<()> {
        let reference = match result {
            Ok(r) => r,
            Err(e) => {
                self.truth.text.clear();
                self.report(format!("ground truth failed: {e}"));
                return Ok(());
            }
        };
        let renderer = &mut self.renderer;
        let pending = renderer.finish()?;
        let last = read_frame(renderer, job.camera())?;
        let terms = crate::effects::estimated_terms(&renderer.config);
        let errors = ground_truth::errors(&last, &reference, job.scene(), terms)?;
        let map = ground_truth::final_flip_map(&last, &reference, job.scene(), terms)?;
        self.frames.absorb(pending);
        self.truth.error_map = match map {
            Some((rgba, w, h)) => {
                let image = Image::new(
                    &self.ctx,
                    "ground truth FLIP map",
                    ImageDesc {
                        width: w,
                        height: h,
                        format: ash::vk::Format::R8G8B8A8_UNORM,
                        // SAMPLED: every image gets a view (memory.rs), which needs a
                        // view-compatible usage; the map is only blitted.
                        usage: ash::vk::ImageUsageFlags::TRANSFER_SRC
                            | ash::vk::ImageUsageFlags::TRANSFER_DST
                            | ash::vk::ImageUsageFlags::SAMPLED,
                    },
                )?;
                upload_image(
                    &self.ctx,
                    &mut Tracker::default(),
                    &image,
                    &rgba,
                    Access::TransferSrc,
                )?;
                Some((image, job.camera()))
            }
            None => None,
        };
        self.truth.text = errors
            .iter()
            .map(|(b, e)| {
                let flip = e.flip.map_or(String::new(), |f| format!(" flip {f:.9e}"));
                format!("ground truth: {} rmse {:.9e}{flip}", b.name(), e.error.rmse)
            })
            .collect();
        for line in &self.truth.text {
            eprintln!("{line}");
        }
        self.panel.message = None;
        Ok(())
    }

    /// The error map no longer matches the view (`why`): drop it, and the scores with it.
    pub(super) fn drop_error_map(&mut self, why: &str) {
        let truth = &mut self.truth;
        truth.error_map = None;
        truth.show_error_map = false;
        truth.text.clear();
        self.report(format!("ground truth dropped: {why}"));
    }
}

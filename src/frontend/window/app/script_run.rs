//! The test script's steps (`script.rs` parses them), run when their frame is due.

use super::App;
use crate::frontend::view_state::{display_cycle, Action};
use crate::frontend::window::script::{self, ScriptOp};
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;

impl App {
    pub(super) fn run_script(&mut self, event_loop: &ActiveEventLoop) {
        for op in script::take_due(&mut self.options.script, self.frames.presented) {
            match op {
                ScriptOp::Resize(w, h) => {
                    if let Some(live) = &self.live {
                        eprintln!("script: resize to {w}x{h}");
                        let _ = live.window.request_inner_size(PhysicalSize::new(w, h));
                    }
                }
                ScriptOp::ZeroExtent(n) => {
                    eprintln!("script: zero extent for {n} event-loop iterations");
                    self.pause.zero_ticks = n.max(1);
                }
                ScriptOp::Key(name) => {
                    if let Some(a) = Action::from_name(&name) {
                        self.act(event_loop, a);
                    }
                }
                ScriptOp::Display(name) => {
                    let index = display_cycle().iter().position(|(_, n)| *n == name);
                    let shown = self.live.as_ref().map(|l| l.displayable.clone());
                    match (index, shown) {
                        (Some(i), Some(shown)) if shown[i] => {
                            self.viewer.view.display = i;
                            eprintln!("display: {name}");
                        }
                        _ => eprintln!("display: {name} is not available in this run"),
                    }
                }
                ScriptOp::WaitTruth => {
                    let result = self.truth.job.take().and_then(|mut job| {
                        let result = job.wait()?;
                        Some((job, result))
                    });
                    match result {
                        Some((job, result)) => {
                            if let Err(e) = self.score_truth(&job, result) {
                                self.fail(event_loop, e);
                            }
                        }
                        None => eprintln!("script: no ground truth is being traced"),
                    }
                }
                ScriptOp::Move(fraction) => {
                    let r = &self.renderer;
                    let c = self.viewer.camera_or(r);
                    let step = c.frame().0 * fraction * r.scene.mesh.bounds.radius();
                    let mut moved = c;
                    moved.position += step;
                    moved.target += step;
                    self.viewer.camera = Some(moved);
                    eprintln!("script: camera moved forward by {fraction} scene radii");
                }
                ScriptOp::Set(key, value) => {
                    if let Err(e) = self.set_setting(&key, &value) {
                        self.fail(event_loop, e);
                    }
                }
            }
        }
    }
}

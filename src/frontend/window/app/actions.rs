//! The viewer's actions (keys, the overlay's buttons, a script's `key=`) and live settings
//! (the overlay's controls, a script's `set=`), applied to the viewer's switches and the
//! renderer's configuration.

use super::App;
use crate::config::parse::parse_render_scale;
use crate::error::{Error, Result};
use crate::frontend::overlay::{History, RENDER_SCALE};
use crate::frontend::view_state::{display_cycle, help, Action, ViewState};
use winit::event_loop::ActiveEventLoop;

impl App {
    pub(super) fn act(&mut self, event_loop: &ActiveEventLoop, action: Action) {
        match action {
            Action::GroundTruth => return self.toggle_truth(),
            Action::ErrorMap => {
                let truth = &mut self.truth;
                truth.show_error_map = truth.error_map.is_some() && !truth.show_error_map;
                return match (&truth.error_map, truth.show_error_map) {
                    (None, _) => self.report("no error map: press G for the ground truth".into()),
                    (Some(_), on) => {
                        eprintln!("error map: {}", if on { "shown" } else { "hidden" })
                    }
                };
            }
            _ => {}
        }
        let view = &mut self.viewer.view;
        match action {
            Action::CycleDisplay(step) => {
                let n = display_cycle().len() as i32;
                let displayable = self.live.as_ref().map(|l| l.displayable.clone());
                for _ in 0..n {
                    view.display = (view.display as i32 + step).rem_euclid(n) as usize;
                    if displayable.as_ref().is_none_or(|d| d[view.display]) {
                        break;
                    }
                }
                eprintln!("display: {}", view.display_name());
            }
            Action::ToggleShadows => view.soft_shadows = !view.soft_shadows,
            Action::ToggleEffect(name) => view.toggle_effect(name),
            Action::ToggleSetting(i) => {
                if let Some(on) = view.toggles.get_mut(i) {
                    *on = !*on;
                }
            }
            Action::ToggleReuse => view.temporal_reuse = !view.temporal_reuse,
            Action::Screenshot => self.viewer.shot_pending = true,
            Action::GroundTruth | Action::ErrorMap => {} // above: they need the whole viewer
            Action::ToggleOverlay => match self.live.as_mut().and_then(|l| l.overlay.as_mut()) {
                Some(overlay) => {
                    overlay.toggle();
                    eprintln!(
                        "overlay: {}",
                        if overlay.visible() { "shown" } else { "hidden" }
                    );
                }
                None => eprintln!("overlay: off for this run (--overlay off)"),
            },
            Action::ToggleOverlayDetail => {
                match self.live.as_mut().and_then(|l| l.overlay.as_mut()) {
                    Some(overlay) => {
                        overlay.toggle_detail();
                        eprintln!(
                            "overlay: {}",
                            if overlay.full() {
                                "full panel"
                            } else {
                                "compact"
                            }
                        );
                    }
                    None => eprintln!("overlay: off for this run (--overlay off)"),
                }
            }
            Action::PrintCamera => {
                let c = self.viewer.camera_or(&self.renderer);
                eprintln!(
                    "{{ \"time\": 0.0, \"position\": [{}, {}, {}], \"target\": [{}, {}, {}] }}",
                    c.position.x, c.position.y, c.position.z, c.target.x, c.target.y, c.target.z
                );
            }
            Action::Help => eprintln!("{}", help()),
            Action::Quit => event_loop.exit(),
        }
        if !matches!(
            action,
            Action::CycleDisplay(_)
                | Action::PrintCamera
                | Action::ToggleOverlay
                | Action::ToggleOverlayDetail
                | Action::Screenshot
                | Action::GroundTruth
                | Action::ErrorMap
                | Action::Help
                | Action::Quit
        ) {
            eprintln!("effects: {}", self.viewer.view.summary());
        }
        if let Err(e) = self.apply_view() {
            self.fail(event_loop, e);
        }
    }

    /// Make the renderer match the viewer's switches. The PCF kernel changes in place; effects
    /// and reuse rebuild the renderer on the same context and size (histories start over). A
    /// configuration the renderer rejects is reported and the switch undone.
    fn apply_view(&mut self) -> Result<()> {
        let wanted = self.viewer.view.config(&self.renderer.config);
        let what = self.viewer.view.summary();
        if !self.apply_config(wanted, &what)? {
            self.reset_view();
        }
        Ok(())
    }

    /// A live setting (the overlay's controls, a script's `set=KEY:VALUE`): `name` is a sweep
    /// key and `value` goes through the same parser as the command line's option, then the
    /// configuration through `RenderConfig::validate`. A refused value is reported (stderr and
    /// the overlay) and changes nothing.
    pub(super) fn set_setting(&mut self, name: &str, value: &str) -> Result<()> {
        if name == RENDER_SCALE {
            return self.set_render_scale(value);
        }
        let mut wanted = self.renderer.config;
        let checked = crate::sweep::keys::parse_key(name).and_then(|key| {
            (key.set)(&mut wanted, value.trim()).map_err(|why| {
                Error::Config(format!(
                    "invalid value {value:?} for {name} ({why}); expected {}",
                    key.syntax
                ))
            })?;
            wanted.validate()
        });
        if let Err(e) = checked {
            self.report(format!("cannot set {name}={value}: {e}"));
            return Ok(());
        }
        if self.apply_config(wanted, &format!("{name}={value}"))? {
            self.remember_setting(name, value);
            self.report(format!("set {name}={value}"));
        }
        self.reset_view();
        Ok(())
    }

    /// The viewer's own setting: the render scale (`--render-scale`'s parser).
    fn set_render_scale(&mut self, value: &str) -> Result<()> {
        match parse_render_scale(value) {
            Ok(scale) => {
                self.options.render_scale = scale;
                if let Some(extent) = self.live.as_ref().map(|l| l.swapchain.extent) {
                    self.fit_renderer((extent.width, extent.height))?;
                }
                self.frames.history = History::default();
                self.remember_setting(RENDER_SCALE, value);
                self.report(format!("set {RENDER_SCALE}={value}"));
            }
            Err(why) => self.report(format!("cannot set {RENDER_SCALE}={value}: {why}")),
        }
        Ok(())
    }

    /// An applied setting, for the printed command line (latest last, once per key).
    fn remember_setting(&mut self, name: &str, value: &str) {
        let settings = &mut self.panel.settings;
        settings.retain(|(n, _)| n != name);
        settings.push((name.to_string(), value.trim().to_string()));
    }

    /// The viewer's switches from the renderer's configuration, keeping the displayed buffer.
    pub(super) fn reset_view(&mut self) {
        let view = &mut self.viewer.view;
        let display = view.display;
        *view = ViewState::new(&self.renderer.config);
        view.display = display;
    }
}

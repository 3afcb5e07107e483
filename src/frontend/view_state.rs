//! What the viewer's keys control: the displayed buffer, effect switches and temporal reuse,
//! and how they map onto a renderer configuration.

use crate::config::pcf::Pcf;
use crate::config::Effects;
use crate::effects;
use crate::renderer::RenderConfig;
use crate::resources::targets::Target;
use std::sync::OnceLock;

/// The effect switches the digit keys toggle, in order from `1`: every `--effects` switch but
/// direct light. Built once (the window's title reads it every frame).
pub fn effect_keys() -> &'static [&'static str] {
    static KEYS: OnceLock<Vec<&'static str>> = OnceLock::new();
    KEYS.get_or_init(|| {
        Effects::NAMES
            .into_iter()
            .filter(|n| *n != "direct")
            .collect()
    })
}

/// The viewer's keys, printed by `F1` and documented in docs/cli.md: the digits toggle
/// [`effect_keys`], then the effects' own settings (`effects::toggles`).
pub fn help() -> String {
    let buffers: Vec<&str> = display_cycle().iter().map(|(_, n)| *n).collect();
    let mut digits = String::new();
    let ambient = effects::ambient_switches();
    for (i, name) in effect_keys().iter().copied().enumerate() {
        let note = if ambient.contains(&name) {
            " (darkens the ambient light: switches the others that do off)"
        } else {
            ""
        };
        digits += &format!("\n  {:<31}toggle --effects {name}{note}", i + 1);
    }
    let first_setting = effect_keys().len() + 1;
    for (i, t) in effects::toggles().enumerate() {
        digits += &format!("\n  {:<31}toggle {}", first_setting + i, t.what);
    }
    format!(
        "ssgi view keys:
  mouse drag (left button held)  look around
  W A S D                        move forward / left / back / right
  Q E                            move down / up
  Shift / Ctrl (held)            move 4x faster / 4x slower
  Tab / Shift+Tab                cycle the displayed buffer ({}; raw values clamped
                                 to 0..1)
  P                              soft (PCF) / hard shadows{digits}
                                 (each digit rebuilds the renderer: histories start over)
  R                              temporal reuse on / off (rebuilds the renderer)
  C                              print the camera as a keyframe (for --path files)
  H                              show / hide the overlay (GPU time per pass and group,
                                 median and p95 over the last second; counters; device)
  O                              the overlay's full panel / its compact summary (by
                                 default the full panel where it covers at most half the
                                 window, else the summary)
  G                              ground truth of the held view: `ssgi reference`'s
                                 tracer in the background, then each buffer's RMSE and the
                                 final image's FLIP against it (moving cancels; G again too)
  M                              show the final image's FLIP map against the ground truth
                                 in place of the image (after G; moving drops it)
  F12                            write the frame as PNG and the last second's GPU
                                 timings as JSON (bench format) into --screenshot-dir
  F1                             print this help
  Esc                            quit",
        buffers.join(", ")
    )
}

/// Buffers the viewer can show, in cycling order: the frame's, then the effects' views marked
/// for the viewer. Depth targets cannot be blitted to a colour image and are left out; a
/// target whose format lacks BLIT_SRC support is skipped. Built once from the registry (the
/// window reads it every frame).
pub fn display_cycle() -> &'static [(Target, &'static str)] {
    static CYCLE: OnceLock<Vec<(Target, &'static str)>> = OnceLock::new();
    CYCLE.get_or_init(build_display_cycle)
}

fn build_display_cycle() -> Vec<(Target, &'static str)> {
    let frame = [
        (Target::Output, "final"),
        (Target::Direct, "direct"),
        (Target::Shadow, "shadow"),
        (Target::Ao, "ao"),
        (Target::Indirect, "indirect"),
        (Target::GNormal, "normal"),
        (Target::GAlbedo, "albedo"),
        (Target::GPosition, "position"),
    ];
    let views = effects::REGISTRY
        .iter()
        .flat_map(|r| r.views)
        .filter(|v| v.in_viewer)
        .map(|v| (Target::Effect(v), v.name));
    frame.into_iter().chain(views).collect()
}

/// What the viewer's keys control; [`ViewState::config`] turns it into a configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewState {
    /// Index into [`display_cycle`].
    pub display: usize,
    /// Soft shadows: the PCF kernel the run started with (or the default), else hard.
    pub soft_shadows: bool,
    pub effects: Effects,
    /// Per `effects::toggles()`, on or off.
    pub toggles: Vec<bool>,
    pub temporal_reuse: bool,
    /// The configuration the viewer started with (its PCF kernel and the settings' values).
    start: RenderConfig,
}

impl ViewState {
    /// The switches of a renderer created with `config`.
    pub fn new(config: &RenderConfig) -> Self {
        Self {
            display: 0,
            soft_shadows: config.pcf != Pcf::HARD,
            effects: config.effects,
            toggles: effects::toggles().map(|t| (t.get)(config)).collect(),
            temporal_reuse: config.temporal.reuse,
            start: *config,
        }
    }

    /// Flip an `--effects` switch; one that darkens the ambient light switches the others that
    /// do off (a run has one at most).
    pub fn toggle_effect(&mut self, name: &str) {
        let on = !self.effects.has(name);
        // Names come from `effect_keys`: known switches.
        let _ = self.effects.set(name, on);
        let ambient = effects::ambient_switches();
        if on && ambient.contains(&name) {
            for other in ambient.into_iter().filter(|o| *o != name) {
                let _ = self.effects.set(other, false);
            }
        }
    }

    /// The renderer configuration the switches ask for, starting from `current`.
    pub fn config(&self, current: &RenderConfig) -> RenderConfig {
        let mut config = *current;
        config.pcf = match (self.soft_shadows, self.start.pcf) {
            (false, _) => Pcf::HARD,
            (true, Pcf::HARD) => Pcf::DEFAULT,
            (true, start) => start,
        };
        config.effects = self.effects;
        for (t, on) in effects::toggles().zip(&self.toggles) {
            (t.set)(&mut config, *on, &self.start);
        }
        config.temporal.reuse = self.temporal_reuse;
        config
    }

    pub fn display_target(&self) -> Target {
        let cycle = display_cycle();
        cycle[self.display % cycle.len()].0
    }

    pub fn display_name(&self) -> &'static str {
        let cycle = display_cycle();
        cycle[self.display % cycle.len()].1
    }

    /// `pcf ao -indirect ...`: every switch, `-` where off.
    pub fn summary(&self) -> String {
        let flag = |on: bool, name: &str| {
            if on {
                name.to_string()
            } else {
                format!("-{name}")
            }
        };
        let mut flags = vec![flag(self.soft_shadows, "pcf")];
        flags.extend(effect_keys().iter().map(|n| flag(self.effects.has(n), n)));
        flags.extend(
            effects::toggles()
                .zip(&self.toggles)
                .map(|(t, on)| flag(*on, t.name)),
        );
        flags.push(flag(self.temporal_reuse, "reuse"));
        flags.join(" ")
    }
}

/// Whether a renderer made with `current` must be rebuilt to run `wanted`: effects, their
/// settings and temporal reuse choose passes and targets at creation; only the PCF kernel
/// changes in place.
pub fn needs_rebuild(current: &RenderConfig, wanted: &RenderConfig) -> bool {
    let in_place = RenderConfig {
        pcf: current.pcf,
        ..*wanted
    };
    in_place != *current
}

/// A viewer command, from a key (`window/keys.rs`) or from a test script.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    CycleDisplay(i32),
    ToggleShadows,
    /// Flip an `--effects` switch (digit keys, [`effect_keys`]).
    ToggleEffect(&'static str),
    /// Flip an effect's own setting (digit keys after the effects', by `effects::toggles`
    /// index).
    ToggleSetting(usize),
    ToggleReuse,
    PrintCamera,
    /// Show or hide the overlay (timings, counters, device).
    ToggleOverlay,
    /// Switch the overlay between its full panel and its compact summary.
    ToggleOverlayDetail,
    /// Write the presented frame (PNG) and the last second's timings (bench JSON).
    Screenshot,
    /// Start (or cancel) the ground truth of the current view.
    GroundTruth,
    /// Show the final image's FLIP map against the ground truth in place of the image.
    ErrorMap,
    Help,
    Quit,
}

impl Action {
    /// The action a test script names (`key=NAME`): cycle, pcf, an effect switch, an effect's
    /// setting, reuse, camera, overlay, panel, screenshot, truth, errormap, help, quit.
    pub fn from_name(name: &str) -> Option<Action> {
        if let Some(e) = effect_keys().iter().copied().find(|e| *e == name) {
            return Some(Action::ToggleEffect(e));
        }
        if let Some(i) = effects::toggles().position(|t| t.name == name) {
            return Some(Action::ToggleSetting(i));
        }
        Some(match name {
            "cycle" => Action::CycleDisplay(1),
            "pcf" => Action::ToggleShadows,
            "reuse" => Action::ToggleReuse,
            "camera" => Action::PrintCamera,
            "overlay" => Action::ToggleOverlay,
            "panel" => Action::ToggleOverlayDetail,
            "screenshot" => Action::Screenshot,
            "truth" => Action::GroundTruth,
            "errormap" => Action::ErrorMap,
            "help" => Action::Help,
            "quit" => Action::Quit,
            _ => return None,
        })
    }

    /// The action of digit key `n` (1-9): an effect switch, then an effect's setting.
    pub fn from_digit(n: usize) -> Option<Action> {
        let keys = effect_keys();
        let i = n.checked_sub(1)?;
        if let Some(e) = keys.get(i) {
            return Some(Action::ToggleEffect(e));
        }
        let t = i - keys.len();
        (t < effects::toggles().count()).then_some(Action::ToggleSetting(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcf_toggle_round_trips() {
        let base = RenderConfig::default();
        let mut v = ViewState::new(&base);
        assert!(v.soft_shadows);
        v.soft_shadows = false;
        assert_eq!(v.config(&base).pcf, Pcf::HARD);
        assert!(
            !needs_rebuild(&base, &v.config(&base)),
            "PCF changes in place"
        );
        v.soft_shadows = true;
        assert_eq!(v.config(&base).pcf, base.pcf, "the run's kernel comes back");
        let hard_run = RenderConfig {
            pcf: Pcf::HARD,
            ..base
        };
        let mut hard = ViewState::new(&hard_run);
        assert!(!hard.soft_shadows);
        hard.soft_shadows = true;
        assert_eq!(
            hard.config(&hard_run).pcf,
            Pcf::DEFAULT,
            "turning PCF on uses the default kernel"
        );
    }

    #[test]
    fn effect_and_reuse_switches_reach_the_config() {
        let base = RenderConfig::default();
        let mut v = ViewState::new(&base);
        assert_eq!(v.effects, base.effects);
        assert_eq!(v.temporal_reuse, base.temporal.reuse);
        assert!(
            !needs_rebuild(&base, &v.config(&base)),
            "unchanged switches"
        );
        v.toggle_effect("ao");
        v.temporal_reuse = !v.temporal_reuse;
        let wanted = v.config(&base);
        assert_eq!(wanted.effects.ao, !base.effects.ao);
        assert_eq!(wanted.temporal.reuse, !base.temporal.reuse);
        assert_eq!(wanted.effects.indirect, base.effects.indirect);
        assert!(needs_rebuild(&base, &wanted));
    }

    #[test]
    fn ambient_switches_exclude_each_other() {
        let base = RenderConfig::default();
        assert!(base.effects.has("ao"));
        let ambient = effects::ambient_switches();
        assert!(ambient.len() >= 2, "{ambient:?}");
        let mut v = ViewState::new(&base);
        for name in &ambient {
            v.effects.set(name, false).unwrap();
        }
        for name in &ambient {
            v.toggle_effect(name);
            let on: Vec<&&str> = ambient.iter().filter(|n| v.effects.has(n)).collect();
            assert_eq!(on, [name], "after switching {name} on");
            assert!(v.config(&base).validate().is_ok(), "{name}");
        }
        // Switching one off leaves the others off.
        v.toggle_effect(ambient[ambient.len() - 1]);
        assert!(ambient.iter().all(|n| !v.effects.has(n)));
    }

    #[test]
    fn settings_turn_off_and_come_back_with_the_runs_value() {
        let base = RenderConfig::default();
        let n = effects::toggles().count();
        assert!(n > 0);
        for (i, t) in effects::toggles().enumerate() {
            let mut v = ViewState::new(&base);
            assert_eq!(v.toggles[i], (t.get)(&base), "{}", t.name);
            v.toggles[i] = !v.toggles[i];
            let flipped = v.config(&base);
            assert_eq!((t.get)(&flipped), v.toggles[i], "{}", t.name);
            assert!(needs_rebuild(&base, &flipped), "{}", t.name);
            v.toggles[i] = !v.toggles[i];
            assert_eq!(v.config(&base), base, "{} round-trips", t.name);
        }
    }

    #[test]
    fn keys_and_script_names_reach_every_switch() {
        let keys = effect_keys();
        for (i, name) in keys.iter().enumerate() {
            assert_eq!(Action::from_digit(i + 1), Some(Action::ToggleEffect(name)));
            assert_eq!(Action::from_name(name), Some(Action::ToggleEffect(name)));
        }
        for (i, t) in effects::toggles().enumerate() {
            let digit = keys.len() + 1 + i;
            assert_eq!(Action::from_digit(digit), Some(Action::ToggleSetting(i)));
            assert_eq!(Action::from_name(t.name), Some(Action::ToggleSetting(i)));
        }
        assert_eq!(Action::from_digit(0), None);
        assert_eq!(
            Action::from_digit(keys.len() + effects::toggles().count() + 1),
            None
        );
        let v = ViewState::new(&RenderConfig::default());
        let summary = v.summary();
        assert!(
            summary.starts_with("pcf ") && summary.ends_with(" reuse"),
            "{summary}"
        );
        assert_eq!(
            summary.split(' ').count(),
            keys.len() + effects::toggles().count() + 2
        );
        let help = help();
        for (_, buffer) in display_cycle() {
            assert!(help.contains(buffer), "{buffer} missing from the help");
        }
    }
}

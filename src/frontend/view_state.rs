//! What the viewer's keys control: the displayed buffer, effect switches and temporal reuse,
//! and how they map onto a renderer configuration.

use crate::effects::ssdo::config::SsdoConfig;
use crate::renderer::frame::Pcf;
use crate::renderer::RenderConfig;
use crate::resources::targets::Target;

/// The viewer's keys, printed by `H` and documented in docs/cli.md.
pub const HELP: &str = "\
ssgi view keys:
  mouse drag (left button held)  look around
  W A S D                        move forward / left / back / right
  Q E                            move down / up
  Shift / Ctrl (held)            move 4x faster / 4x slower
  Tab / Shift+Tab                cycle the displayed buffer (final, direct, shadow, AO,
                                 indirect, SSDO bounce, G-buffer normal / albedo /
                                 position; raw values clamped to 0..1)
  P                              soft (PCF) / hard shadows
  1 2                            toggle AO / indirect light (rebuilds the renderer:
                                 temporal histories start over)
  3 4                            toggle SSDO (in place of AO) / its bilateral filter
                                 (rebuild the renderer)
  R                              temporal reuse on / off (rebuilds the renderer)
  C                              print the camera as a keyframe (for --path files)
  H                              print this help
  Esc                            quit";

/// Buffers the viewer can show, in cycling order. Depth targets cannot be blitted to a colour
/// image and are left out; a target whose format lacks BLIT_SRC support is skipped.
pub const DISPLAY_CYCLE: [(Target, &str); 9] = [
    (Target::Output, "final"),
    (Target::Direct, "direct"),
    (Target::Shadow, "shadow"),
    (Target::Ao, "ao"),
    (Target::Indirect, "indirect"),
    (Target::SsdoBounce, "ssdo bounce"),
    (Target::GNormal, "normal"),
    (Target::GAlbedo, "albedo"),
    (Target::GPosition, "position"),
];

/// Effect switches, reaching the renderer through [`ViewState::config`]: `soft_shadows` (the
/// PCF kernel), `ao`, `indirect`, `ssdo` (exclusive with `ao`) and `filter` (SSDO's bilateral
/// filter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EffectToggles {
    pub soft_shadows: bool,
    pub ao: bool,
    pub indirect: bool,
    pub ssdo: bool,
    pub filter: bool,
}

/// What the viewer's keys control.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewState {
    /// Index into [`DISPLAY_CYCLE`].
    pub display: usize,
    pub effects: EffectToggles,
    pub temporal_reuse: bool,
    /// The PCF kernel to use when soft shadows are on (the one the run started with).
    soft_pcf: Pcf,
    /// The bilateral filter's side when it is on (the run's, or the default).
    filter_side: u32,
}

impl ViewState {
    /// The switches of a renderer created with `config`.
    pub fn new(config: &RenderConfig) -> Self {
        let soft = config.pcf != Pcf::HARD;
        Self {
            display: 0,
            effects: EffectToggles {
                soft_shadows: soft,
                ao: config.effects.ao,
                indirect: config.effects.indirect,
                ssdo: config.effects.ssdo,
                filter: config.ssdo.filter > 0,
            },
            temporal_reuse: config.temporal.reuse,
            soft_pcf: if soft { config.pcf } else { Pcf::DEFAULT },
            filter_side: if config.ssdo.filter > 0 {
                config.ssdo.filter
            } else {
                SsdoConfig::default().filter
            },
        }
    }

    /// The renderer configuration the switches ask for, starting from `current`.
    pub fn config(&self, current: &RenderConfig) -> RenderConfig {
        let mut config = *current;
        config.pcf = if self.effects.soft_shadows {
            self.soft_pcf
        } else {
            Pcf::HARD
        };
        config.effects.ao = self.effects.ao;
        config.effects.indirect = self.effects.indirect;
        config.effects.ssdo = self.effects.ssdo;
        config.ssdo.filter = if self.effects.filter {
            self.filter_side
        } else {
            0
        };
        config.temporal.reuse = self.temporal_reuse;
        config
    }

    pub fn display_target(&self) -> Target {
        DISPLAY_CYCLE[self.display % DISPLAY_CYCLE.len()].0
    }

    pub fn display_name(&self) -> &'static str {
        DISPLAY_CYCLE[self.display % DISPLAY_CYCLE.len()].1
    }

    pub fn summary(&self) -> String {
        let e = &self.effects;
        let flag = |on: bool, name: &str| {
            if on {
                name.to_string()
            } else {
                format!("-{name}")
            }
        };
        [
            flag(e.soft_shadows, "pcf"),
            flag(e.ao, "ao"),
            flag(e.indirect, "indirect"),
            flag(e.ssdo, "ssdo"),
            flag(e.filter, "filter"),
            flag(self.temporal_reuse, "reuse"),
        ]
        .join(" ")
    }
}

/// Whether a renderer made with `current` must be rebuilt to run `wanted`: effects and temporal
/// reuse choose passes and targets at creation; the PCF kernel changes in place.
pub fn needs_rebuild(current: &RenderConfig, wanted: &RenderConfig) -> bool {
    current.effects != wanted.effects
        || current.temporal.reuse != wanted.temporal.reuse
        || current.ssdo != wanted.ssdo
}

/// A viewer command, from a key (`window/keys.rs`) or from a test script.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    CycleDisplay(i32),
    ToggleShadows,
    ToggleAo,
    ToggleIndirect,
    ToggleSsdo,
    ToggleFilter,
    ToggleReuse,
    PrintCamera,
    Help,
    Quit,
}

impl Action {
    /// The action a test script names (`key=NAME`).
    pub fn from_name(name: &str) -> Option<Action> {
        Some(match name {
            "cycle" => Action::CycleDisplay(1),
            "pcf" => Action::ToggleShadows,
            "ao" => Action::ToggleAo,
            "indirect" => Action::ToggleIndirect,
            "ssdo" => Action::ToggleSsdo,
            "filter" => Action::ToggleFilter,
            "reuse" => Action::ToggleReuse,
            "camera" => Action::PrintCamera,
            "help" => Action::Help,
            "quit" => Action::Quit,
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcf_toggle_round_trips() {
        let base = RenderConfig::default();
        let mut v = ViewState::new(&base);
        assert!(v.effects.soft_shadows);
        v.effects.soft_shadows = false;
        assert_eq!(v.soft_pcf, base.pcf);
        assert_eq!(v.config(&base).pcf, Pcf::HARD);
        assert!(
            !needs_rebuild(&base, &v.config(&base)),
            "PCF changes in place"
        );
        let hard = ViewState::new(&RenderConfig {
            pcf: Pcf::HARD,
            ..base
        });
        assert!(!hard.effects.soft_shadows);
        assert_eq!(
            hard.soft_pcf,
            Pcf::DEFAULT,
            "turning PCF on uses the default kernel"
        );
    }

    #[test]
    fn effect_and_reuse_switches_reach_the_config() {
        let base = RenderConfig::default();
        let mut v = ViewState::new(&base);
        assert_eq!(v.effects.ao, base.effects.ao);
        assert_eq!(v.temporal_reuse, base.temporal.reuse);
        assert!(
            !needs_rebuild(&base, &v.config(&base)),
            "unchanged switches"
        );
        v.effects.ao = !v.effects.ao;
        v.temporal_reuse = !v.temporal_reuse;
        let wanted = v.config(&base);
        assert_eq!(wanted.effects.ao, !base.effects.ao);
        assert_eq!(wanted.temporal.reuse, !base.temporal.reuse);
        assert_eq!(wanted.effects.indirect, base.effects.indirect);
        assert!(needs_rebuild(&base, &wanted));
        v.effects.ssdo = true;
        assert_eq!(
            v.summary().split(' ').collect::<Vec<_>>(),
            [
                "pcf",
                if base.effects.ao { "-ao" } else { "ao" },
                "indirect",
                "ssdo",
                "filter",
                if base.temporal.reuse {
                    "-reuse"
                } else {
                    "reuse"
                }
            ]
        );
        // SSDO and its filter reach the configuration, and rebuild the renderer.
        v.effects.ao = false;
        v.effects.filter = false;
        let wanted = v.config(&base);
        assert!(wanted.effects.ssdo && !wanted.effects.ao);
        assert_eq!(wanted.ssdo.filter, 0);
        v.effects.filter = true;
        assert_eq!(v.config(&base).ssdo.filter, base.ssdo.filter);
        assert!(needs_rebuild(&base, &wanted));
    }
}

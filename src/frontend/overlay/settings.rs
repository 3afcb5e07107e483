//! The overlay's live settings: effect and reuse switches (the viewer's key actions) and
//! sweep keys (AO estimator, indirect filter, accumulation, VPLs, refresh budget). Widgets
//! only ask; the viewer applies each request through the command line's parsers and
//! `RenderConfig::validate`, as a script's `set=KEY:VALUE` (`window/app/actions.rs`).

use crate::config::antialias::AaMode;
use crate::config::parse::AccumulateMode;
use crate::config::sweep_key::value_names;
use crate::config::RenderConfig;
use crate::effects::ao::config::AoEstimator;
use crate::effects::indirect::config::IndirectFilter;
use crate::frontend::view_state::{effect_keys, Action};
use crate::sweep::keys::{apply, parse_key};

/// What a widget asks the viewer for.
#[derive(Clone, Debug, PartialEq)]
pub enum Request {
    /// A viewer action (an effect or reuse switch).
    Action(Action),
    /// A sweep key's new value, in the command line's syntax.
    Set(&'static str, String),
    /// Print the equivalent command line.
    CommandLine,
}

/// The names an enum's variants go by (`value_names::<E>`).
type Names = fn() -> Vec<String>;

/// Keys offered as a choice among their plain values, each list from its enum (the one source
/// of the names the command line and the sweep take).
const CHOICES: [(&str, &str, Names); 4] = [
    ("AO", "ao.estimator", value_names::<AoEstimator>),
    ("indirect", "indirect.filter", value_names::<IndirectFilter>),
    (
        "accumulate",
        "temporal.accumulate",
        value_names::<AccumulateMode>,
    ),
    ("antialias", "aa", value_names::<AaMode>),
];

/// Which of `values` of sweep key `key` the configuration holds: the one whose parser turns
/// `config` into itself (a value with another parameter, `gated:3`, matches none).
pub fn current<'a>(config: &RenderConfig, key: &str, values: &'a [String]) -> Option<&'a str> {
    let key = parse_key(key).ok()?;
    values.iter().map(String::as_str).find(|v| {
        let mut c = *config;
        apply(&mut c, key, v).is_ok() && c == *config
    })
}

/// The viewer's own setting (not a sweep key): the render size as a fraction of the
/// window's, `--render-scale`.
pub const RENDER_SCALE: &str = "render_scale";

/// The edit fields' values, kept between frames so a drag applies once, on release.
pub struct Fields<'a> {
    pub vpls: &'a mut u32,
    /// Refresh budget, percent.
    pub budget: &'a mut f32,
    /// The render scale being edited, and the one in use.
    pub scale: (&'a mut f32, f32),
}

/// The settings section.
pub fn show(ui: &mut egui::Ui, config: &RenderConfig, f: Fields<'_>, out: &mut Vec<Request>) {
    let Fields {
        vpls,
        budget,
        scale: (scale, scale_now),
    } = f;
    ui.horizontal_wrapped(|ui| {
        for name in effect_keys() {
            let mut on = config.effects.has(name);
            if ui.checkbox(&mut on, *name).changed() {
                out.push(Request::Action(Action::ToggleEffect(name)));
            }
        }
        let mut reuse = config.temporal.reuse;
        if ui.checkbox(&mut reuse, "reuse").changed() {
            out.push(Request::Action(Action::ToggleReuse));
        }
    });
    egui::Grid::new("overlay settings")
        .num_columns(2)
        .spacing([8.0, 1.0])
        .show(ui, |ui| {
            for (label, key, values) in CHOICES {
                ui.label(label);
                let values = values();
                let now = current(config, key, &values);
                egui::ComboBox::from_id_salt(key)
                    .selected_text(now.unwrap_or("(other)"))
                    .show_ui(ui, |ui| {
                        for v in values.iter().map(String::as_str) {
                            if ui.selectable_label(now == Some(v), v).clicked() && now != Some(v) {
                                out.push(Request::Set(key, v.to_string()));
                            }
                        }
                    });
                ui.end_row();
            }
            ui.label("VPLs");
            let r = ui.add(egui::DragValue::new(vpls).range(1..=16384));
            if released(&r) && *vpls != config.indirect.vpls {
                out.push(Request::Set("indirect.vpls", vpls.to_string()));
            }
            ui.end_row();
            ui.label("refresh %");
            let r = ui.add(egui::DragValue::new(budget).range(0.1..=100.0).speed(0.5));
            if released(&r) && (*budget - 100.0 * config.temporal.refresh_budget).abs() > 1e-3 {
                out.push(Request::Set(
                    "temporal.refresh_budget",
                    format!("{budget}%"),
                ));
            }
            ui.end_row();
            ui.label("render scale");
            let r = ui.add(egui::DragValue::new(scale).range(0.1..=1.0).speed(0.01));
            if released(&r) && (*scale - scale_now).abs() > 1e-4 {
                out.push(Request::Set(RENDER_SCALE, format!("{scale}")));
            }
            ui.end_row();
        });
    if ui.button("print the command line").clicked() {
        out.push(Request::CommandLine);
    }
}

/// An edit field's value is final: the drag ended, or it was typed and left.
fn released(r: &egui::Response) -> bool {
    r.drag_stopped() || (r.changed() && !r.dragged())
}

/// `base` (the command line the viewer started with) plus each live setting as the command
/// line's option, where the sweep key names one (`--ao`, `--vpls`, ...); switches as the
/// configuration now has them.
pub fn command_line(
    base: &[String],
    config: &RenderConfig,
    settings: &[(String, String)],
) -> String {
    let mut args: Vec<String> = base.to_vec();
    for (key, value) in settings {
        let option = match key.as_str() {
            RENDER_SCALE => Some("--render-scale"),
            _ => parse_key(key).ok().and_then(|k| option_of(k.description)),
        };
        match option {
            Some(option) => {
                args.push(option.to_string());
                args.push(value.clone());
            }
            None => args.push(format!("# {key}={value} (no option of its own)")),
        }
    }
    let effects: Vec<&str> = crate::config::Effects::NAMES
        .into_iter()
        .filter(|n| config.effects.has(n))
        .collect();
    args.extend(["--effects".into(), effects.join(",")]);
    args.extend([
        "--reuse".into(),
        if config.temporal.reuse { "on" } else { "off" }.into(),
    ]);
    args.join(" ")
}

/// The command-line option a sweep key's description names: `... (--vpls)` gives `--vpls`.
fn option_of(description: &str) -> Option<&str> {
    let start = description.find("(--")? + 1;
    let len = description[start..].find([')', ' ', ','])?;
    Some(&description[start..start + len])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn current_value_comes_from_the_keys_parser() {
        let mut c = RenderConfig::default();
        assert_eq!(current(&c, "ao.estimator", &CHOICES[0].2()), Some("thesis"));
        apply(&mut c, parse_key("ao.estimator").unwrap(), "gtao").unwrap();
        assert_eq!(current(&c, "ao.estimator", &CHOICES[0].2()), Some("gtao"));
        apply(&mut c, parse_key("temporal.accumulate").unwrap(), "gated:7").unwrap();
        assert_eq!(current(&c, "temporal.accumulate", &CHOICES[2].2()), None);
    }

    #[test]
    fn command_line_uses_each_keys_option() {
        assert_eq!(
            option_of("VPLs gathered per pixel (--vpls)"),
            Some("--vpls")
        );
        assert_eq!(option_of("SSAO estimator (--ao)"), Some("--ao"));
        assert_eq!(option_of("no option here"), None);
        let c = RenderConfig::default();
        let line = command_line(
            &["ssgi".into(), "view".into()],
            &c,
            &[
                ("ao.estimator".into(), "gtao".into()),
                ("indirect.vpls".into(), "64".into()),
            ],
        );
        assert!(
            line.starts_with("ssgi view --ao gtao --vpls 64 --effects "),
            "{line}"
        );
        assert!(line.ends_with("--reuse on"), "{line}");
    }
}

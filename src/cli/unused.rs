//! Options of a technique the run leaves off (`--ssdo-scale 0.5` without ssdo in --effects)
//! change nothing: the command line says so in a warning, not an error, since a script may
//! pass one set of options to runs of several effect sets. A sweep warns only about options
//! that no combination uses, once each, however its keys cross.

use super::args::{Cli, Command as Job};
use crate::config::RenderConfig;
use crate::effects::indirect::config::IndirectFilter;
use clap::parser::ValueSource;
use clap::{ArgMatches, Command};

/// An effect's flattened options (clap names the group after the `Args` struct), when they
/// matter, and why not otherwise.
struct Group {
    id: &'static str,
    applies: fn(&RenderConfig) -> bool,
    why: &'static str,
}

const GROUPS: [Group; 5] = [
    Group {
        id: "AoArgs",
        applies: |c| c.effects.ao,
        why: "ao is not in --effects",
    },
    Group {
        id: "IndirectArgs",
        applies: |c| c.effects.indirect,
        why: "indirect is not in --effects",
    },
    Group {
        id: "CcipcaArgs",
        applies: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Ccipca,
        why: "the indirect light is not filtered by CCIPCA (--indirect-filter ccipca)",
    },
    Group {
        id: "SvgfArgs",
        applies: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Svgf,
        why: "the indirect light is not filtered by SVGF (--indirect-filter svgf)",
    },
    Group {
        id: "SsdoArgs",
        applies: |c| c.effects.ssdo,
        why: "ssdo is not in --effects",
    },
];

/// One warning per effect whose options were given on the command line but apply to none of
/// the run's configurations.
pub fn warnings(cli: &Cli, cmd: &Command, matches: &ArgMatches) -> Vec<String> {
    let Some((name, sub_matches)) = matches.subcommand() else {
        return Vec::new();
    };
    let Some(sub) = cmd.find_subcommand(name) else {
        return Vec::new();
    };
    let configs = configurations(cli);
    let sweep = matches!(cli.command, Job::Sweep(_));
    let mut out = Vec::new();
    for group in GROUPS {
        if configs.is_empty() || configs.iter().any(group.applies) {
            continue;
        }
        let given = given_options(sub, sub_matches, group.id);
        if given.is_empty() {
            continue;
        }
        let verb = if given.len() == 1 { "has" } else { "have" };
        let scope = if sweep { " in any combination" } else { "" };
        out.push(format!(
            "{} {verb} no effect{scope}: {}",
            given.join(", "),
            group.why
        ));
    }
    out
}

/// The configurations a command renders: the flags', or a sweep's every combination (none
/// when they do not parse: the job reports that).
fn configurations(cli: &Cli) -> Vec<RenderConfig> {
    let scene = match &cli.command {
        Job::Render(a) => &a.scene,
        Job::Bench(a) => &a.scene,
        Job::View(a) => &a.scene,
        Job::Sweep(a) => {
            let base = a.scene.render_config();
            let varies: Option<Vec<_>> = a
                .vary
                .iter()
                .map(|v| crate::sweep::keys::parse_vary(v).ok())
                .collect();
            return varies
                .and_then(|v| crate::sweep::keys::combinations(&base, &v).ok())
                .map(|combos| combos.into_iter().map(|(_, c)| c).collect())
                .unwrap_or_default();
        }
        _ => return Vec::new(),
    };
    vec![scene.render_config()]
}

/// The options of `group` given on the command line, as `--name`.
fn given_options(sub: &Command, matches: &ArgMatches, group: &str) -> Vec<String> {
    let Some(g) = sub.get_groups().find(|g| g.get_id() == group) else {
        return Vec::new();
    };
    g.get_args()
        .filter(|id| matches.value_source(id.as_str()) == Some(ValueSource::CommandLine))
        .filter_map(|id| sub.get_arguments().find(|a| a.get_id() == id))
        .filter_map(|a| a.get_long().map(|l| format!("--{l}")))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::parse::try_parse_from;

    fn warnings(args: &[&str]) -> Vec<String> {
        let args = std::iter::once("ssgi").chain(args.iter().copied());
        try_parse_from(args).unwrap().warnings
    }

    #[test]
    fn options_of_an_effect_that_is_off_are_named_once() {
        assert_eq!(
            warnings(&[
                "render",
                "--effects",
                "direct,ao",
                "--ssdo-scale",
                "0.5",
                "--bilateral",
                "5"
            ]),
            ["--bilateral, --ssdo-scale have no effect: ssdo is not in --effects"]
        );
        assert_eq!(
            warnings(&["bench", "--svgf-alpha", "0.1"]),
            [
                "--svgf-alpha has no effect: the indirect light is not filtered by SVGF \
              (--indirect-filter svgf)"
            ]
        );
        // Given where they apply, or left at their defaults: nothing to say.
        assert!(warnings(&["render", "--effects", "ssdo", "--ssdo-scale", "0.5"]).is_empty());
        assert!(warnings(&["render", "--effects", "direct"]).is_empty());
        assert!(
            warnings(&["render", "--indirect-filter", "svgf", "--svgf-alpha", "0.1"]).is_empty()
        );
    }

    #[test]
    fn a_sweep_warns_only_about_options_no_combination_uses() {
        // Crossed keys (GTAO's steps under the thesis estimator too) are valid; an option
        // that some combination uses (SVGF's, where indirect.filter is svgf) is no warning.
        let args = [
            "sweep",
            "--effects",
            "direct,ao,indirect",
            "--svgf-alpha",
            "0.1",
            "--vary",
            "indirect.filter=accumulate,svgf",
            "--vary",
            "ao.estimator=thesis,gtao",
            "--vary",
            "ao.steps=4,8",
        ];
        assert!(warnings(&args).is_empty(), "{:?}", warnings(&args));
        let args = [
            "sweep",
            "--effects",
            "direct",
            "--ao-samples",
            "8",
            "--vary",
            "pcf=9,25",
        ];
        assert_eq!(
            warnings(&args),
            ["--ao-samples has no effect in any combination: ao is not in --effects"]
        );
    }
}

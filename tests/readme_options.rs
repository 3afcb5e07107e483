//! The README and the command line agree (issue 19): every option in the README's option
//! tables exists on `render` and `bench` (or globally) with the default the table states, and
//! every long option of every subcommand is mentioned in the README.

use clap::CommandFactory;
use ssgi::cli::args::Cli;
use std::collections::BTreeMap;

/// `--name` -> clap's default, joined with "," ("" when it has none), of subcommand `sub`.
fn options(sub: Option<&str>) -> BTreeMap<String, String> {
    let root = Cli::command();
    let cmd = match sub {
        Some(name) => root
            .find_subcommand(name)
            .unwrap_or_else(|| panic!("no subcommand {name}"))
            .clone(),
        None => root,
    };
    cmd.get_arguments()
        // Hidden options are the tests' own hooks (the viewer's --script, --capture).
        .filter(|a| !a.is_hide_set())
        .filter_map(|a| {
            let long = a.get_long()?;
            let default: Vec<String> = a
                .get_default_values()
                .iter()
                .map(|v| v.to_string_lossy().into_owned())
                .collect();
            Some((format!("--{long}"), default.join(",")))
        })
        .collect()
}

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap()
}

/// The README's option table rows: (option, default cell when the table has one).
fn table_rows(text: &str) -> Vec<(String, Option<String>)> {
    text.lines()
        .filter(|l| l.starts_with("| `--"))
        .map(|l| {
            let cells: Vec<&str> = l.trim_matches('|').split(" | ").map(str::trim).collect();
            let name: String = cells[0]
                .trim_start_matches('`')
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                .collect();
            let default = (cells.len() > 2).then(|| cells[1].to_string());
            (name, default)
        })
        .collect()
}

#[test]
fn option_tables_match_clap() {
    let text = readme();
    let rows = table_rows(&text);
    assert!(rows.len() >= 25, "only {} option rows found", rows.len());
    let global = options(None);
    let subs = ["render", "bench"].map(|s| (s, options(Some(s))));
    let mut problems = Vec::new();
    for (name, default) in &rows {
        if default.is_none() {
            if !global.contains_key(name) {
                problems.push(format!(
                    "{name}: in the global table but not a global option"
                ));
            }
            continue;
        }
        let stated = default.as_deref().unwrap_or_default();
        for (sub, opts) in &subs {
            let Some(clap_default) = opts.get(name) else {
                problems.push(format!(
                    "{name}: documented but `ssgi {sub}` has no such option"
                ));
                continue;
            };
            // The table's default is the first backticked value of its cell. An option without
            // a clap default computes it (a flag that is off, thresholds that follow the sample
            // range): the cell describes that, and is not compared.
            let shown = stated.split('`').nth(1).unwrap_or(stated);
            if !clap_default.is_empty() && shown != clap_default {
                problems.push(format!(
                    "{name}: README default {stated:?}, `ssgi {sub}` default {clap_default:?}"
                ));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "README and clap disagree:\n{}",
        problems.join("\n")
    );
}

#[test]
fn every_option_is_documented() {
    let text = readme();
    let mut missing = Vec::new();
    let subs = [
        "render",
        "bench",
        "view",
        "table",
        "reference",
        "sweep",
        "stress",
    ];
    for (sub, opts) in subs.map(|s| (s, options(Some(s)))) {
        for name in opts.keys() {
            if name == "--help" || name == "--version" {
                continue;
            }
            let mentioned = text.match_indices(name.as_str()).any(|(i, _)| {
                // The whole option, not the prefix of a longer one.
                let next = text[i + name.len()..].chars().next();
                !next.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-')
            });
            if !mentioned {
                missing.push(format!("ssgi {sub} {name}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "not in the README:\n{}",
        missing.join("\n")
    );
}

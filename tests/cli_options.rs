//! docs/cli.md and the command line agree (issue 19): every option of every subcommand has a
//! row in an option table of docs/cli.md whose `<!-- options: ... -->` marker names that
//! subcommand (or `global`), every row names an option that each subcommand its marker names
//! has, with the default clap has, and every table has its section in docs/tables.md. The
//! README's example commands parse, one per subcommand at least.

use clap::{CommandFactory, Parser};
use ssgi::cli::args::Cli;
use std::collections::BTreeMap;

fn doc(path: &str) -> String {
    let full = format!("{}/{path}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{full}: {e}"))
}

/// What the documentation must say of one option: the default it states, compared when clap
/// has one (a flag's is `off`).
#[derive(Debug)]
struct ClapOption {
    default: Option<String>,
}

/// The command as the program parses it, global options propagated to every subcommand.
fn command() -> clap::Command {
    let mut root = Cli::command();
    root.build();
    root
}

/// `--name` -> its default, of the root command (`None`) or subcommand `sub`. Hidden options
/// are the tests' own hooks (the viewer's --script, --capture); --help and --version are
/// clap's.
fn options(root: &clap::Command, sub: Option<&str>) -> BTreeMap<String, ClapOption> {
    let cmd = match sub {
        Some(name) => root
            .find_subcommand(name)
            .unwrap_or_else(|| panic!("no subcommand {name}")),
        None => root,
    };
    cmd.get_arguments()
        .filter(|a| !a.is_hide_set())
        .filter_map(|a| {
            let long = a.get_long()?;
            if long == "help" || long == "version" {
                return None;
            }
            let default = if a.get_action().takes_values() {
                let values: Vec<String> = a
                    .get_default_values()
                    .iter()
                    .map(|v| v.to_string_lossy().into_owned())
                    .collect();
                (!values.is_empty()).then(|| values.join(","))
            } else {
                Some("off".to_string())
            };
            Some((format!("--{long}"), ClapOption { default }))
        })
        .collect()
}

/// One option table of docs/cli.md: the subcommands its marker names (`global` for the root's
/// options) and its rows as (option, default cell when the table has a default column).
#[derive(Debug)]
struct Table {
    line: usize,
    scope: Vec<String>,
    rows: Vec<(String, Option<String>)>,
}

/// The cells of a table line; `\|` inside a cell is not a separator.
fn cells(line: &str) -> Vec<String> {
    line.trim()
        .trim_matches('|')
        .split(" | ")
        .map(|c| c.trim().to_string())
        .collect()
}

/// Every table right after a `<!-- options: SCOPE... -->` line.
fn tables(text: &str) -> Vec<Table> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(scope) = line
            .trim()
            .strip_prefix("<!-- options:")
            .and_then(|r| r.strip_suffix("-->"))
        else {
            continue;
        };
        let body: Vec<&str> = lines[i + 1..]
            .iter()
            .take_while(|l| l.starts_with('|'))
            .copied()
            .collect();
        assert!(
            body.len() >= 3,
            "docs/cli.md:{}: a marker must be followed by a table (header, separator, rows)",
            i + 1
        );
        let header = cells(body[0]);
        let default_col = header.iter().position(|c| c == "default");
        let rows = body[2..]
            .iter()
            .map(|l| {
                let cells = cells(l);
                let name: String = cells[0]
                    .trim_start_matches('`')
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                    .collect();
                assert!(
                    name.starts_with("--"),
                    "docs/cli.md: a row that names no option: {l}"
                );
                (name, default_col.map(|c| cells[c].clone()))
            })
            .collect();
        out.push(Table {
            line: i + 1,
            scope: scope.split_whitespace().map(str::to_string).collect(),
            rows,
        });
    }
    out
}

fn subcommands(root: &clap::Command) -> Vec<String> {
    root.get_subcommands()
        .map(|s| s.get_name().to_string())
        .filter(|n| n != "help")
        .collect()
}

/// Every row is an option of each subcommand its table names, with clap's default.
#[test]
fn option_tables_match_clap() {
    let root = command();
    let tables = tables(&doc("docs/cli.md"));
    assert!(
        tables.len() >= 8,
        "only {} option tables found",
        tables.len()
    );
    let subs = subcommands(&root);
    let mut problems = Vec::new();
    for table in &tables {
        for scope in &table.scope {
            let opts = if scope == "global" {
                options(&root, None)
            } else if subs.contains(scope) {
                options(&root, Some(scope))
            } else {
                problems.push(format!("line {}: no subcommand {scope}", table.line));
                continue;
            };
            for (name, cell) in &table.rows {
                let Some(opt) = opts.get(name) else {
                    problems.push(format!("{name}: documented for `{scope}`, which has none"));
                    continue;
                };
                // The table's default is the first backticked value of its cell. An option
                // without a clap default computes it (thresholds that follow the sample range,
                // the rotation limit): the cell describes that, and is not compared.
                let (Some(cell), Some(want)) = (cell, &opt.default) else {
                    continue;
                };
                let shown = cell.split('`').nth(1).unwrap_or(cell);
                if shown != want {
                    problems.push(format!(
                        "{name}: docs/cli.md default {cell:?}, `{scope}` default {want:?}"
                    ));
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "docs/cli.md and clap disagree:\n{}",
        problems.join("\n")
    );
}

/// Every option of every subcommand has a row in a table for that subcommand (its own, or the
/// global options' table for the options it shares with every subcommand).
#[test]
fn every_option_has_a_row() {
    let root = command();
    let tables = tables(&doc("docs/cli.md"));
    let rows_of = |scope: &str| -> Vec<&String> {
        tables
            .iter()
            .filter(|t| t.scope.iter().any(|s| s == scope))
            .flat_map(|t| t.rows.iter().map(|(name, _)| name))
            .collect()
    };
    let global = rows_of("global");
    let mut missing = Vec::new();
    for name in options(&root, None).keys() {
        if !global.contains(&name) {
            missing.push(format!("ssgi {name} (global)"));
        }
    }
    let subs = subcommands(&root);
    assert!(subs.len() >= 7, "subcommands: {subs:?}");
    for sub in &subs {
        let rows = rows_of(sub);
        for name in options(&root, Some(sub)).keys() {
            if !rows.contains(&name) && !global.contains(&name) {
                missing.push(format!("ssgi {sub} {name}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "no row in docs/cli.md:\n{}",
        missing.join("\n")
    );
}

/// Every table `ssgi table` takes has its section in docs/tables.md.
#[test]
fn every_table_has_a_section() {
    let root = command();
    let table = root.find_subcommand("table").unwrap();
    let which = table
        .get_positionals()
        .next()
        .expect("ssgi table takes the table's name");
    let text = doc("docs/tables.md");
    let names: Vec<String> = which
        .get_possible_values()
        .iter()
        .map(|v| v.get_name().to_string())
        .collect();
    assert!(names.len() >= 7, "tables: {names:?}");
    let missing: Vec<&String> = names
        .iter()
        .filter(|n| {
            !text
                .lines()
                .any(|l| l.starts_with("## ") && l.contains(&format!("`ssgi table {n}`")))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "no `## ... ssgi table NAME` heading in docs/tables.md for {missing:?}"
    );
}

/// The `ssgi` command lines of a file's ```sh blocks (environment assignments and comments
/// left out), as arguments.
fn example_commands(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut in_sh = false;
    for line in text.lines() {
        match line.trim() {
            "```sh" => in_sh = true,
            "```" => in_sh = false,
            l if in_sh => {
                let l = l.split(" #").next().unwrap();
                let words: Vec<&str> = l
                    .split_whitespace()
                    .skip_while(|w| w.contains('=') && !w.starts_with('-'))
                    .collect();
                if words.first() == Some(&"ssgi") {
                    assert!(!l.contains(['"', '\'', '\\']), "quote or escape in {l}");
                    out.push(words.iter().map(|w| w.to_string()).collect());
                }
            }
            _ => {}
        }
    }
    out
}

/// The README's examples parse, and there is one for every subcommand; so do the examples of
/// docs/cli.md and docs/tables.md.
#[test]
fn examples_parse() {
    let readme = example_commands(&doc("README.md"));
    let mut problems = Vec::new();
    let mut shown = Vec::new();
    for args in readme
        .iter()
        .chain(&example_commands(&doc("docs/cli.md")))
        .chain(&example_commands(&doc("docs/tables.md")))
    {
        match Cli::try_parse_from(args) {
            Ok(_) => {}
            Err(e) => problems.push(format!("{}: {e}", args.join(" "))),
        }
    }
    let subs = subcommands(&command());
    for args in &readme {
        if let Some(sub) = args.iter().find(|a| subs.contains(a)) {
            shown.push(sub.clone());
        }
    }
    for sub in &subs {
        if !shown.contains(sub) {
            problems.push(format!("the README has no example of `ssgi {sub}`"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

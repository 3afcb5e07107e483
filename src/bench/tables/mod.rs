//! The papers' tables (`ssgi table <name>`): one declaration per table (its name, title,
//! defaults and run), read by the command line and the job, so adding a table is one entry
//! here and one file beside it. Every table writes `report.json`, `report.md` and
//! `<name>.csv` through `run::write_reports`, its Markdown and CSV from one `Sheet`.

pub mod ao;
pub mod chang1;
pub mod chang_flicker;
pub mod chiu1;
mod def;
pub mod dynamic;
pub mod paths;
pub mod reuse;
pub mod run;
pub mod szentandrasi;
pub mod thesis41;
pub mod walkthroughs;

pub use def::TableDef;

/// Every table, in the order `--help` lists them.
pub const TABLES: [&TableDef; 8] = [
    &thesis41::TABLE,
    &walkthroughs::TABLE,
    &szentandrasi::TABLE,
    &chiu1::TABLE,
    &chang1::TABLE,
    &chang_flicker::TABLE,
    &dynamic::TABLE,
    &ao::TABLE,
];

/// The table called `name`.
pub fn find(name: &str) -> Option<&'static TableDef> {
    TABLES.into_iter().find(|t| t.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_distinct_and_found() {
        for (i, t) in TABLES.iter().enumerate() {
            assert!(TABLES[..i].iter().all(|u| u.name != t.name), "{}", t.name);
            assert_eq!(find(t.name).unwrap().title, t.title);
            assert!(!t.title.is_empty() && !t.summary.is_empty());
            assert!(t.frames > 0);
        }
        assert!(find("thesis-4.2").is_none());
    }

    /// A table's `--set` prefixes name the sweep keys' registry, so a renamed key cannot leave
    /// a table offering a parameter that no longer exists.
    #[test]
    fn settable_prefixes_name_sweep_keys() {
        let keys = crate::sweep::keys::all_keys();
        for t in TABLES {
            for prefix in t.settable {
                assert!(
                    keys.iter().any(|k| k.name.starts_with(prefix)),
                    "table {}: --set prefix {prefix} matches no sweep key",
                    t.name
                );
            }
        }
    }

    #[test]
    fn sizes_prefer_the_command_line_then_the_papers() {
        let chang = find("chang-1").unwrap();
        assert_eq!(chang.sizes(Some((64, 48))), [(64, 48)]);
        assert_eq!(chang.sizes(None).len(), 5);
        assert_eq!(find("dynamic").unwrap().sizes(None), [(256, 256)]);
    }
}

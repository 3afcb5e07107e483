//! A parameter `ssgi sweep --vary KEY=V1,V2,...` can vary: declared as data where the
//! parameter lives (frame-wide ones in `sweep::keys`, an effect's in its folder's
//! `sweep.rs`), so the sweep learns an effect's keys from the registry.

use super::RenderConfig;
use std::fmt;

/// One sweepable parameter. Values use the command line's syntax and parsers, so a sweep
/// accepts exactly what a single run accepts.
pub struct SweepKey {
    /// The name given to `--vary`: the field's path in `RenderConfig` (`ao.samples`).
    pub name: &'static str,
    /// The values accepted, as shown in errors and `ssgi sweep --list-keys`.
    pub syntax: Syntax,
    /// What it changes (with the command-line option that sets the same).
    pub description: &'static str,
    /// Write `value` into the configuration; the error says why the value is not one of
    /// `syntax`'s. Only the value's own range is checked: `RenderConfig::validate` judges it
    /// beside the other fields.
    pub set: fn(&mut RenderConfig, &str) -> Result<(), String>,
}

/// The values a key accepts.
#[derive(Clone, Copy)]
pub enum Syntax {
    /// Described in words (`integer 1..=4096`).
    Text(&'static str),
    /// One of an enum's names: the enum (a `clap::ValueEnum`, as the command line's option
    /// takes it) is the list's one source, so a new variant is offered everywhere at once.
    Names(fn() -> Vec<String>),
}

impl Syntax {
    /// The names a `Names` key takes; `None` for one described in words.
    pub fn names(self) -> Option<Vec<String>> {
        match self {
            Syntax::Text(_) => None,
            Syntax::Names(names) => Some(names()),
        }
    }
}

impl fmt::Display for Syntax {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Syntax::Text(t) => f.write_str(t),
            Syntax::Names(names) => f.write_str(&names().join("|")),
        }
    }
}

/// The names of `E`'s variants, as its command-line option and `--vary` take them (hidden
/// ones left out), in declaration order.
pub fn value_names<E: clap::ValueEnum>() -> Vec<String> {
    E::value_variants()
        .iter()
        .filter_map(|v| v.to_possible_value())
        .filter(|v| !v.is_hide_set())
        .map(|v| v.get_name().to_string())
        .collect()
}

/// The name of `value` as its command-line option takes it.
pub fn value_name<E: clap::ValueEnum>(value: E) -> String {
    value
        .to_possible_value()
        .map_or_else(String::new, |v| v.get_name().to_string())
}

impl PartialEq for SweepKey {
    fn eq(&self, other: &SweepKey) -> bool {
        self.name == other.name
    }
}

impl Eq for SweepKey {}

impl fmt::Debug for SweepKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

impl fmt::Display for SweepKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

/// Sets the field a key should set, written out by hand (tests).
#[cfg(test)]
pub type SetByHand = fn(&mut RenderConfig);

/// Test helper: every key of `keys` has a case, in the keys' order, and setting its value on
/// the default configuration changes exactly what the case's hand-written setter changes.
#[cfg(test)]
pub fn assert_each_key_sets_its_field(keys: &[SweepKey], cases: Vec<(&str, &str, SetByHand)>) {
    let base = RenderConfig::default();
    assert_eq!(cases.len(), keys.len(), "a key without a test");
    for (key, (name, value, by_hand)) in keys.iter().zip(cases) {
        assert_eq!(key.name, name, "cases in the keys' order");
        let mut expected = base;
        by_hand(&mut expected);
        assert_ne!(
            expected, base,
            "{name}={value} must differ from the default"
        );
        let mut got = base;
        (key.set)(&mut got, value).unwrap();
        assert_eq!(got, expected, "{name}={value}");
    }
}

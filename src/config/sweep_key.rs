//! A parameter `ssgi sweep --vary KEY=V1,V2,...` can vary: declared as data where the
//! parameter lives (frame-wide ones in `bench::sweep_keys`, an effect's in its folder's
//! `sweep.rs`), so the sweep learns an effect's keys from the registry.

use super::RenderConfig;
use std::fmt;

/// One sweepable parameter. Values use the command line's syntax and parsers, so a sweep
/// accepts exactly what a single run accepts.
pub struct SweepKey {
    /// The name given to `--vary`: the field's path in `RenderConfig` (`ao.samples`).
    pub name: &'static str,
    /// The values accepted, as shown in errors and `ssgi sweep --list-keys`.
    pub syntax: &'static str,
    /// What it changes (with the command-line option that sets the same).
    pub description: &'static str,
    /// Write `value` into the configuration; the error says why the value is not one of
    /// `syntax`'s. Only the value's own range is checked: `RenderConfig::validate` judges it
    /// beside the other fields.
    pub set: fn(&mut RenderConfig, &str) -> Result<(), String>,
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

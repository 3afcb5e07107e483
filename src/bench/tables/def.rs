//! What a table declares: its name, title, defaults and how it runs.

use crate::bench::warmup::Warmup;
use crate::bench::TableOptions;
use crate::config::Effects;
use crate::error::Result;
use crate::frontend::sink::FrameSink;
use crate::vk::Context;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Measure a table with `opts` and write its files into the directory; returns their paths.
pub type RunTable =
    fn(&Arc<Context>, &mut dyn FrameSink, &TableOptions, &Path) -> Result<Vec<PathBuf>>;

/// One table of `ssgi table`.
pub struct TableDef {
    /// The command-line name and the CSV's file stem.
    pub name: &'static str,
    /// One line for `--help`.
    pub summary: &'static str,
    /// The report's heading.
    pub title: &'static str,
    /// Size, frames and warmup when the command line leaves them out.
    pub size: (u32, u32),
    pub frames: u32,
    pub warmup: Warmup,
    /// The paper's sizes, each a set of rows, unless `--size` names one (empty: `size`).
    pub sizes: &'static [(u32, u32)],
    /// The effects rows render unless `--effects` says; `None`: the rows choose their own and
    /// `--effects` is refused.
    pub effects: Option<Effects>,
    /// Prefixes of the sweep keys `--set` may change (`svgf.`, or a whole key): parameters of
    /// the compared techniques that no row sets itself. Empty: `--set` is refused.
    pub settable: &'static [&'static str],
    pub run: RunTable,
}

impl TableDef {
    /// Whether `--set` may change `key` (a sweep key's name).
    pub fn settable(&self, key: &str) -> bool {
        self.settable.iter().any(|prefix| key.starts_with(prefix))
    }

    /// The sizes to measure: `--size`, else the paper's, else the default.
    pub fn sizes(&self, given: Option<(u32, u32)>) -> Vec<(u32, u32)> {
        match given {
            Some(size) => vec![size],
            None if self.sizes.is_empty() => vec![self.size],
            None => self.sizes.to_vec(),
        }
    }
}

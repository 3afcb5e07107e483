//! What a table run was asked for, independent of the command line.

use crate::bench::warmup::Warmup;
use crate::config::sweep_key::SweepKey;
use crate::config::{Effects, RenderConfig};
use crate::error::{Error, Result};
use std::path::PathBuf;

#[derive(Clone, Debug)]
pub struct TableOptions {
    /// Render size (width, height): `--size`, else the table's default.
    pub size: (u32, u32),
    /// The sizes whose rows a table measures (`TableDef::sizes`).
    pub sizes: Vec<(u32, u32)>,
    /// Frames measured per row along the path, after the warmup (`warmup::before_path`).
    pub frames: u32,
    pub warmup: Warmup,
    /// Frame i of the path is shown at i / fps seconds.
    pub fps: f32,
    /// Camera path override (table-specific meaning; `None`: the table's default).
    pub path: Option<String>,
    /// Effects rendered by every row.
    pub effects: Effects,
    /// Asset directory (`None`: `$SSGI_ASSETS`).
    pub assets: Option<PathBuf>,
    /// Show progress bars on stderr.
    pub progress: bool,
    /// The command line, recorded in the report.
    pub command: String,
    /// `--set KEY=VALUE`, in the order given: applied to every row's configuration after the
    /// table's own choices (the table accepts only keys its rows leave alone).
    pub sets: Vec<(&'static SweepKey, String)>,
}

impl TableOptions {
    /// `config` with every `--set` applied; a refused value names its key.
    pub fn with_sets(&self, mut config: RenderConfig) -> Result<RenderConfig> {
        for (key, value) in &self.sets {
            (key.set)(&mut config, value)
                .map_err(|why| Error::Config(format!("--set {key}={value}: {why}")))?;
        }
        Ok(config)
    }

    /// The `--set`s as `KEY=VALUE`, for reports ("none" without any).
    pub fn sets_text(&self) -> String {
        if self.sets.is_empty() {
            return "none".into();
        }
        let all: Vec<String> = self.sets.iter().map(|(k, v)| format!("{k}={v}")).collect();
        all.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options(sets: Vec<(&'static SweepKey, String)>) -> TableOptions {
        TableOptions {
            size: (8, 8),
            sizes: vec![],
            frames: 1,
            warmup: Warmup::Frames(0),
            fps: 60.0,
            path: None,
            effects: Effects::ALL,
            assets: None,
            progress: false,
            command: String::new(),
            sets,
        }
    }

    fn key(name: &str) -> &'static SweepKey {
        crate::sweep::keys::parse_key(name).unwrap()
    }

    /// Each `--set` changes its field and nothing else, in order; a refused value names its
    /// key; no sets leave the configuration as it was.
    #[test]
    fn sets_change_their_fields_in_order() {
        let base = RenderConfig::default();
        assert_eq!(options(vec![]).with_sets(base).unwrap(), base);
        assert_eq!(options(vec![]).sets_text(), "none");
        let opts = options(vec![
            (key("svgf.alpha"), "0.05".into()),
            (key("svgf.iterations"), "4".into()),
        ]);
        let mut expected = base;
        expected.svgf.alpha = 0.05;
        expected.svgf.iterations = 4;
        assert_eq!(opts.with_sets(base).unwrap(), expected);
        assert_eq!(opts.sets_text(), "svgf.alpha=0.05, svgf.iterations=4");
        let bad = options(vec![(key("svgf.alpha"), "2".into())]);
        let e = bad.with_sets(base).unwrap_err().to_string();
        assert!(e.contains("--set svgf.alpha=2"), "{e}");
    }
}

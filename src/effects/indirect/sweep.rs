//! The indirect light's keys for `ssgi sweep --vary` (the gather's: they apply to the per-frame
//! filters' noisy gather too).

use crate::config::parse::{parse_count, parse_on_off, parse_vpls};
use crate::config::sweep_key::{value_names, SweepKey, Syntax};
use crate::config::{IndirectConfig, IndirectFilter};
use clap::ValueEnum;

pub const SWEEP_KEYS: &[SweepKey] = &[
    SweepKey {
        name: "indirect.vpls",
        syntax: Syntax::Text("integer 1..=16384|all"),
        description: "VPLs gathered per pixel and frame; all = every RSM texel (--vpls)",
        set: |c, v| {
            c.indirect.vpls = parse_vpls(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "indirect.interleave",
        syntax: Syntax::Text("integer 1..=8"),
        description: "interleaved gather: NxN blocks share the VPLs (--interleave)",
        set: |c, v| {
            c.indirect.interleave = parse_count(v, 1, IndirectConfig::MAX_INTERLEAVE)?;
            Ok(())
        },
    },
    SweepKey {
        name: "indirect.visibility",
        syntax: Syntax::Text("on|off"),
        description: "screen-space visibility test per VPL (--vpl-visibility)",
        set: |c, v| {
            c.indirect.visibility = parse_on_off(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "indirect.filter",
        syntax: Syntax::Names(value_names::<IndirectFilter>),
        description: "what makes indirect light smooth over time (--indirect-filter)",
        set: |c, v| {
            c.indirect.filter = IndirectFilter::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "indirect.half_res",
        syntax: Syntax::Text("on|off"),
        description: "indirect gather at half resolution (--half-res)",
        set: |c, v| {
            c.indirect.half_res = parse_on_off(v)?;
            Ok(())
        },
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::sweep_key::{assert_each_key_sets_its_field, SetByHand};

    #[test]
    fn each_key_changes_exactly_its_field() {
        let cases: Vec<(&str, &str, SetByHand)> = vec![
            ("indirect.vpls", "all", |c| c.indirect.vpls = 0),
            ("indirect.interleave", "2", |c| c.indirect.interleave = 2),
            ("indirect.visibility", "on", |c| {
                c.indirect.visibility = true
            }),
            ("indirect.filter", "svgf", |c| {
                c.indirect.filter = IndirectFilter::Svgf
            }),
            ("indirect.half_res", "off", |c| c.indirect.half_res = false),
        ];
        assert_each_key_sets_its_field(SWEEP_KEYS, cases);
    }
}

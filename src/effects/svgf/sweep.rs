//! SVGF's keys for `ssgi sweep --vary` (the registry hands them to the sweep).

use super::config::{parse_sigma, parse_weight, SvgfConfig, SvgfHistory};
use crate::config::parse::parse_count;
use crate::config::sweep_key::{value_names, SweepKey, Syntax};
use clap::ValueEnum;

pub const SWEEP_KEYS: &[SweepKey] = &[
    SweepKey {
        name: "svgf.iterations",
        syntax: Syntax::Text("integer 0..=10"),
        description: "SVGF's a-trous iterations (--svgf-iterations)",
        set: |c, v| {
            c.svgf.iterations = parse_count(v, 0, SvgfConfig::MAX_ITERATIONS)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.alpha",
        syntax: Syntax::Text("number in (0, 1]"),
        description: "SVGF's smallest weight of a new sample in the colour (--svgf-alpha)",
        set: |c, v| {
            c.svgf.alpha = parse_weight(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.alpha_moments",
        syntax: Syntax::Text("number in (0, 1]"),
        description: "the same for the luminance moments (--svgf-alpha-moments)",
        set: |c, v| {
            c.svgf.alpha_moments = parse_weight(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.alpha_still",
        syntax: Syntax::Text("number in (0, 1]"),
        description: "both smallest weights once the lighting holds still (--svgf-alpha-still)",
        set: |c, v| {
            c.svgf.alpha_still = parse_weight(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.history",
        syntax: Syntax::Names(value_names::<SvgfHistory>),
        description: "how SVGF reads last frame's values (--svgf-history)",
        set: |c, v| {
            c.svgf.history = SvgfHistory::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.sigma_luminance",
        syntax: Syntax::Text("number >= 0"),
        description: "SVGF's luminance edge-stopping (--svgf-sigma-luminance)",
        set: |c, v| {
            c.svgf.sigma_luminance = parse_sigma(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.sigma_normal",
        syntax: Syntax::Text("number >= 0"),
        description: "SVGF's normal edge-stopping exponent (--svgf-sigma-normal)",
        set: |c, v| {
            c.svgf.sigma_normal = parse_sigma(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "svgf.sigma_depth",
        syntax: Syntax::Text("number >= 0"),
        description: "SVGF's depth edge-stopping (--svgf-sigma-depth)",
        set: |c, v| {
            c.svgf.sigma_depth = parse_sigma(v)?;
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
            ("svgf.iterations", "2", |c| c.svgf.iterations = 2),
            ("svgf.alpha", "0.5", |c| c.svgf.alpha = 0.5),
            ("svgf.alpha_moments", "0.1", |c| c.svgf.alpha_moments = 0.1),
            ("svgf.alpha_still", "0.1", |c| c.svgf.alpha_still = 0.1),
            ("svgf.history", "bilinear", |c| {
                c.svgf.history = SvgfHistory::Bilinear
            }),
            ("svgf.sigma_luminance", "8", |c| {
                c.svgf.sigma_luminance = 8.0
            }),
            ("svgf.sigma_normal", "64", |c| c.svgf.sigma_normal = 64.0),
            ("svgf.sigma_depth", "2", |c| c.svgf.sigma_depth = 2.0),
        ];
        assert_each_key_sets_its_field(SWEEP_KEYS, cases);
    }
}

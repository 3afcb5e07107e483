//! SSAO's keys for `ssgi sweep --vary` (the registry hands them to the sweep).

use super::config::{AoConfig, AoEstimator};
use crate::config::parse::{parse_attenuation, parse_count, parse_on_off, parse_radius};
use crate::config::sweep_key::{value_names, SweepKey, Syntax};
use clap::ValueEnum;

pub const SWEEP_KEYS: &[SweepKey] = &[
    SweepKey {
        name: "ao.samples",
        syntax: Syntax::Text("integer 1..=4096"),
        description: "SSAO samples per pattern (--ao-samples)",
        set: |c, v| {
            c.ao.samples = parse_count(v, 1, 4096)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.estimator",
        syntax: Syntax::Names(value_names::<AoEstimator>),
        description: "SSAO estimator (--ao)",
        set: |c, v| {
            c.ao.estimator = AoEstimator::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.steps",
        syntax: Syntax::Text("integer 1..=256"),
        description: "GTAO steps per side of a slice (--ao-steps)",
        set: |c, v| {
            c.ao.steps = parse_count(v, 1, AoConfig::MAX_STEPS)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.moving_denoise",
        syntax: Syntax::Text("on|off"),
        description: "GTAO with the cache: denoise each pattern while the camera moves \
                      (--gtao-moving-denoise)",
        set: |c, v| {
            c.ao.moving_denoise = parse_on_off(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.radius",
        syntax: Syntax::Text("number in (0, 10]"),
        description: "SSAO sampling radius, fraction of the scene's bounding radius",
        set: |c, v| {
            c.ao.radius = parse_radius(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.attenuation",
        syntax: Syntax::Text("A:B, each finite and >= 0"),
        description: "eq 7's D(d) = 1 + A d + B d^2 (0:0: binary visibility within the radius; \
                      --ao-attenuation); the ground truth follows it",
        set: |c, v| {
            c.ao.attenuation = parse_attenuation(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.patterns",
        syntax: Syntax::Text("integer 1..=1024"),
        description: "SSAO patterns evaluated at once per frame",
        set: |c, v| {
            c.ao.patterns = parse_count(v, 1, 1024)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ao.position_mips",
        syntax: Syntax::Text("integer 0..=3"),
        description: "far SSAO taps read position levels up to this; 0 = off (--ao-position-mips)",
        set: |c, v| {
            c.ao.position_mips = parse_count(v, 0, AoConfig::MAX_POSITION_MIPS)?;
            Ok(())
        },
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::sweep_key::{assert_each_key_sets_its_field, SetByHand};
    use crate::effects::ao::config::AoEstimator;

    #[test]
    fn each_key_changes_exactly_its_field() {
        let cases: Vec<(&str, &str, SetByHand)> = vec![
            ("ao.samples", "16", |c| c.ao.samples = 16),
            ("ao.estimator", "crytek", |c| {
                c.ao.estimator = AoEstimator::Crytek
            }),
            ("ao.steps", "16", |c| c.ao.steps = 16),
            ("ao.moving_denoise", "off", |c| c.ao.moving_denoise = false),
            ("ao.radius", "0.5", |c| c.ao.radius = 0.5),
            ("ao.attenuation", "0:0", |c| c.ao.attenuation = [0.0, 0.0]),
            ("ao.patterns", "8", |c| c.ao.patterns = 8),
            ("ao.position_mips", "2", |c| c.ao.position_mips = 2),
        ];
        assert_each_key_sets_its_field(SWEEP_KEYS, cases);
    }
}
